"""The ROS 2 bridge node: a simulator behind the e-puck's standard ROS 2 topics.

Lockstep (the default): each command on ``/cmd_vel`` (read as Twist and as TwistStamped, whatever
the distribution), ``/motor`` or ``/action`` advances one
control step, then the state topics go out stamped with the new simulation time: ``/tf``, the
motion, the sensors, ``/clock`` last (:attr:`~mazesim.ros2.state.StateTopics.order`).
Before the first command the bridge publishes the reset state once (stamped 1 ns; its sensors and
``/clock`` ``MOTION_LEAD_S`` after its motion), after a writer
on one of its command topics or a reader of a state topic has matched and a grace period has
passed, and again every
``RESEND_S`` seconds while a command writer is matched and no command has come (a node that
answers only its second message, or whose first command went out before it matched, gets
another), saying so on stderr; when that goes unanswered too, ``/clock`` runs on its own until
the first command, the simulator standing still, for a node that waits for simulated time first.
Once the reset state has gone out, a command writer or state reader that matches later (a node
started or restarted while the bridge runs, a ``wait_for_message`` reader made before the first
command), or a goal on ``/goal_pose`` (a navigator that drives once it has one), with no
command within the grace period gets its robot's last state again (byte for byte once
stepping), and so does every robot the world waits for when no command has come for
``RESEND_S`` seconds (a node that let a state go unanswered). Free-running: the bridge
steps on its own at ``speed`` (see :mod:`mazesim.ros2.clock`), with the last commanded wheel
speeds. Topics and QoS: :mod:`mazesim.ros2.state`; the page ``docs/ros2.md``.

The services ``/reset_simulation`` and ``/reset_world`` (``std_srvs/srv/Empty``, as Gazebo's
``gazebo_ros_init`` offers them; :mod:`mazesim.ros.resets` and :mod:`mazesim.ros2.services`)
put the simulation back; the state after the reset goes out before the call is answered. The
node's parameter services answer ``ros2 param`` (:mod:`mazesim.ros2.parameters`).

A world of several robots publishes each robot's topics in its own namespace and reads each
robot's commands there (:mod:`mazesim.ros2.robots`), with one ``/clock``. In lockstep the world
steps once every robot whose command topics have a writer has sent its command for the step; a
robot nobody drives keeps its last wheel speeds (at first, none).
"""

from __future__ import annotations

import dataclasses
import functools
import math
import re
import signal
import sys
import threading
import time
from collections import deque
from collections.abc import Callable
from typing import Any

from mazesim._core import Simulator
from mazesim.actions import wheel_speeds
from mazesim.errors import InvalidActionError, InvalidArgumentError, _known_name, _shown
from mazesim.ros import standard, topics
from mazesim.ros.lockstep import (
    IDLE_CLOCK_AFTER_S,
    IDLE_EXIT_STATUS,
    IDLE_TIMEOUT_S,
    RESEND_S,
    CommandDeadline,
    IdleTimeout,
    TimerHold,
    UnansweredState,
)
from mazesim.ros.resets import RESET_SIMULATION, RESETS, EpisodeResets, service_name
from mazesim.ros2 import cdr, network
from mazesim.ros2.bag import BagRecorder
from mazesim.ros2.clock import SIM_CONTROL_TOPIC, FreeRunning, stamp_nanoseconds
from mazesim.ros2.node import MOST_NAME_CHARACTERS, Node, Reader
from mazesim.ros2.nodes import leaves_signals_as_found
from mazesim.ros2.occupancy import map_topics, occupancy_grid
from mazesim.ros2.parameters import ParameterServers, bridge_parameters
from mazesim.ros2.qos import CLOCK, COMMAND, TF_STATIC, IncompatibleQos, TopicQos
from mazesim.ros2.robots import RobotOf, frame_prefix, robot_namespaces, step_rounds
from mazesim.ros2.ros_args import RosArguments
from mazesim.ros2.state import CLOCK_TOPIC, CLOCK_TYPE, StateTopics
from mazesim.ros2.unpublished import UnpublishedTopics

__all__ = ["IDLE_CLOCK_AFTER_S", "RESEND_S", "BridgeSettings", "Ros2Bridge", "run_bridge"]

NODE_NAME = "mazesim_bridge"
#: Seconds between a command writer matching and the reset state going out.
READY_GRACE_S = 0.5
#: Seconds between two looks at the readers other nodes created (see :mod:`.unpublished`).
READERS_CHECK_S = 1.0
#: The longest ``--namespace``: room left under ROS 2's bound on a name for the longest topic
#: the bridge makes under it (``/camera/image_raw/compressed``, ``/odom``...).
MOST_NAMESPACE_CHARACTERS = MOST_NAME_CHARACTERS - 64

_ROS_NAMESPACE = re.compile(r"/?[A-Za-z_][A-Za-z0-9_]*(/[A-Za-z_][A-Za-z0-9_]*)*")
#: Lockstep: seconds between the first state's transforms and motion and its sensor messages.
MOTION_LEAD_S = 0.25
#: Lockstep: seconds between two looks for command writers that matched late.
NEWCOMERS_CHECK_S = 0.1
TWIST = "geometry_msgs/msg/Twist"
TWIST_STAMPED = "geometry_msgs/msg/TwistStamped"
STRING = "std_msgs/msg/String"
FLOAT64_ARRAY = "std_msgs/msg/Float64MultiArray"
POSE_STAMPED = "geometry_msgs/msg/PoseStamped"
#: Where rviz2's "2D Goal Pose" tool (and Nav2's simple commander) sends a goal: the bridge only
#: notes that one came (see :meth:`Ros2Bridge._greet_newcomers`). Best effort, so that writers
#: of either reliability match.
GOAL_TOPIC = "goal_pose"
GOAL_QOS = TopicQos(reliable=False, transient_local=False, depth=10)
OCCUPANCY_GRID = "nav_msgs/msg/OccupancyGrid"


