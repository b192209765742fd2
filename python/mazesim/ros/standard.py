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
- ``scan`` (``sensor_msgs/LaserScan``, robots with the e-puck's ``ps0`` .. ``ps7``): the
  distance sensors as one scan in frame ``laser_scanner``, as Webots' e-puck driver builds it
  (:func:`scan_ranges`);
- ``/tf_static`` (``tf2_msgs/TFMessage``, latched, sent once): ``base_link`` -> each sensor frame,
  from the sensor poses of the robot profile, and ``laser_scanner`` where there is a scan; and
  ``map`` -> ``odom``, the identity;
- ``map`` (``nav_msgs/OccupancyGrid``, latched, sent once): the world's walls as ``map_server``
  publishes a map (:mod:`mazesim.ros.occupancy`), in frame ``map``;
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

from mazesim._checks import answers_non_finite
from mazesim._core import RobotProfile, Simulator
from mazesim.errors import InvalidActionError
from mazesim.ros.occupancy import MAP_FRAME, MAP_RESOLUTION, MAP_TOPIC, occupied_cells

__all__ = [
    "BASE_FRAME",
    "CMD_VEL_TOPIC",
    "FIELD_OF_VIEW",
    "ODOM_FRAME",
    "ODOM_TOPIC",
    "SCAN_FRAME",
    "SCAN_TOPIC",
    "TF_STATIC_TOPIC",
    "TF_TOPIC",
    "BodyVelocity",
    "SensorFrame",
    "StandardPublishers",
    "body_velocity",
    "has_scan",
    "latched_map",
    "ranges",
    "scan_angles",
    "scan_ranges",
    "sensor_frames",
    "state_to_send_again",
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
#: The e-puck's distance sensors as one LaserScan, in both bridges.
SCAN_TOPIC = "scan"
#: The LaserScan's frame, 0.033 m above ``base_link`` as in Webots' e-puck driver.
SCAN_FRAME = "laser_scanner"
SCAN_HEIGHT = 0.033
#: Webots' e-puck driver: rays every 15 degrees from -150 to +150; each sensor's range is
#: measured from the body's centre by adding its radius, 0.035 m; readings beyond 0.04 m (of
#: the infra-red sensors) are out of range; range_min 0.035 + 0.009, range_max 0.035 + 1.0.
SCAN_STEP_DEGREES = 15
SCAN_HALF_DEGREES = 150
SCAN_BODY_OFFSET = 0.035
SCAN_INFRARED_MAX = 0.04
SCAN_RANGE_MIN = SCAN_BODY_OFFSET + 0.009
SCAN_RANGE_MAX = SCAN_BODY_OFFSET + 1.0
#: Each e-puck sensor's ray in the scan, in degrees.
SCAN_ANGLES = {
    "ps0": -15, "ps1": -45, "ps2": -90, "ps3": -150, "ps4": 150, "ps5": 90, "ps6": 45, "ps7": 15,
    "tof": 0,
}  # fmt: skip


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


@answers_non_finite  # refused as an action (InvalidActionError), as every bad command is
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
    if not (math.isfinite(left) and math.isfinite(right)):
        # A huge finite twist (1e307 m/s) overflows: the same arc from the twist scaled down
        # (the limit scaled an infinite speed by 0 into NaN, and the step was lost).
        size = max(abs(linear), abs(angular * half_axle))
        left = (linear / size - angular * half_axle / size) / robot.wheel_radius
        right = (linear / size + angular * half_axle / size) / robot.wheel_radius
        fastest = max(abs(left), abs(right))
        return (
            left / fastest * robot.max_wheel_speed,
            right / fastest * robot.max_wheel_speed,
        )
    fastest = max(abs(left), abs(right))
    if fastest > robot.max_wheel_speed:
        scale = robot.max_wheel_speed / fastest
        left, right = left * scale, right * scale
    return left, right


def has_scan(frames: list[SensorFrame]) -> bool:
    """Whether a robot with these sensor frames has the e-puck's scan (``ps0`` .. ``ps7``)."""
    return {f"ps{index}" for index in range(8)} <= {frame.frame for frame in frames}


def scan_angles() -> tuple[float, float, float]:
    """The scan's ``angle_min``, ``angle_max`` and ``angle_increment``, in radians."""
    half = math.radians(SCAN_HALF_DEGREES)
    return -half, half, math.radians(SCAN_STEP_DEGREES)


def scan_ranges(distances: dict[str, float]) -> list[float]:
    """The ranges of the LaserScan of the e-puck's sensors, from each sensor's distance by name
    (:func:`ranges`; ``inf``: nothing in range): a sensor's ray is its distance plus the body's
    radius, or the body's radius alone (below ``range_min``, so dropped) when it reads nothing
    within 0.04 m; the rays of no sensor are 0."""
    count = 2 * SCAN_HALF_DEGREES // SCAN_STEP_DEGREES + 1
    ranges = [0.0] * count
    for name, degrees in SCAN_ANGLES.items():
        if name not in distances:
            continue
        distance = distances[name]
        if name != "tof" and not distance <= SCAN_INFRARED_MAX:
            distance = 0.0
        elif not math.isfinite(distance):
            distance = 0.0
        ranges[(degrees + SCAN_HALF_DEGREES) // SCAN_STEP_DEGREES] = distance + SCAN_BODY_OFFSET
    return ranges


def latched_map(ros: Any, world: Any) -> Any:
    """Publishes ``world``'s walls as a ``nav_msgs/OccupancyGrid`` in frame ``map``, latched and
    sent once as map_server publishes a map (relative: in the bridge's namespace, as the other
    topics); returns the publisher."""
    cells, x0, y0 = occupied_cells(world)
    grid = ros.OccupancyGrid()
    grid.header.stamp = ros.rospy.Time(0)
    grid.header.frame_id = MAP_FRAME
    grid.info.resolution = MAP_RESOLUTION
    grid.info.height, grid.info.width = cells.shape
    grid.info.origin.position.x, grid.info.origin.position.y = x0, y0
    grid.info.origin.orientation.w = 1.0
    grid.data = cells.ravel().tolist()
    made = ros.rospy.Publisher(MAP_TOPIC.lstrip("/"), ros.OccupancyGrid, queue_size=1, latch=True)
    made.publish(grid)
    return made


class StandardPublishers:
    """Publishes the standard messages of one simulator; the bridge calls it after each step.

    Args:
        ros: The namespace of :func:`mazesim.ros._ros.require_ros`.
        simulator: The simulator whose state is published (or one robot of a simulator of
            several, :class:`mazesim.ros.robots.RobotOf`).
        make_publisher: Creates a publisher from a topic and a message class, as the bridge's
            other topics are created (synchronous in lockstep, latched).
        namespace: The robot's namespace (``"/west"``): its ``odom``, Range topics and ``scan``
            are ``/west/odom``...; ``""`` (a world of one robot): relative to the node's.
        frame_prefix: What every frame name starts with (``"west/"``,
            :func:`mazesim.ros.robots.frame_prefix`), ``""`` for none.
        transforms: Whether it sends ``/tf``, ``/tf_static`` and ``map`` itself. A robot of
            several leaves them to its bridge, which sends every robot's transforms in one
            message (a latched topic keeps one message): :meth:`publish` returns the robot's
            ``/tf`` transforms, :meth:`static_transforms` its ``/tf_static`` ones.
    """

    def __init__(
        self,
        ros: Any,
        simulator: Simulator,
        make_publisher: Any,
        namespace: str = "",
        frame_prefix: str = "",
        transforms: bool = True,
    ) -> None:
        self.ros = ros
        self.simulator = simulator
        self.namespace = namespace
        self.prefix = frame_prefix
        self.frames = sensor_frames(simulator.robot)
        self.previous: tuple[float, float, float] | None = None
        self.previous_time = 0.0
        self.odom_publisher = make_publisher(self._topic(ODOM_TOPIC), ros.Odometry)
        self.tf_publisher = make_publisher(TF_TOPIC, ros.TFMessage) if transforms else None
        self.range_publishers = [
            make_publisher(self._topic(f.frame), ros.Range) for f in self.frames
        ]
        self.scan_publisher = None
        if has_scan(self.frames):
            self.scan_publisher = make_publisher(self._topic(SCAN_TOPIC), ros.LaserScan)
        if not transforms:
            return
        # Latched and sent once: the sensors do not move on the robot.
        self.tf_static_publisher = ros.rospy.Publisher(
            TF_STATIC_TOPIC, ros.TFMessage, queue_size=1, latch=True
        )
        self.tf_static_publisher.publish(ros.TFMessage(transforms=self.static_transforms()))
        self.map_publisher = latched_map(ros, simulator.world)

    def _topic(self, name: str) -> str:
        """Topic ``name`` in the robot's namespace (relative without one)."""
        return f"{self.namespace}/{name}" if self.namespace else name

    def frame(self, name: str) -> str:
        """The frame ``name`` (``base_link``) as this robot's messages give it."""
        return self.prefix + name

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

    def static_transforms(self) -> list[Any]:
        """The ``/tf_static`` transforms: ``base_link`` -> each sensor frame (and the scan's),
        and ``map`` -> ``odom``, the identity."""
        stamp = self.ros.rospy.Time(0)
        base = self.frame(BASE_FRAME)
        transforms = [
            self._transform(stamp, base, self.frame(f.frame), f.x, f.y, f.yaw) for f in self.frames
        ]
        if self.scan_publisher is not None:
            scan = self._transform(stamp, base, self.frame(SCAN_FRAME), 0.0, 0.0, 0.0)
            scan.transform.translation.z = SCAN_HEIGHT
            transforms.append(scan)
        transforms.append(self._transform(stamp, MAP_FRAME, self.frame(ODOM_FRAME), 0.0, 0.0, 0.0))
        return transforms

    def publish(self, stamp: Any) -> list[Any]:
        """Publishes ``odom``, ``/tf``, every Range topic and ``scan`` for the current step at
        ``stamp``; returns the ``/tf`` transforms (sent by the bridge when it sends them)."""
        ros, simulator = self.ros, self.simulator
        pose = simulator.pose
        velocity = BodyVelocity(0.0, 0.0, 0.0)
        step_seconds = simulator.time - self.previous_time
        if self.previous is not None:
            velocity = body_velocity(self.previous, pose, step_seconds)
        self.previous, self.previous_time = pose, simulator.time
        x, y, yaw = pose
        odom = ros.Odometry()
        odom.header.stamp = stamp
        odom.header.frame_id = self.frame(ODOM_FRAME)
        odom.child_frame_id = self.frame(BASE_FRAME)
        odom.pose.pose.position.x = x
        odom.pose.pose.position.y = y
        orientation = odom.pose.pose.orientation
        orientation.x, orientation.y, orientation.z, orientation.w = yaw_quaternion(yaw)
        odom.twist.twist.linear.x = velocity.forward
        odom.twist.twist.linear.y = velocity.leftward
        odom.twist.twist.angular.z = velocity.turn
        self.odom_publisher.publish(odom)
        transform = self._transform(
            stamp, self.frame(ODOM_FRAME), self.frame(BASE_FRAME), x, y, yaw
        )
        if self.tf_publisher is not None:
            self.tf_publisher.publish(ros.TFMessage(transforms=[transform]))
        distances = ranges(simulator)
        for frame, distance, range_publisher in zip(self.frames, distances, self.range_publishers):
            message = ros.Range(
                radiation_type=ros.Range.INFRARED,
                field_of_view=FIELD_OF_VIEW,
                min_range=frame.min_range,
                max_range=frame.max_range,
                range=distance,
            )
            message.header.stamp = stamp
            message.header.frame_id = self.frame(frame.frame)
            range_publisher.publish(message)
        if self.scan_publisher is not None:
            by_name = {frame.frame: distance for frame, distance in zip(self.frames, distances)}
            angle_min, angle_max, increment = scan_angles()
            scan = ros.LaserScan(
                angle_min=angle_min,
                angle_max=angle_max,
                angle_increment=increment,
                scan_time=step_seconds,
                range_min=SCAN_RANGE_MIN,
                range_max=SCAN_RANGE_MAX,
                ranges=scan_ranges(by_name),
            )
            scan.header.stamp = stamp
            scan.header.frame_id = self.frame(SCAN_FRAME)
            self.scan_publisher.publish(scan)
        return [transform]


def state_to_send_again(last_state: list[tuple[Any, Any]]) -> list[tuple[Any, Any]]:
    """The messages of a state (publisher, message, as they went out) that a ROS 1 bridge sends
    again when it went unanswered: all but ``/tf``, which went out at the state's stamp already.
    tf2 keeps transforms by stamp and warns of the same one again (``TF_REPEATED_DATA``); a
    subscription that connected since gets it on connecting. The rule of both ROS 1 bridges,
    one robot or several."""
    return [(made, message) for made, message in last_state if made.resolved_name != TF_TOPIC]
