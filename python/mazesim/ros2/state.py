"""The topics the bridge publishes after each step, and their messages, encoded.

As Webots' e-puck driver and the real robot's publish them (``webots_ros2_epuck``): a
``sensor_msgs/msg/Range`` per distance sensor (``/ps0`` .. ``/ps7``, ``/tof`` on the e-puck2,
frames named after the sensors) and per ground sensor (``/gs0`` .. ``/gs2``), ``/scan`` built from
them, ``/odom``, the wheels' ``/joint_states``, ``/tf``, ``/tf_static`` once and ``/clock``; and
the report's own topics as the ROS 1 bridge has them (``/sensors``, ``/sensor_data``,
``/pose``). The numbers are those of :mod:`mazesim.ros.standard` and :mod:`mazesim.ros.topics`,
so both bridges say the same. A robot
of a world of several robots publishes the same topics in its own namespace (``/west/ps0``,
``/west/tf``...), without ``/clock``, which the bridge publishes once for all; with a frame prefix
(``west/``) its frames are ``west/odom``, ``west/base_link``, ``west/ps0``... and its transforms
go on the one ``/tf`` and ``/tf_static``, as ros2_controllers' diff drive controller (the one
Webots' e-puck driver runs) names its frames after its namespace and publishes them on ``/tf``.
"""

from __future__ import annotations

import math
import zlib
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from mazesim._core import RobotProfile, Simulator
from mazesim._toml import load_toml
from mazesim.ros import standard, topics
from mazesim.ros2 import cdr
from mazesim.ros2.occupancy import MAP_FRAME
from mazesim.ros2.qos import CLOCK, SENSOR, TF, TF_STATIC, TopicQos

__all__ = [
    "CLOCK_TOPIC",
    "IMU_NOISE",
    "StateTopics",
    "TF_MESSAGE",
    "Topic",
    "ground_distance",
]

CLOCK_TOPIC = "/clock"
TF_TOPIC = "/tf"
TF_STATIC_TOPIC = "/tf_static"
RADIATION_INFRARED = 1
JOINT_STATES_TOPIC = "/joint_states"
#: The wheels' joints as Webots' e-puck driver names them: its ros2_control joints, which
#: joint_state_broadcaster publishes on ``joint_states`` (``webots_ros2_epuck/resource/
#: ros2_control.yml`` and ``epuck_webots.urdf`` in cyberbotics/webots_ros2).
WHEEL_JOINTS = ("left wheel motor", "right wheel motor")

RANGE = "sensor_msgs/msg/Range"
LASER_SCAN = "sensor_msgs/msg/LaserScan"
ODOMETRY = "nav_msgs/msg/Odometry"
TF_MESSAGE = "tf2_msgs/msg/TFMessage"
FLOAT64_ARRAY = "std_msgs/msg/Float64MultiArray"
JOINT_STATE = "sensor_msgs/msg/JointState"
IMU = "sensor_msgs/msg/Imu"
IMU_TOPIC = "/imu"
#: Standard gravity (m/s^2): what an accelerometer at rest reads up.
GRAVITY = 9.81
#: The relative standard deviation of ``/imu``'s angular velocity and linear acceleration: the
#: noise column of the E-puck PROTO's accelerometer (``lookupTable [-100 -100 0.003 100 100
#: 0.003]``) and gyro (``[-13.315805 -100000 0.003 13.315805 100000 0.003]``) tables in
#: cyberbotics/webots; Webots adds a Gaussian of that share of the value. Its orientation is
#: noise-free, as an InertialUnit without ``noise`` is.
IMU_NOISE = 0.003
CLOCK_TYPE = "rosgraph_msgs/msg/Clock"


class Topic(NamedTuple):
    """A topic the bridge publishes: name, message type, QoS."""

    name: str
    msgtype: str
    qos: TopicQos


def _sent_rank(topic: Topic) -> int:
    """Where a state topic's message goes out in a step (see :attr:`StateTopics.order`)."""
    if topic.msgtype == TF_MESSAGE:
        return 0
    if topic.msgtype in (ODOMETRY, JOINT_STATE, IMU) or topic.name.endswith(
        "/" + topics.POSE_TOPIC
    ):
        return 1
    return 3 if topic.msgtype == CLOCK_TYPE else 2


def _ground_tables(robot: RobotProfile) -> list[list[tuple[float, float]]]:
    """Each ground sensor's table rows ``(distance, reading)``, from the profile."""
    profile = load_toml(robot.to_toml(), f"the {robot.name} profile")
    models = profile.get("models", {})
    return [
        [(float(row[0]), float(row[1])) for row in models[sensor["model"]]["table"]]
        for sensor in profile.get("ground_sensors", [])
    ]