@dataclasses.dataclass
class BridgeSettings:
    """What the bridge simulates and how it runs."""

    world: str = "seed-maze"
    robot: str = "e-puck"
    seed: int = 0
    noise: bool = True
    distro: str = "humble"
    mode: str = "lockstep"
    #: Free-running: simulated seconds per wall-clock second, 0 for as fast as possible.
    speed: float = 1.0
    #: Free-running: start paused.
    paused: bool = False
    #: Stop after this many steps (0: never).
    stop_after: int = 0
    stop_at_goal: bool = False
    #: A rosbag2 MCAP folder to record into, or ``None``.
    bag: str | None = None
    #: Open discovery to the network (the subnet) instead of this machine.
    network: bool = False
    #: A world of several robots: each robot's frames start with its namespace's name
    #: (``west/odom``), and its transforms go on the one ``/tf`` and ``/tf_static``.
    frame_prefix: bool = False
    #: A world of one robot: the namespace its topics go in (``epuck0``: ``/epuck0/odom``...),
    #: as a node written for one robot of several names them; ``""`` for none.
    namespace: str = ""
    #: Lockstep: the period in seconds of the timer on simulated time the driving node commands
    #: on; each command holds until the clock reaches its next tick (0: none, one step each;
    #: see :class:`mazesim.ros.lockstep.TimerHold`).
    command_period: float = 0.0
    #: Lockstep: wall-clock seconds after a state with no command before the bridge steps with
    #: the last command held, then on in real time until one comes (0: none, it waits; see
    #: :class:`mazesim.ros.lockstep.CommandDeadline`).
    command_deadline: float = 0.0
    #: Wall-clock seconds with no command and no command writer matched before the bridge
    #: gives up (0: never; see :class:`mazesim.ros.lockstep.IdleTimeout`).
    idle_timeout: float = IDLE_TIMEOUT_S
    #: The ``--ros-args`` of the command line (a launch file's): the node's name, namespace
    #: and remappings.
    ros_arguments: RosArguments = RosArguments()

    def validate(self) -> None:
        """Raises :class:`InvalidArgumentError` on a setting the bridge cannot run."""
        _known_name(self.mode, "mode", ("lockstep", "free"))
        if not (math.isfinite(self.speed) and self.speed >= 0.0):
            raise InvalidArgumentError(
                f"expected a speed >= 0 (0: as fast as possible); found {self.speed}"
            )
        if self.stop_after < 0:
            raise InvalidArgumentError(f"expected stop_after >= 0; found {self.stop_after}")
        if self.command_period and self.mode != "lockstep":
            raise InvalidArgumentError(
                "expected --command-period with --mode lockstep (free-running, a node's timer "
                f"on simulated time runs as it is); found --mode {self.mode}"
            )
        if self.command_deadline and self.mode != "lockstep":
            raise InvalidArgumentError(
                "expected --command-deadline with --mode lockstep (free-running, time moves "
                f"whether or not a command comes); found --mode {self.mode}"
            )
        if not (math.isfinite(self.idle_timeout) and self.idle_timeout >= 0.0):
            raise InvalidArgumentError(
                "expected --idle-timeout to be seconds >= 0 (0: never give up); found "
                f"{_shown(self.idle_timeout)}"
            )
        if self.namespace and not _ROS_NAMESPACE.fullmatch(self.namespace):
            raise InvalidArgumentError(
                "expected a ROS namespace for --namespace (names of letters, digits and _, "
                "not starting with a digit, joined by /: epuck0, /team/epuck0); found "
                f"{_shown(self.namespace)}"
            )
        if len(self.namespace) > MOST_NAMESPACE_CHARACTERS:
            raise InvalidArgumentError(
                f"expected a ROS namespace for --namespace of at most "
                f"{MOST_NAMESPACE_CHARACTERS} characters (the topics under it are ROS 2 names "
                f"of at most {MOST_NAME_CHARACTERS}); found one of {len(self.namespace)}"
            )


def _types_by_topic(endpoints: list[Any]) -> dict[str, list[str]]:
    """The message types of the endpoints on each topic (``/cmd_vel``: Twist, TwistStamped)."""
    types: dict[str, list[str]] = {}
    for endpoint in endpoints:
        if endpoint.msgtype not in types.setdefault(endpoint.topic, []):
            types[endpoint.topic].append(endpoint.msgtype)
    return types


def _motor_speeds(data: bytes) -> tuple[float, float]:
    return topics.motor_command(cdr.decode_float64_array(data))


