"""The standard ROS messages of the bridge, as plain Python (this module does not need ROS).

Beside the report's ``std_msgs/Float64MultiArray`` topics (:mod:`mazesim.ros.topics`), the bridge
speaks the messages that rviz and the usual ROS tools understand, as Cyberbotics' e-puck driver
for Webots does:

- one ``sensor_msgs/Range`` topic per distance sensor, named after the sensor's frame (``ps0`` ..
  ``ps7`` on the e-puck; ``front``, ``back``, ``left``, ``right``, ``left_front``, ``right_front``
  on the ``seed`` robot): radiation type ``INFRARED``, the frame of the sensor, ``min_range`` and
  ``max_range`` from the sensor's table in the robot profile, and the distance at which the sensor
  reads its current value off a white wall; a reading at or beyond the far end of the table is
  ``+inf`` (nothing in range, as REP 117 asks);
- ``odom`` (``nav_msgs/Odometry``): the simulator's pose in frame ``odom`` (the world's frame) and
  the body's velocity over the last control step in frame ``base_link``;
- ``/tf`` (``tf2_msgs/TFMessage``): the same pose as the transform ``odom`` -> ``base_link``;
- ``/tf_static`` (``tf2_msgs/TFMessage``, latched, sent once): ``base_link`` -> each sensor frame,
  from the sensor poses of the robot profile;
- ``cmd_vel`` (``geometry_msgs/Twist``, subscribed): ``linear.x`` in m/s and ``angular.z`` in
  rad/s, turned into wheel speeds with the profile's wheel radius and axle length; when a wheel
  would exceed the motor limit both are scaled down by the same factor, so the robot keeps the
  commanded arc, slower.

All stamps are simulated time. Every number comes from the simulator and its robot profile; the
functions here turn them into the messages' fields.
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

from mazesim._core import RobotProfile, Simulator
from mazesim.errors import InvalidActionError

__all__ = [
    "BASE_FRAME",
    "CMD_VEL_TOPIC",
    "FIELD_OF_VIEW",
    "ODOM_FRAME",
    "ODOM_TOPIC",
    "TF_STATIC_TOPIC",
    "TF_TOPIC",
    "BodyVelocity",
    "SensorFrame",
    "StandardPublishers",
    "body_velocity",
    "ranges",
    "sensor_frames",
    "twist_wheel_speeds",
    "yaw_quaternion",
]

ODOM_TOPIC = "odom"
CMD_VEL_TOPIC = "cmd_vel"
TF_TOPIC = "/tf"
TF_STATIC_TOPIC = "/tf_static"
#: The fixed frame: the world's frame, in which the robot starts at the world's start pose.
ODOM_FRAME = "odom"
#: The robot's frame: x forward, y left, at the centre between the wheels.
BASE_FRAME = "base_link"
#: Opening of the cone rviz draws for a Range message, in radians. mazesim casts one ray per
#: sensor, so this is for display only.
FIELD_OF_VIEW = 0.1
#: Relative tolerance under which a distance counts as the far end of the sensor's table.
FAR_END_TOLERANCE = 1e-6


class SensorFrame(NamedTuple):
    """A distance sensor's frame, its pose on the robot and its table's distances."""

    #: The frame id, also the name of the sensor's Range topic (the sensor's name, ``-`` -> ``_``).
    frame: str
    #: Position in ``base_link``, metres.
    x: float
    y: float
    #: Heading in ``base_link``, radians counter-clockwise from forward.
    yaw: float
    #: Nearest and farthest distance of the sensor's table, metres.
    min_range: float
    max_range: float


class BodyVelocity(NamedTuple):
    """The body's velocity in ``base_link``: m/s forward and leftward, rad/s counter-clockwise."""

    forward: float
    leftward: float
    turn: float


def sensor_frames(robot: RobotProfile) -> list[SensorFrame]:
    """The frame of each distance sensor of ``robot``, in the profile's order."""
    poses = robot.distance_sensor_poses().tolist()
    limits = robot.distance_sensor_limits().tolist()
    return [
        SensorFrame(name.replace("-", "_"), x, y, yaw, near, far)
        for name, (x, y, yaw), (near, far) in zip(robot.distance_sensor_names, poses, limits)
    ]


def ranges(
    simulator: Simulator,
    robot: RobotProfile | None = None,
    frames: list[SensorFrame] | None = None,
) -> list[float]:
    """The distance each sensor reports on its Range topic, in metres (``inf``: nothing in range).

    A reading is turned into the distance at which the sensor reads it off a white wall (its
    table inverted), as a controller that knows only the reading would. A caller that publishes
    every step passes the simulator's ``robot`` and its :func:`sensor_frames`, read once.
    """
    robot = simulator.robot if robot is None else robot
    frames = sensor_frames(robot) if frames is None else frames
    distances = []
    for index, (reading, frame) in enumerate(zip(simulator.distance_sensors().tolist(), frames)):
        distance = robot.distance_from_reading(index, reading)
        # Within float32 rounding of the far end (readings are float32): nothing in range.
        nothing = distance >= frame.max_range * (1.0 - FAR_END_TOLERANCE)
        distances.append(math.inf if nothing else distance)
    return distances


def yaw_quaternion(yaw: float) -> tuple[float, float, float, float]:
    """The quaternion ``(x, y, z, w)`` of a rotation by ``yaw`` radians about z."""
    return (0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0))