def ground_distance(table: Sequence[tuple[float, float]], reading: float) -> float:
    """The distance at which a ground sensor's table gives ``reading`` (interpolated, clamped)."""
    for (near, near_value), (far, far_value) in zip(table, table[1:]):
        low, high = sorted((near_value, far_value))
        if low <= reading <= high and near_value != far_value:
            return near + (reading - near_value) * (far - near) / (far_value - near_value)
    first, last = table[0], table[-1]
    # Beyond the table: the end whose reading is nearer.
    return first[0] if abs(reading - first[1]) <= abs(reading - last[1]) else last[0]


class StateTopics:
    """The state topics of one simulator, and their messages after each step.

    Args:
        simulator: The simulator whose state is published (or one robot of a simulator of
            several, :class:`mazesim.ros2.robots.RobotOf`).
        distro: ``humble`` or ``jazzy`` (Jazzy's Range carries a variance).
        namespace: The robot's namespace (``"/west"``), or ``""`` for none (a world of one robot,
            unless the bridge is given one).
        clock: Whether ``/clock`` is among the topics (not for a robot in a namespace).
        frame_prefix: What every frame name starts with (``"west/"``), ``""`` for none; with a
            prefix the transforms go on ``/tf`` and ``/tf_static``, outside the namespace.
        imu_seed: The seed of ``/imu``'s noise (:data:`IMU_NOISE`, a stream of its own named
            after the topic), or None for none (the simulator run without noise).
    """

    def __init__(
        self,
        simulator: Simulator,
        distro: str,
        namespace: str = "",
        clock: bool = True,
        frame_prefix: str = "",
        imu_seed: int | None = None,
    ) -> None:
        self.simulator = simulator
        self.namespace = namespace
        self._imu_seed = imu_seed
        self.imu_noise: np.random.Generator | None = None
        self._imu_draws: tuple[float, list[float]] = (-1.0, [])
        self._start_imu_noise()
        self.clock = clock
        self.frame_prefix = frame_prefix
        #: Where the transforms go: the robot's own ``tf``, or with a frame prefix the one ``/tf``.
        self.tf_namespace = "" if frame_prefix else namespace
        self.robot = robot = simulator.robot
        self.jazzy = distro != "humble"
        self.frames = standard.sensor_frames(robot)
        self.ground_names = [name.replace("-", "_") for name in robot.ground_sensor_names]
        self.ground_tables = _ground_tables(robot)
        self.ground_limits = [
            (min(row[0] for row in table), max(row[0] for row in table))
            for table in self.ground_tables
        ]
        self.has_scan = standard.has_scan(self.frames)
        self.sensor_labels = topics.sensor_names(simulator)
        self.sharp = topics.has_sharp_sensors(simulator)
        self.sensor_data_labels = [f"{name} cm" for name in robot.distance_sensor_names] + [
            "checkpoint"
        ]
        self.before = simulator.pose
        self.encoders_before = simulator.encoders
        #: The body's velocity over the last step in the world's frame (x, y), for ``/imu``.
        self.world_velocity = (0.0, 0.0)
        ns = namespace
        self.topics: list[Topic] = [
            *(Topic(f"{ns}/{frame.frame}", RANGE, SENSOR) for frame in self.frames),
            *(Topic(f"{ns}/{name}", RANGE, SENSOR) for name in self.ground_names),
        ]
        if self.has_scan:
            self.topics.append(Topic(f"{ns}/{standard.SCAN_TOPIC}", LASER_SCAN, SENSOR))
        self.topics += [
            Topic(f"{ns}/odom", ODOMETRY, SENSOR),
            Topic(ns + JOINT_STATES_TOPIC, JOINT_STATE, SENSOR),
            Topic(ns + IMU_TOPIC, IMU, SENSOR),
            Topic(self.tf_namespace + TF_TOPIC, TF_MESSAGE, TF),
            Topic(f"{ns}/{topics.SENSORS_TOPIC}", FLOAT64_ARRAY, SENSOR),
        ]
        if self.sharp:
            self.topics.append(Topic(f"{ns}/{topics.SENSOR_DATA_TOPIC}", FLOAT64_ARRAY, SENSOR))
        self.topics.append(Topic(f"{ns}/{topics.POSE_TOPIC}", FLOAT64_ARRAY, SENSOR))
        if clock:
            self.topics.append(Topic(CLOCK_TOPIC, CLOCK_TYPE, CLOCK))
        #: The order in which a step's messages go out (indices into :attr:`topics`): ``/tf``,
        #: then the robot's motion (``/odom``, ``/joint_states``, ``/imu``, ``/pose``), then what
        #: its sensors read, ``/clock`` last. A node that answers a sensor message with the
        #: latest odometry or transform (a Bug planner's ``/scan`` callback that skips until an
        #: ``/odom`` has come, tf2's lookup at the scan's stamp) has that step's already, the
        #: reset state's included.
        self.order = sorted(range(len(self.topics)), key=lambda at: _sent_rank(self.topics[at]))
        #: How many of :attr:`order` are the transforms and the motion (the rest: the sensors and
        #: ``/clock``); a lockstep bridge sends its first state in these two parts.
        self.motion_count = sum(_sent_rank(topic) < 2 for topic in self.topics)

    def _start_imu_noise(self) -> None:
        """Starts ``/imu``'s noise stream (None: noise-free) from its seed, no draws made."""
        #: ``/imu``'s draws and the simulated time of the step they are for.
        self._imu_draws = (-1.0, [])
        seed = self._imu_seed
        key = (zlib.crc32((self.namespace + IMU_TOPIC).encode("utf-8")),)
        self.imu_noise = (
            None
            if seed is None
            else np.random.default_rng(np.random.SeedSequence(seed, spawn_key=key))
        )

    def restart(self, from_the_start: bool) -> None:
        """Forgets the steps before a reset of the simulator (:mod:`mazesim.ros.resets`): the
        next messages' twist and rates are those of a robot at rest, and with
        ``from_the_start`` (``reset_simulation``) ``/imu``'s noise stream starts again, so
        the messages are those of a bridge just started."""
        self.before = self.simulator.pose
        self.encoders_before = self.simulator.encoders
        self.world_velocity = (0.0, 0.0)
        if from_the_start:
            self._start_imu_noise()

    def static_topic(self) -> Topic:
        """``/tf_static`` (in the robot's namespace unless its frames have a prefix)."""
        return Topic(self.tf_namespace + TF_STATIC_TOPIC, TF_MESSAGE, TF_STATIC)

    def frame(self, name: str) -> str:
        """The frame ``name`` (``base_link``) as this robot's messages give it."""
        return self.frame_prefix + name

    def static_transforms(self, stamp: cdr.Stamp) -> bytes:
        """The ``/tf_static`` message: ``base_link`` -> every sensor frame (and the scan's)."""
        base = self.frame(standard.BASE_FRAME)
        transforms: list[cdr.Transform] = [
            (
                stamp,
                base,
                self.frame(frame.frame),
                (frame.x, frame.y, 0.0),
                standard.yaw_quaternion(frame.yaw),
            )
            for frame in self.frames
        ]
        positions = self.robot.ground_sensor_positions().tolist()
        for name, (x, y) in zip(self.ground_names, positions):
            # Looking down: pitched by +90 degrees about y.
            down = (0.0, math.sqrt(0.5), 0.0, math.sqrt(0.5))
            transforms.append((stamp, base, self.frame(name), (x, y, 0.0), down))
        if self.has_scan:
            transforms.append(
                (
                    stamp,
                    base,
                    self.frame(standard.SCAN_FRAME),
                    (0.0, 0.0, standard.SCAN_HEIGHT),
                    (0.0, 0.0, 0.0, 1.0),
                )
            )
        # The odometry is the simulator's pose in the world's frame, that of /map.
        identity = (0.0, 0.0, 0.0, 1.0)
        odom = self.frame(standard.ODOM_FRAME)
        transforms.append((stamp, MAP_FRAME, odom, (0.0, 0.0, 0.0), identity))
        return cdr.encode_tf_message(transforms)

    def _imu(
        self,
        stamp: cdr.Stamp,
        after: tuple[float, float, float],
        turn: float,
        step_seconds: float,
    ) -> bytes:
        """The ``/imu`` message: the inertial unit's orientation (the yaw), the gyro's turn rate
        over the last step, and the accelerometer's specific force: the body's acceleration
        over the last two steps, in its frame, plus gravity up; with noise, each of the six
        vector components of the gyro and the accelerometer is off by :data:`IMU_NOISE` of
        itself (a standard normal draw each, in that order), as Webots' tables say."""
        x, y, yaw = after
        if step_seconds > 0.0:
            velocity = ((x - self.before[0]) / step_seconds, (y - self.before[1]) / step_seconds)
            ax = (velocity[0] - self.world_velocity[0]) / step_seconds
            ay = (velocity[1] - self.world_velocity[1]) / step_seconds
            self.world_velocity = velocity
        else:
            ax = ay = 0.0
        c, s = math.cos(yaw), math.sin(yaw)
        rates = (0.0, 0.0, turn)
        force = (c * ax + s * ay, -s * ax + c * ay, GRAVITY)
        if self.imu_noise is not None:
            # One set of draws a step: a state published again (the reset state sent again
            # before the first command) carries the same readings.
            if self._imu_draws[0] != self.simulator.time:
                self._imu_draws = (self.simulator.time, self.imu_noise.standard_normal(6).tolist())
            draws = self._imu_draws[1]
            wx, wy, wz = (v + abs(v) * IMU_NOISE * n for v, n in zip(rates, draws[:3]))
            fx, fy, fz = (v + abs(v) * IMU_NOISE * n for v, n in zip(force, draws[3:]))
            rates, force = (wx, wy, wz), (fx, fy, fz)
        return cdr.encode_imu(
            stamp, self.frame(standard.BASE_FRAME), standard.yaw_quaternion(yaw), rates, force
        )

    def messages(self, stamp: cdr.Stamp, step_seconds: float) -> list[bytes]:
        """The encoded message of each of :attr:`topics`, in order, for the current state.

        Args:
            stamp: The simulation time the messages carry.
            step_seconds: The time since the previous state (the odometry twist's interval).
        """
        simulator = self.simulator
        variance = 0.0 if self.jazzy else None
        distances = standard.ranges(simulator, self.robot, self.frames)
        out = [
            cdr.encode_range(
                stamp,
                self.frame(frame.frame),
                RADIATION_INFRARED,
                standard.FIELD_OF_VIEW,
                frame.min_range,
                frame.max_range,
                distance,
                variance,
            )
            for frame, distance in zip(self.frames, distances)
        ]
        for name, table, (near, far), reading in zip(
            self.ground_names,
            self.ground_tables,
            self.ground_limits,
            simulator.ground_sensors().tolist(),
        ):
            distance = ground_distance(table, reading)
            out.append(
                cdr.encode_range(
                    stamp,
                    self.frame(name),
                    RADIATION_INFRARED,
                    standard.FIELD_OF_VIEW,
                    near,
                    far,
                    distance,
                    variance,
                )  # fmt: skip
            )
        if self.has_scan:
            by_name = {frame.frame: distance for frame, distance in zip(self.frames, distances)}
            out.append(
                cdr.encode_laser_scan(
                    stamp,
                    self.frame(standard.SCAN_FRAME),
                    standard.scan_angles(),
                    (0.0, step_seconds),
                    (standard.SCAN_RANGE_MIN, standard.SCAN_RANGE_MAX),
                    standard.scan_ranges(by_name),
                )
            )
        x, y, yaw = after = simulator.pose
        velocity = standard.body_velocity(self.before, after, step_seconds)
        imu = self._imu(stamp, after, velocity.turn, step_seconds)
        self.before = after
        rotation = standard.yaw_quaternion(yaw)
        odom, base = self.frame(standard.ODOM_FRAME), self.frame(standard.BASE_FRAME)
        out.append(
            cdr.encode_odometry(
                stamp,
                odom,
                base,
                (x, y, 0.0, *rotation),
                (velocity.forward, velocity.leftward, 0.0, 0.0, 0.0, velocity.turn),
            )
        )
        encoders = simulator.encoders
        turns = [
            (now - then) / step_seconds if step_seconds > 0.0 else 0.0
            for now, then in zip(encoders, self.encoders_before)
        ]
        self.encoders_before = encoders
        out.append(cdr.encode_joint_state(stamp, WHEEL_JOINTS, encoders, turns))
        out.append(imu)
        out.append(cdr.encode_tf_message([(stamp, odom, base, (x, y, 0.0), rotation)]))
        out.append(
            cdr.encode_float64_multi_array(self.sensor_labels, topics.sensors_values(simulator))
        )
        if self.sharp:
            out.append(
                cdr.encode_float64_multi_array(
                    self.sensor_data_labels, topics.sensor_data_values(simulator)
                )
            )
        out.append(
            cdr.encode_float64_multi_array(("x", "y", "yaw", "time"), topics.pose_values(simulator))
        )
        if self.clock:
            out.append(cdr.encode_clock(stamp))
        return out