class RobotChannel:
    """One robot's topics on a node: the writers of its state, the readers of its commands and
    the commands received but not yet stepped.

    Args:
        node: The bridge's node.
        state: The robot's state topics (their namespace is the commands' too).
        distro: ``humble`` or ``jazzy`` (Jazzy's ``cmd_vel`` is a TwistStamped).
    """

    def __init__(self, node: Node, state: StateTopics, distro: str) -> None:
        self.state = state
        self.writers = [node.writer(t.name, t.msgtype, t.qos) for t in state.topics]
        static = state.static_topic()
        self.static_writer = node.writer(static.name, static.msgtype, static.qos)
        jazzy = distro != "humble"
        ns = state.namespace
        # The distribution's cmd_vel type first (Webots' e-puck driver reads Twist on Humble,
        # TwistStamped from Jazzy on); the other one is read too, so a node written for the other
        # distribution (teleop_twist_keyboard's stamped:=true) drives as well.
        kinds = [(TWIST, cdr.decode_twist), (TWIST_STAMPED, cdr.decode_twist_stamped)]
        self.cmd_vels = [
            (node.reader(f"{ns}/{standard.CMD_VEL_TOPIC}", kind, COMMAND), decode)
            for kind, decode in (kinds[::-1] if jazzy else kinds)
        ]
        self.motor = node.reader(f"{ns}/{topics.MOTOR_TOPIC}", FLOAT64_ARRAY, COMMAND)
        self.action = node.reader(f"{ns}/{topics.ACTION_TOPIC}", STRING, COMMAND)
        #: Goals sent to the robot's navigator: read only to note that one came.
        self.goal = node.reader(f"{ns}/{GOAL_TOPIC}", POSE_STAMPED, GOAL_QOS)
        self.pending: deque[tuple[float, float]] = deque()
        self.wheel_speeds = (0.0, 0.0)
        self.held = topics.HeldCommand()
        #: Commands received so far (accepted or not).
        self.received = 0
        #: The robot's last state as it went out: each writer with its message.
        self.last_state: list[tuple[Any, bytes]] = []
        #: The command writers and state readers matched at the last look, and when a new one
        #: came and how many commands the robot had received then (see
        #: :meth:`Ros2Bridge._greet_newcomers`).
        self.known_writers: set[int] = set()
        self.known_readers: set[int] = set()
        self.newcomer_since: tuple[float, int] | None = None

    def command_readers(self) -> list[Reader]:
        """The readers of the robot's command topics (``cmd_vel`` of both types)."""
        return [reader for reader, _ in self.cmd_vels] + [self.motor, self.action]

    def driven(self) -> bool:
        """Whether a writer on one of the robot's command topics has matched."""
        return any(reader.publishers() for reader in self.command_readers())

    def watched(self) -> bool:
        """Whether a reader of one of the robot's state topics (``/tf_static`` aside) has
        matched."""
        return any(writer.subscribers() for writer in self.writers)

    def command_writers(self) -> set[int]:
        """The writers matched now on the robot's command topics."""
        return set().union(*(reader.matched_writers() for reader in self.command_readers()))

    def state_readers(self) -> set[int]:
        """The readers matched now on the robot's state topics (a node's new subscription, as
        ``rclpy.wait_for_message`` makes one, is new)."""
        return set().union(*(writer.matched_readers() for writer in self.writers))

    def commands(self) -> list[tuple[float, float]]:
        """The wheel speeds of every command received since the last call. A bad one is
        reported on stderr and keeps the wheel speeds of the command before it
        (:class:`~mazesim.ros.topics.HeldCommand`, the rule of both bridges)."""
        speeds: list[tuple[float, float]] = []
        for reader, decode in self.cmd_vels:
            for data in reader.take():
                self._accept(speeds, functools.partial(self._twist_speeds, decode, data))
        for data in self.motor.take():
            self._accept(speeds, functools.partial(_motor_speeds, data))
        for data in self.action.take():
            self._accept(speeds, functools.partial(self._action_speeds, data))
        return speeds

    def _twist_speeds(
        self, decode: Callable[[bytes], tuple[float, float]], data: bytes
    ) -> tuple[float, float]:
        linear, angular = decode(data)
        return standard.twist_wheel_speeds(linear, angular, self.state.robot)

    def _action_speeds(self, data: bytes) -> tuple[float, float]:
        return wheel_speeds(cdr.decode_string(data), self.state.robot.max_wheel_speed)

    def _accept(
        self, speeds: list[tuple[float, float]], read: Callable[[], tuple[float, float]]
    ) -> None:
        self.received += 1
        wheels, refused = self.held.take(read)
        if refused:
            where = f" for {self.state.namespace[1:]}" if self.state.namespace else ""
            print(
                f"mazesim ros2 bridge: ignored a command{where}: {refused}; the robot keeps its "
                "wheel speeds for that step",
                file=sys.stderr,
                flush=True,
            )
        speeds.append(wheels)