def body_velocity(
    before: tuple[float, float, float], after: tuple[float, float, float], seconds: float
) -> BodyVelocity:
    """The body's mean velocity between two poses ``(x, y, yaw)`` taken ``seconds`` apart.

    It is what the body did, contacts included, not what the wheels were told: pushed along a
    wall, the robot moves sideways (``leftward``) and slower than its wheels turn. The translation
    is expressed in the body's frame at the middle of the turn.
    """
    if seconds <= 0.0:
        return BodyVelocity(0.0, 0.0, 0.0)
    turn = math.remainder(after[2] - before[2], math.tau)
    middle = before[2] + turn / 2.0
    dx, dy = after[0] - before[0], after[1] - before[1]
    cos, sin = math.cos(middle), math.sin(middle)
    return BodyVelocity(
        (cos * dx + sin * dy) / seconds, (-sin * dx + cos * dy) / seconds, turn / seconds
    )


def twist_wheel_speeds(linear: float, angular: float, robot: RobotProfile) -> tuple[float, float]:
    """The (left, right) wheel speeds in rad/s that drive ``robot`` at a ``cmd_vel`` twist.

    Args:
        linear: Forward speed in m/s (``linear.x``).
        angular: Turn rate in rad/s, counter-clockwise (``angular.z``).
        robot: The profile with the wheel radius, axle length and motor limit.

    Returns:
        The wheel speeds; if one would exceed the motor limit, both are scaled down by the same
        factor, which keeps the ratio of the two and so the arc the robot drives.

    Raises:
        InvalidActionError: A speed is not a finite number.
    """
    for field, value in (("linear.x", linear), ("angular.z", angular)):
        if not math.isfinite(value):
            raise InvalidActionError(f"expected a finite {field} on {CMD_VEL_TOPIC}; found {value}")
    half_axle = robot.axle_length / 2.0
    left = (linear - angular * half_axle) / robot.wheel_radius
    right = (linear + angular * half_axle) / robot.wheel_radius
    fastest = max(abs(left), abs(right))
    if fastest > robot.max_wheel_speed:
        scale = robot.max_wheel_speed / fastest
        left, right = left * scale, right * scale
    return left, right


class StandardPublishers:
    """Publishes the standard messages of one simulator; the bridge calls it after each step.

    Args:
        ros: The namespace of :func:`mazesim.ros._ros.require_ros`.
        simulator: The simulator whose state is published.
        make_publisher: Creates a publisher from a topic and a message class, as the bridge's
            other topics are created (synchronous in lockstep, latched).
    """

    def __init__(self, ros: Any, simulator: Simulator, make_publisher: Any) -> None:
        self.ros = ros
        self.simulator = simulator
        self.frames = sensor_frames(simulator.robot)
        self.previous: tuple[float, float, float] | None = None
        self.previous_time = 0.0
        self.odom_publisher = make_publisher(ODOM_TOPIC, ros.Odometry)
        self.tf_publisher = make_publisher(TF_TOPIC, ros.TFMessage)
        self.range_publishers = [make_publisher(f.frame, ros.Range) for f in self.frames]
        # Latched and sent once: the sensors do not move on the robot.
        self.tf_static_publisher = ros.rospy.Publisher(
            TF_STATIC_TOPIC, ros.TFMessage, queue_size=1, latch=True
        )
        self.tf_static_publisher.publish(ros.TFMessage(transforms=self._sensor_transforms()))

    def _transform(
        self, stamp: Any, parent: str, child: str, x: float, y: float, yaw: float
    ) -> Any:
        message = self.ros.TransformStamped()
        message.header.stamp = stamp
        message.header.frame_id = parent
        message.child_frame_id = child
        message.transform.translation.x = x
        message.transform.translation.y = y
        rotation = message.transform.rotation
        rotation.x, rotation.y, rotation.z, rotation.w = yaw_quaternion(yaw)
        return message

    def _sensor_transforms(self) -> list[Any]:
        stamp = self.ros.rospy.Time(0)
        return [self._transform(stamp, BASE_FRAME, f.frame, f.x, f.y, f.yaw) for f in self.frames]

    def publish(self, stamp: Any) -> None:
        """Publishes ``odom``, ``/tf`` and every Range topic for the current step at ``stamp``."""
        ros, simulator = self.ros, self.simulator
        pose = simulator.pose
        velocity = BodyVelocity(0.0, 0.0, 0.0)
        if self.previous is not None:
            velocity = body_velocity(self.previous, pose, simulator.time - self.previous_time)
        self.previous, self.previous_time = pose, simulator.time
        x, y, yaw = pose
        odom = ros.Odometry()
        odom.header.stamp = stamp
        odom.header.frame_id = ODOM_FRAME
        odom.child_frame_id = BASE_FRAME
        odom.pose.pose.position.x = x
        odom.pose.pose.position.y = y
        orientation = odom.pose.pose.orientation
        orientation.x, orientation.y, orientation.z, orientation.w = yaw_quaternion(yaw)
        odom.twist.twist.linear.x = velocity.forward
        odom.twist.twist.linear.y = velocity.leftward
        odom.twist.twist.angular.z = velocity.turn
        self.odom_publisher.publish(odom)
        transform = self._transform(stamp, ODOM_FRAME, BASE_FRAME, x, y, yaw)
        self.tf_publisher.publish(ros.TFMessage(transforms=[transform]))
        for frame, distance, range_publisher in zip(
            self.frames, ranges(simulator), self.range_publishers
        ):
            message = ros.Range(
                radiation_type=ros.Range.INFRARED,
                field_of_view=FIELD_OF_VIEW,
                min_range=frame.min_range,
                max_range=frame.max_range,
                range=distance,
            )
            message.header.stamp = stamp
            message.header.frame_id = frame.frame
            range_publisher.publish(message)