class Ros2Bridge:
    """The bridge node around one simulator.

    Args:
        simulator: The simulator to drive.
        settings: Mode, distribution, stop conditions, bag.
        node: The ROS 2 node to publish on (a new one by default).
    """

    def __init__(
        self, simulator: Simulator, settings: BridgeSettings, node: Node | None = None
    ) -> None:
        if settings.namespace and simulator.num_robots > 1:
            raise InvalidArgumentError(
                "expected a world of one robot for --namespace; found "
                f"{simulator.num_robots} robots in {_shown(simulator.world.name)}, each in the "
                "namespace of its name: leave --namespace out"
            )
        own = "/" + settings.namespace.strip("/") if settings.namespace else ""
        if settings.frame_prefix and simulator.num_robots == 1 and not own:
            raise InvalidArgumentError(
                "expected a world of several robots for --frame-prefix (each robot's frames "
                f"start with its name); found one robot in {_shown(simulator.world.name)}, whose "
                "frames are odom, base_link...: leave --frame-prefix out"
            )
        #: Lockstep: how long each command holds (``--command-period``).
        self.hold = TimerHold(settings.command_period, simulator.control_step_ms / 1000.0)
        #: Lockstep: when the bridge steps without a command (``--command-deadline``).
        self.deadline = CommandDeadline(
            settings.command_deadline, simulator.control_step_ms / 1000.0
        )
        self.simulator = simulator
        self.settings = settings
        self.node = node or Node(
            settings.ros_arguments.node_name or NODE_NAME,
            settings.distro,
            network.discovery_from_environment(network=settings.network),
            namespace=own or "/",
            ros_arguments=settings.ros_arguments,
        )
        imu_seed = settings.seed if settings.noise else None
        if simulator.num_robots == 1:
            prefix = frame_prefix(own) if settings.frame_prefix else ""
            states = [
                StateTopics(
                    simulator,
                    settings.distro,
                    own,
                    clock=not own,
                    frame_prefix=prefix,
                    imu_seed=imu_seed,
                )
            ]
        else:
            namespaces = robot_namespaces(simulator.robot_names)
            states = [
                StateTopics(
                    RobotOf(simulator, i),  # type: ignore[arg-type]
                    settings.distro,
                    namespace,
                    clock=False,
                    frame_prefix=frame_prefix(namespace) if settings.frame_prefix else "",
                    imu_seed=imu_seed,
                )
                for i, namespace in enumerate(namespaces)
            ]
        self.robots = [RobotChannel(self.node, state, settings.distro) for state in states]
        self.state = states[0]
        #: ``/clock`` for a world of several robots (a world of one has it among its topics).
        self.clock_writer = (
            None
            if simulator.num_robots == 1 and not own
            else self.node.writer(CLOCK_TOPIC, CLOCK_TYPE, CLOCK)
        )
        #: ``/map``: the world's walls, once, latched as ``map_server`` publishes it; the same
        #: map in each robot's namespace too (``/west/map``), where Nav2 brought up in a
        #: namespace (its map server, AMCL and costmaps' static layers) reads ``map``.
        self.map_writers = [
            self.node.writer(topic, OCCUPANCY_GRID, TF_STATIC)
            for topic in map_topics([robot.state.namespace for robot in self.robots])
        ]
        self.control: Reader | None = None
        if settings.mode == "free":
            self.control = self.node.reader(SIM_CONTROL_TOPIC, STRING, COMMAND)
        #: ``/reset_simulation`` and ``/reset_world`` (``std_srvs/srv/Empty``, as Gazebo's
        #: ``gazebo_ros_init`` offers them; :mod:`mazesim.ros.resets`).
        self.resets = EpisodeResets(simulator)
        self.reset_servers = [
            (self.node.service_server(service_name(kind, ros1=False)), kind) for kind in RESETS
        ]
        #: ``ros2 param list/get/set/describe``: ``use_sim_time`` and the settings, read-only.
        self.parameters = ParameterServers(self.node, bridge_parameters(settings), self._say)
        self.node.announce()
        published = [writer.topic for writer in self.node.writers]
        self.unpublished = UnpublishedTopics(
            self.node.participant,
            published,
            simulator.robot.name,
            self._say,
            read=[reader.topic for reader in self.node.readers],
            namespaces=[robot.state.namespace for robot in self.robots if robot.state.namespace],
            types=_types_by_topic([*self.node.writers, *self.node.readers]),
            node=f"{self.node.namespace.rstrip('/')}/{self.node.name}",
        )
        self.incompatible = IncompatibleQos(self.node.writers, self.node.readers, self._say)
        self._readers_checked = 0.0
        self._newcomers_checked = 0.0
        self.bag = BagRecorder(settings.bag, settings.distro) if settings.bag else None
        self.goal = simulator.world.goal
        self.goal_step: int | None = None
        self.stop = threading.Event()
        self.rejected_controls = 0
        #: Reset calls answered so far.
        self.resets_served = 0
        #: Lockstep: the reset state has gone out (from then on a node that matches late gets
        #: its robot's state again, see :meth:`_greet_newcomers`).
        self.reset_state_out = False
        #: Lockstep: the first state's sensor messages and ``/clock``, while they wait for
        #: :data:`MOTION_LEAD_S` after its motion (see :meth:`_publish_first_state`), and when.
        self._first_rest: list[tuple[Any, bytes]] = []
        self._first_rest_at = math.inf
        #: Lockstep: when a state that went unanswered goes out again.
        self.unanswered = UnansweredState()
        #: Lockstep: control steps ``/clock`` ran on its own before the first command; every
        #: stamp after them is that many steps later than the simulator's time.
        self.idle_steps = 0
        #: When a bridge nobody drives gives up (``idle_timeout``).
        self.idle = IdleTimeout(settings.idle_timeout, time.monotonic())
        self._idle_tick_at = math.inf
        self._waitset = self._make_waitset()

    def _make_waitset(self) -> Any:
        from cyclonedds.core import InstanceState, ReadCondition, SampleState, ViewState, WaitSet

        waitset = WaitSet(self.node.participant)
        mask = SampleState.Any | ViewState.Any | InstanceState.Any
        for reader in self.node.readers:
            waitset.attach(ReadCondition(reader.dds, mask))
        for server in self.node.services:
            waitset.attach(ReadCondition(server.requests.dds, mask))
        return waitset

    @staticmethod
    def _say(message: str) -> None:
        print(f"mazesim ros2 bridge: {message}", file=sys.stderr, flush=True)

    def _check_readers(self) -> None:
        """Says which topics other nodes read that the bridge does not publish, and which of
        their readers and writers cannot match the bridge's QoS (every second)."""
        now = time.monotonic()
        if now - self._readers_checked >= READERS_CHECK_S:
            self._readers_checked = now
            self.unpublished.check()
            self.incompatible.check()

    def _send(self, writer: Any, nanoseconds: int, data: bytes) -> None:
        writer.publish(data)
        if self.bag is not None:
            self.bag.write(writer.topic, writer.msgtype, nanoseconds, data)

    @property
    def rejected(self) -> int:
        """Commands refused, over every robot, and simulation controls refused."""
        return sum(robot.held.refused for robot in self.robots) + self.rejected_controls

    def stamp(self) -> int:
        """The stamp of the current step in nanoseconds: the simulator's time, plus the steps
        ``/clock`` ran on its own before the first command (lockstep; see
        :meth:`_tick_idle_clock`)."""
        control_step_s = self.simulator.control_step_ms / 1000.0
        return stamp_nanoseconds(self.simulator.time + self.idle_steps * control_step_s)

    def publish_static(self) -> None:
        """Publishes ``/tf_static`` and ``/map`` (transient local: late subscribers get them
        too)."""
        nanoseconds = self.stamp()
        world_map = occupancy_grid(self.simulator.world, cdr.stamp_of(nanoseconds))
        for writer in self.map_writers:
            self._send(writer, nanoseconds, world_map)
        for robot in self.robots:
            data = robot.state.static_transforms(cdr.stamp_of(nanoseconds))
            self._send(robot.static_writer, nanoseconds, data)

    def publish_state(self, step_seconds: float, first: bool = False) -> None:
        """Publishes every state topic for the current step, ``/clock`` last; with ``first``,
        the transforms and motion only, keeping the rest for :meth:`_finish_first_state`."""
        if not first:
            self._finish_first_state()
        nanoseconds = self.stamp()
        for robot in self.robots:
            self._publish_robot_state(robot, step_seconds, first)
        if self.clock_writer is not None:
            clock = (self.clock_writer, cdr.encode_clock(cdr.stamp_of(nanoseconds)))
            if first:
                self._first_rest.append(clock)
            else:
                self._send(clock[0], nanoseconds, clock[1])

    def _publish_robot_state(
        self, robot: RobotChannel, step_seconds: float, first: bool = False
    ) -> None:
        """Publishes one robot's state topics for the current step in the state's order
        (:attr:`~mazesim.ros2.state.StateTopics.order`: ``/tf`` first, then the odometry, then
        the sensors, so a node that answers a sensor message with the latest pose has that
        step's), and keeps them as they went out; with ``first``, the transforms and motion
        only, the rest kept for :meth:`_finish_first_state`."""
        nanoseconds = self.stamp()
        messages = robot.state.messages(cdr.stamp_of(nanoseconds), step_seconds)
        robot.last_state = [(robot.writers[at], messages[at]) for at in robot.state.order]
        now = robot.state.motion_count if first else len(robot.last_state)
        for writer, data in robot.last_state[:now]:
            self._send(writer, nanoseconds, data)
        self._first_rest += robot.last_state[now:]

    def _publish_first_state(self) -> None:
        """Lockstep: publishes the reset state in two parts, ``/tf`` and the motion
        (``/odom``, ``/joint_states``, ``/imu``, ``/pose``) first and the sensor messages and
        ``/clock`` :data:`MOTION_LEAD_S` later (or before the first step, if a command comes
        sooner). A node that answers a sensor message with the latest odometry (a Bug planner's
        ``/scan`` callback that skips until an ``/odom`` has come) has the reset state's odometry
        whatever order its executor serves the two subscriptions in once both are ready (rclpy
        and rclcpp serve them in the order they were made), and answers the reset state; after
        it every state finds the one before in the node's caches."""
        self.publish_state(0.0, first=True)
        self._first_rest_at = time.monotonic() + MOTION_LEAD_S

    def _finish_first_state(self) -> None:
        """Sends the first state's sensor messages and ``/clock`` if they still wait."""
        rest, self._first_rest, self._first_rest_at = self._first_rest, [], math.inf
        nanoseconds = self.stamp()
        for writer, data in rest:
            self._send(writer, nanoseconds, data)
        if rest:
            self.unanswered.went_out(time.monotonic())

    def _note_goal(self) -> None:
        if self.goal is not None and self.goal_step is None:
            x, y, _ = self.simulator.pose
            goal_x, goal_y, radius = self.goal
            if math.hypot(x - goal_x, y - goal_y) <= radius:
                self.goal_step = self.simulator.steps
        settings = self.settings
        if settings.stop_at_goal and self.goal_step is not None:
            self.stop.set()
        if settings.stop_after and self.simulator.steps >= settings.stop_after:
            self.stop.set()

    def step(self, left: float, right: float) -> None:
        """One control step with these wheel speeds (robot 0's; the others keep theirs), then
        the state topics."""
        self.robots[0].wheel_speeds = (left, right)
        self.step_robots()

    def step_robots(self) -> None:
        """One control step with each robot's wheel speeds, then the state topics."""
        self._finish_first_state()
        if len(self.robots) == 1:
            self.simulator.step(*self.robots[0].wheel_speeds)
        else:
            import numpy as np

            commands = np.array([robot.wheel_speeds for robot in self.robots], dtype=np.float64)
            self.simulator.step_robots(commands)
        self.publish_state(self.simulator.control_step_ms / 1000.0)
        self.unanswered.went_out(time.monotonic())
        self._note_goal()

    def commands(self) -> list[tuple[float, float]]:
        """Robot 0's commands received since the last call (see :meth:`RobotChannel.commands`)."""
        return self.robots[0].commands()

    def _step_pending(self) -> None:
        """Lockstep: steps the world while every robot that is driven has a command waiting
        (robots that are not keep their wheel speeds)."""
        for robot in self.robots:
            robot.pending.extend(robot.commands())

        def step() -> None:
            self.hold.start(self.stamp())
            self._step_held()

        step_rounds(self.robots, self.stop, step)

    def _step_held(self) -> None:
        """Lockstep: one step, and with ``--command-period`` the further steps the command holds
        until the clock reaches the node's next tick (:class:`~mazesim.ros.lockstep.TimerHold`)."""
        self.step_robots()
        while self.hold.holds(self.stamp()) and not self.stop.is_set():
            self.step_robots()
        self.hold.ended(time.monotonic())
        self.deadline.commanded(time.monotonic())

    def _step_on_skipped_tick(self) -> None:
        """Lockstep with ``--command-period``, once a command has been stepped: when no command
        has come ``SKIPPED_TICK_S`` after a hold ended at the node's tick, the node let that tick
        go (it found a message of the tick not come yet); every robot's last command holds on to
        the next tick (a robot whose command waits takes it), as a simulator whose clock runs on
        would, so that the node's timer fires again (:class:`~mazesim.ros.lockstep.TimerHold`,
        the rule of both bridges)."""
        if self.stop.is_set() or not self.hold.let_go(time.monotonic()):
            return
        for robot in self.robots:
            if robot.pending:
                robot.wheel_speeds = robot.pending.popleft()
        notice = self.hold.holding_on()
        if notice is not None:
            self._say(notice)
        self.hold.start(self.stamp())
        self._step_held()

    def _step_on_deadline(self) -> None:
        """Lockstep with ``--command-deadline``, once a command has been stepped: when none
        has come within the deadline after a state, one step with every robot's last command
        held (a robot whose command waits takes it), and so on in real time until a command
        comes (:class:`~mazesim.ros.lockstep.CommandDeadline`), so that a node waiting for
        simulated time the bridge cannot foresee gets it."""
        now = time.monotonic()
        if self.stop.is_set() or not self.deadline.due(now):
            return
        for robot in self.robots:
            if robot.pending:
                robot.wheel_speeds = robot.pending.popleft()
        notice = self.deadline.stepped(now)
        if notice is not None:
            self._say(notice)
        self.step_robots()

    def _serve_resets(self) -> None:
        """Answers the calls of ``/reset_simulation`` and ``/reset_world``: puts the simulator
        back (:class:`~mazesim.ros.resets.EpisodeResets`), every robot's wheels at rest and no
        command waiting, publishes the state after the reset (in lockstep the state the next
        command answers) and then answers the call."""
        for server, kind in self.reset_servers:
            server.flush()
            for request in server.take_requests():
                self.resets.apply(kind)
                from_the_start = kind == RESET_SIMULATION
                if from_the_start:
                    self.idle_steps = 0
                self.hold.start(self.stamp())  # no tick waits for a command across a reset
                for robot in self.robots:
                    robot.pending.clear()
                    robot.wheel_speeds = robot.held.latest = (0.0, 0.0)
                    robot.state.restart(from_the_start)
                self._say(
                    f"{server.service}: {RESETS[kind]} (step {self.simulator.steps}, "
                    f"{self.simulator.time:.3f} s simulated); publishing the state after it"
                )
                self.publish_state(0.0)
                self.unanswered.went_out(time.monotonic())
                self.deadline.commanded(time.monotonic())
                self.resets_served += 1
                server.reply(request)

    def wait_for_driver(self) -> None:
        """Lockstep: waits until a command writer or a reader of a state topic has matched (a
        node that waits for one state before it creates its command writer, as
        ``rclpy.wait_for_message`` at start-up does, gets the reset state), then the grace
        period."""
        while not self._given_up_when_idle():
            self._check_readers()
            self.parameters.serve()
            if any(robot.driven() or robot.watched() for robot in self.robots):
                self.stop.wait(READY_GRACE_S)
                return
            self.stop.wait(0.02)

    def run(self) -> None:
        """Runs until stopped (a signal, ``stop_after`` or the goal)."""
        self.publish_static()
        if self.settings.mode == "lockstep":
            self.wait_for_driver()
            if not self.stop.is_set():
                self._note_matched()  # the nodes matched now get the reset state: not late
                self._publish_first_state()
                self.reset_state_out = True
                self.unanswered.went_out(time.monotonic())
                if self.hold.active:  # at rest, no command yet, until the node's first tick
                    self.hold.start(self.stamp())
                    while self.hold.holds(self.stamp()) and not self.stop.is_set():
                        self.step_robots()
            while not self.stop.is_set():
                now = time.monotonic()
                wait = min(
                    0.1,
                    max(self._idle_tick_at - now, 0.0),
                    self.deadline.wait(now),
                    self.hold.wait(now),
                )
                self._waitset.wait(int(wait * 1e9))
                if time.monotonic() >= self._first_rest_at:
                    self._finish_first_state()
                self._step_pending()
                self._step_on_deadline()
                self._step_on_skipped_tick()
                self._serve_resets()
                self.parameters.serve()
                self._check_readers()
                self._greet_newcomers()
                self._resend_unanswered()
                self._tick_idle_clock()
                self._given_up_when_idle()
            return
        self._run_free()

    def _given_up_when_idle(self) -> bool:
        """Stops the bridge once no command writer has been matched for ``idle_timeout``
        seconds (no command can come without one; :class:`~mazesim.ros.lockstep.IdleTimeout`),
        saying so; returns whether the bridge is stopped."""
        driven = any(robot.driven() for robot in self.robots)
        if not self.stop.is_set() and self.idle.watch(time.monotonic(), driven):
            self._say(self.idle.message("--idle-timeout"))
            self.stop.set()
        return self.stop.is_set()

    def _resend_unanswered(self) -> None:
        """Lockstep: when no command has come ``RESEND_S`` after a state went out while a
        command writer is matched (:class:`~mazesim.ros.lockstep.UnansweredState`, the rule of
        both bridges), publishes it again: before the first command the reset state (a node
        that answers only from its second message, or whose first command went out before it
        matched, gets another; if that goes unanswered too, ``/clock`` runs on its own
        ``IDLE_CLOCK_AFTER_S`` later, see :meth:`_tick_idle_clock`); once stepping, the last
        state of every robot the world waits for, as it went out (same bytes, same stamp): a
        node that let one state go unanswered (a lifecycle node paused and resumed by its
        manager, whose publisher dropped the answer meanwhile) gets it again, and the run stays
        the in-process run step for step. Says so on stderr the first time."""
        if not self.unanswered.waited_long(time.monotonic()):
            return
        stepped = self.simulator.steps > 0
        pending = any(robot.pending for robot in self.robots)
        if (pending and not stepped) or any(robot.newcomer_since for robot in self.robots):
            return  # a node that came late gets the state from _greet_newcomers, once
        robots = [robot for robot in self.robots if robot.driven() and not robot.pending]
        if not robots:
            return
        topic = f"{robots[0].state.namespace}/{standard.CMD_VEL_TOPIC}"
        notice = self.unanswered.resending(
            stepped, self.simulator.steps, topic, "run it with --command-period or --mode free"
        )
        if notice is not None:
            idle = (
                ""
                if stepped
                else f"; if this one goes unanswered too, /clock runs on its own "
                f"{IDLE_CLOCK_AFTER_S:g} s later, for a node that waits for simulated time "
                "before its first command"
            )
            self._say(notice + idle)
        if not stepped:
            self.publish_state(0.0)
            if self._idle_tick_at == math.inf:
                self._idle_tick_at = time.monotonic() + IDLE_CLOCK_AFTER_S
            return
        for robot in robots:
            nanoseconds = self.stamp()
            for writer, data in robot.last_state:
                self._send(writer, nanoseconds, data)

    def _tick_idle_clock(self) -> None:
        """Lockstep, before the first command: once the reset state sent again has gone
        unanswered for ``IDLE_CLOCK_AFTER_S``, ``/clock`` runs on its own in real time, one control
        step at a time, the robot standing still and nothing else published, so that a node that
        waits for simulated time before its first command (``teleop_twist_keyboard``'s
        ``rospy.sleep``, a start-up sleep or one-shot timer on ``/clock``) can start. The
        simulator does not step: the run stays the in-process run with the same commands, step
        for step and reading for reading, its stamps later by the steps the clock ran
        (:attr:`idle_steps`, said on stderr at the first command and at the end). A node that
        answers the reset state, or the reset state sent again, never sees the clock run."""
        if self.simulator.steps or time.monotonic() < self._idle_tick_at or self.stop.is_set():
            if self.simulator.steps and self._idle_tick_at != math.inf:
                self._idle_tick_at = math.inf
                if self.idle_steps:
                    self._say(
                        f"lockstep: the first command came after /clock ran {self.idle_steps} "
                        "steps on its own; from here every stamp is that many steps later "
                        "than the in-process run's, whose steps and readings this run keeps"
                    )
            return
        if any(robot.pending for robot in self.robots):
            return
        if self.idle_steps == 0:
            self._say(
                "lockstep: the reset state sent again went unanswered; /clock now runs on its "
                "own in real time, the robot standing still, until the first command (a node "
                "that waits for simulated time before its first command can start; one that "
                "commands on a timer of simulated time slower than the control step runs in "
                "lockstep with --command-period, its timer's period)"
            )
        self.idle_steps += 1
        nanoseconds = self.stamp()
        clock = self.clock_writer or next(
            writer for writer in self.robots[0].writers if writer.topic == CLOCK_TOPIC
        )
        self._send(clock, nanoseconds, cdr.encode_clock(cdr.stamp_of(nanoseconds)))
        self._idle_tick_at += self.simulator.control_step_ms / 1000.0

    def _note_matched(self) -> None:
        """Notes the command writers and state readers matched now as known (not late)."""
        for robot in self.robots:
            robot.known_writers, robot.known_readers = (
                robot.command_writers(),
                robot.state_readers(),
            )

    def _greet_newcomers(self) -> None:
        """Lockstep, once the reset state has gone out (before the first command as after it,
        and after a reset): a node that starts writing a robot's commands after the robot's
        last state went out (started, or restarted, while the bridge runs), makes a new reader
        of its state (``rclpy.wait_for_message`` before its first command, after a reset call
        or between two commands: a volatile reader receives nothing sent before it matched), or
        drives only once it has a goal (one came on ``/goal_pose``), waits for a state, and the
        bridge for its command. When a command writer or a state reader matches that was not
        matched before, or a goal comes, and the robot has received no command
        ``READY_GRACE_S`` later, the robot's last state goes out again as it went out (same
        stamp; ``/clock`` too in a world of one robot; before the first step the reset state,
        made again at the current stamp); a node that answers at once gets nothing twice. Says
        so on stderr."""
        now = time.monotonic()
        if now - self._newcomers_checked < NEWCOMERS_CHECK_S:
            return  # a look costs a DDS query per command topic: not at every lockstep step
        self._newcomers_checked = now
        for robot in self.robots:
            writers, readers = robot.command_writers(), robot.state_readers()
            # A node that drives once it has a goal waits for a state, as a new one does.
            goal_came = robot.goal.take()
            came = bool(writers - robot.known_writers or readers - robot.known_readers) or goal_came
            if came and self.reset_state_out:
                robot.newcomer_since = (now, robot.received)
            robot.known_writers, robot.known_readers = writers, readers
            if robot.newcomer_since is None:
                continue
            since, received = robot.newcomer_since
            if robot.received != received or robot.pending:
                robot.newcomer_since = None
            elif now - since >= READY_GRACE_S:
                robot.newcomer_since = None
                self._send_last_state(robot)

    def _send_last_state(self, robot: RobotChannel) -> None:
        """Sends the robot's last state again; before the first step the reset state, made
        again at the current stamp (``/clock`` may have run on its own since it went out, and
        must not go back)."""
        self.unanswered.went_out(time.monotonic())
        if self.simulator.steps == 0:
            self._publish_robot_state(robot, 0.0)
        else:
            nanoseconds = self.stamp()
            for writer, data in robot.last_state:
                self._send(writer, nanoseconds, data)
        topic = f"{robot.state.namespace}/{standard.CMD_VEL_TOPIC}"
        self._say(
            f"lockstep: a command writer or state reader matched after the last state went out "
            f"(e.g. on {topic}: a node started or restarted while the bridge runs, or one waiting "
            f"for a message after the reset state or a reset call), or a goal came on "
            f"{robot.goal.topic} (a navigator that drives once it has one), and no command came "
            f"in {READY_GRACE_S:g} s; "
            f"publishing that state again (step {self.simulator.steps})"
        )

    def _run_free(self) -> None:
        control_step_s = self.simulator.control_step_ms / 1000.0
        pace = FreeRunning(self.settings.speed, control_step_s, self.settings.paused)
        self.publish_state(0.0)
        while not self._given_up_when_idle():
            assert self.control is not None
            for data in self.control.take():
                try:
                    pace.control(cdr.decode_string(data))
                except InvalidActionError as error:
                    self.rejected_controls += 1
                    print(f"mazesim ros2 bridge: ignored: {error}", file=sys.stderr, flush=True)
            for robot in self.robots:
                for speeds in robot.commands():
                    robot.wheel_speeds = speeds
            self._serve_resets()
            self.parameters.serve()
            self._check_readers()
            delay = pace.due(self.simulator.time, control_step_s)
            if delay is None:
                self._waitset.wait(50_000_000)
                continue
            if delay > 0.0:
                self._waitset.wait(int(delay * 1e9))
                continue
            self.step_robots()
            pace.stepped()

    def close(self) -> None:
        """Finishes the bag and leaves the DDS domain."""
        if self.bag is not None:
            self.bag.close()
            self.bag = None
        self.node.close()


@leaves_signals_as_found
def run_bridge(settings: BridgeSettings) -> int:
    """Runs the bridge from the command line until SIGINT/SIGTERM, ``stop_after`` or the goal.

    Returns:
        The exit code, 0 once the bridge has stopped, ``IDLE_EXIT_STATUS`` when it gave up with
        no node driving it (``idle_timeout``).
    """
    settings.validate()
    import mazesim

    world = mazesim.load_world(settings.world)
    if settings.stop_at_goal and world.goal is None:
        raise InvalidArgumentError(f"--stop-at-goal: world {_shown(world.name)} has no goal")
    simulator = Simulator(world, robot=settings.robot, seed=settings.seed, noise=settings.noise)
    bridge = Ros2Bridge(simulator, settings)

    def on_signal(number: int, frame: Any) -> None:
        bridge.stop.set()

    signal.signal(signal.SIGINT, on_signal)
    signal.signal(signal.SIGTERM, on_signal)
    started = time.monotonic()
    frames = ", frames prefixed with the namespace's name, on /tf" if settings.frame_prefix else ""
    robots = (
        settings.robot
        + (f" (namespace {bridge.state.namespace}{frames})" if settings.namespace else "")
        if simulator.num_robots == 1
        else f"{simulator.num_robots} robots (namespaces "
        f"{', '.join(robot.state.namespace for robot in bridge.robots)}{frames})"
    )
    print(
        f"mazesim ros2 bridge: {robots} in {world.name}, ROS 2 {settings.distro}, "
        f"{settings.mode}, domain {bridge.node.discovery.domain_id} "
        f"({bridge.node.discovery.reach.lower()})",
        file=sys.stderr,
        flush=True,
    )
    try:
        bridge.run()
    finally:
        bridge.close()
    goal = (
        "no goal in this world"
        if bridge.goal is None
        else (
            "goal not reached"
            if bridge.goal_step is None
            else f"goal reached at step {bridge.goal_step}"
        )
    )
    idle = (
        f", /clock ran {bridge.idle_steps} steps before the first command"
        if bridge.idle_steps
        else ""
    )
    unanswered = bridge.deadline.steps
    held = f", {unanswered} steps without a command (--command-deadline)" if unanswered else ""
    skipped = bridge.hold.skipped
    let_go = f", {skipped} ticks let go without a command (--command-period)" if skipped else ""
    print(
        f"mazesim ros2 bridge: stopped after {simulator.steps} steps "
        f"({simulator.time:.3f} s simulated, {time.monotonic() - started:.1f} s wall clock), "
        f"{goal}{idle}{held}{let_go}",
        file=sys.stderr,
        flush=True,
    )
    return IDLE_EXIT_STATUS if bridge.idle.expired else 0
