"""The bridge node: one mazesim simulator as the report's custom ROS controller (Listing 3.1).

The bridge publishes ``sensors``, ``sensor_data`` (robots with Sharp sensors), ``pose`` and
``/clock``, and takes wheel speeds from ``motor`` or primitive action codes from ``action``; see
:mod:`mazesim.ros.topics` for the layouts. Beside them it speaks the standard messages (one
``sensor_msgs/Range`` per distance sensor, ``nav_msgs/Odometry`` on ``odom``, ``/tf`` and
``/tf_static``, ``geometry_msgs/Twist`` commands on ``cmd_vel``); see :mod:`mazesim.ros.standard`.
A ``cmd_vel`` twist is a command like the others. It runs in one of two modes:

- ``lockstep`` (the default): the simulation advances exactly one control step for each command
  received, then publishes the new state, as Webots does with ``--synchronize``. The controller
  answers each ``sensors`` (or ``sensor_data``) message with one command, so no reading is ever
  missed or stale whatever the load, and a run is as deterministic as the in-process simulator.
  The state topics are latched: a controller that connects late still receives the state waiting
  for its command, once, in the order it went out, once its command publisher is connected too
  (:mod:`mazesim.ros.latched`). While a
  publisher of one of the command topics is connected and no command has come ``RESEND_S``
  seconds after a state went out, the bridge publishes that state again
  (:class:`~mazesim.ros.lockstep.UnansweredState`, shared with the ROS 2 bridge): before the
  first command the reset state (a controller whose first command went out before the bridge
  listened, or that answers only from its second message, gets another), afterwards the last
  state as it went out (a controller that let one go unanswered gets it again), and says so.
  A controller commanding at a ``rospy.Rate`` of simulated time slower than the control step
  gets ``command_period``, the rate's period: each command holds over whole control steps until
  the clock reaches the rate's next tick (:class:`~mazesim.ros.lockstep.TimerHold`, the rule of
  both bridges; the state before the first step is stamped 1 ns, never 0, as ROS 2's bridge
  stamps it, and a ``rospy.Rate`` made then counts from it). A controller that waits for
  simulated time the bridge cannot foresee (a ``rospy.Timer`` or ``rospy.sleep`` counted from
  some later time) gets ``command_deadline``: when no command comes within it after a state, the
  bridge steps with the last command held, then on in real time until one comes
  (:class:`~mazesim.ros.lockstep.CommandDeadline`, the rule of both bridges). Run exactly one
  controller in this mode.
- ``realtime``: the simulation steps on its own, ``speed`` times faster than the wall clock, with
  the last commanded wheel speeds.

Parameters (private, e.g. ``~world``; options of ``mazesim ros bridge`` take precedence):
``world`` (built-in name or world file, default ``seed-maze``), ``robot`` (``e-puck``), ``seed``
(0), ``mode`` (``lockstep``), ``speed`` (1.0), ``duration`` (simulated seconds after which the
bridge stops, 0 for never), ``noise`` (true), ``stop_at_goal`` (false: stop after the step that
brings the robot into the world's goal disc), ``command_period`` (0: a step per command),
``command_deadline`` (0: wait for each command). The
bridge sets ``/use_sim_time`` to true unless it
is already set, and sets ``control_step_ms`` in its namespace (next to its topics, e.g.
``/control_step_ms``) to the length of its control step before it listens for commands: the
perform-learning node dead-reckons its sub-tasks with it. It logs the step at which the robot first
reaches the goal, and says in its last log line whether it did.

A world of several robots is served by :mod:`mazesim.ros.several`: each robot's topics in a
namespace of its name, one ``/clock``.

It offers Gazebo's reset services, ``/gazebo/reset_simulation`` and ``/gazebo/reset_world``
(``std_srvs/Empty``; :mod:`mazesim.ros.resets`, shared with the ROS 2 bridge): the state after
the reset goes out before the call is answered.

A bad command (not two finite numbers, an unknown action code) is logged and keeps the wheel
speeds of the last command accepted (:class:`~mazesim.ros.topics.HeldCommand`, the rule of both
bridges): in lockstep it still takes its step, so a controller answering each state with one
command gets the next state.
"""

from __future__ import annotations

import functools
import math
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, fields
from typing import Any

import mazesim
from mazesim._core import Simulator, World
from mazesim.actions import wheel_speeds
from mazesim.errors import InvalidArgumentError, MazesimError, _known_name, _shown
from mazesim.ros import standard, topics
from mazesim.ros._ros import start_node, topics_of_nodes, writers_connected
from mazesim.ros.bag import BagWriter
from mazesim.ros.latched import LateConnections, state_publisher
from mazesim.ros.lockstep import (
    IDLE_CLOCK_AFTER_S,
    IDLE_EXIT_STATUS,
    IDLE_TIMEOUT_S,
    RESEND_S,
    CommandDeadline,
    IdleTimeout,
    RealTimePace,
    TimerHold,
    UnansweredState,
    stamp_nanoseconds,
)
from mazesim.ros.resets import RESET_SIMULATION, RESETS, EpisodeResets, service_name
from mazesim.ros.several import SeveralRobotsBridge, refuse_single_robot_settings
from mazesim.ros.standard import StandardPublishers

__all__ = [
    "IDLE_CLOCK_AFTER_S",
    "IDLE_EXIT_STATUS",
    "MODES",
    "MAX_SETTING_SECONDS",
    "MIN_SPEED",
    "RESEND_S",
    "Bridge",
    "BridgeSettings",
    "refuse_several_robots",
    "run_bridge",
    "xml_rpc_value",
]

#: The bridge's modes.
MODES = ("lockstep", "realtime")
#: Seconds without a command after which a lockstep bridge says it is waiting for one.
IDLE_WARNING_S = 5.0
#: Where rviz's "2D Nav Goal" sends a goal (``move_base``'s simple goal topic): the bridge only
#: notes that one came (see :meth:`Bridge.answer_goal`).
GOAL_TOPIC = "move_base_simple/goal"
#: Lockstep: seconds after a goal came, no command come, before the state goes out again.
GOAL_GRACE_S = 0.5
#: The most seconds a setting of seconds takes (duration, command period, deadline, idle
#: timeout), as the command line's options take (``mazesim.cli._args.MAX_SECONDS``).
MAX_SETTING_SECONDS = 1e6
#: The slowest real-time factor (and 1 / it the fastest): a step's wait stays within the clock's.
MIN_SPEED = 1e-6


@dataclass
class BridgeSettings:
    """What the bridge simulates and how; each field is also a private ROS parameter."""

    world: str = "seed-maze"
    robot: str = "e-puck"
    seed: int = 0
    mode: str = "lockstep"
    speed: float = 1.0
    duration: float = 0.0
    noise: bool = True
    stop_at_goal: bool = False
    #: Lockstep: the controller commands at a ``rospy.Rate`` of simulated time with this period
    #: in seconds; each command holds until the clock reaches the rate's next tick (0: none, one
    #: step each; see :class:`mazesim.ros.lockstep.TimerHold`).
    command_period: float = 0.0
    #: Lockstep: wall-clock seconds after a state with no command before the bridge steps with
    #: the last command held, then on in real time until one comes (0: none, it waits; see
    #: :class:`mazesim.ros.lockstep.CommandDeadline`).
    command_deadline: float = 0.0
    #: A bag the bridge writes every message it sends and every command it takes into (see
    #: :mod:`mazesim.ros.bag`; empty: none).
    bag: str = ""
    #: Wall-clock seconds with no command and no publisher of a command topic connected before
    #: the bridge gives up (0: never; see :class:`mazesim.ros.lockstep.IdleTimeout`).
    idle_timeout: float = IDLE_TIMEOUT_S

    def validate(self) -> None:
        """Raises InvalidArgumentError naming the first parameter that is out of range: the
        same ranges whether a setting came from the command line or a ROS parameter (a
        parameter of 1e9 s was taken where the option is refused)."""
        _known_name(self.mode, "parameter mode", tuple(MODES))
        if not (math.isfinite(self.speed) and MIN_SPEED <= self.speed <= 1.0 / MIN_SPEED):
            # A factor of 1e-12 made a step's wait too long for the clock (an internal error).
            raise InvalidArgumentError(
                f"expected parameter speed to be a factor from {MIN_SPEED:g} to "
                f"{1.0 / MIN_SPEED:g}; found {_shown(self.speed)}"
            )
        for name in ("duration", "command_period", "command_deadline", "idle_timeout"):
            seconds = getattr(self, name)
            if math.isfinite(seconds) and seconds > MAX_SETTING_SECONDS:
                raise InvalidArgumentError(
                    f"expected parameter {name} to be at most {MAX_SETTING_SECONDS:g} seconds "
                    f"(0: none); found {_shown(seconds)}"
                )
        if not (math.isfinite(self.duration) and self.duration >= 0.0):
            raise InvalidArgumentError(
                f"expected parameter duration to be seconds >= 0 (0: no limit); "
                f"found {_shown(self.duration)}"
            )
        if not (math.isfinite(self.command_period) and self.command_period >= 0.0):
            raise InvalidArgumentError(
                "expected parameter command_period to be seconds >= 0 (0: a step per command); "
                f"found {_shown(self.command_period)}"
            )
        if not (math.isfinite(self.command_deadline) and self.command_deadline >= 0.0):
            raise InvalidArgumentError(
                "expected parameter command_deadline to be seconds >= 0 (0: wait for each "
                f"command); found {_shown(self.command_deadline)}"
            )
        if self.command_deadline and self.mode != "lockstep":
            raise InvalidArgumentError(
                "expected parameter command_deadline with mode lockstep (in realtime mode time "
                f"moves whether or not a command comes); found mode {_shown(self.mode)}"
            )
        if self.command_period and self.mode != "lockstep":
            raise InvalidArgumentError(
                "expected parameter command_period with mode lockstep (in realtime mode a "
                f"rospy.Rate on simulated time runs as it is); found mode {_shown(self.mode)}"
            )
        if not 0 <= self.seed < 2**64:
            raise InvalidArgumentError(
                f"expected parameter seed in [0, 2^64); found {_shown(self.seed)}"
            )
        if not (math.isfinite(self.idle_timeout) and self.idle_timeout >= 0.0):
            raise InvalidArgumentError(
                "expected parameter idle_timeout to be seconds >= 0 (0: never give up); "
                f"found {_shown(self.idle_timeout)}"
            )


def xml_rpc_value(value: Any) -> Any:
    """``value`` as the parameter server can hold it, to write a setting back: an integer beyond
    XML-RPC's 32 bits (a seed of 3e9) as its digits, which the bridge reads back as the number;
    None for a text XML cannot carry (a file name with a control character: left unwritten).
    Written as they were, both ended the bridge in an internal error."""
    if isinstance(value, int) and not isinstance(value, bool) and not -(2**31) <= value < 2**31:
        return str(value)
    if isinstance(value, str) and any(
        (ord(c) < 0x20 and c not in "\t\n\r") or 0xD800 <= ord(c) <= 0xDFFF or c in "\ufffe\uffff"
        for c in value
    ):
        return None
    return value


def _convert(name: str, value: Any, kind: type) -> Any:
    """Converts a parameter value read from the ROS parameter server to the field's type (a
    ``true`` given for a number is refused: it was seed 1)."""
    if kind in (int, float) and isinstance(value, bool):
        raise InvalidArgumentError(
            f"expected parameter {name} to be a {kind.__name__}; found {_shown(value)} (a bool)"
        )
    try:
        if kind is bool:
            if isinstance(value, str):
                if value.strip().lower() in ("true", "1", "yes"):
                    return True
                if value.strip().lower() in ("false", "0", "no"):
                    return False
                raise ValueError(value)
            if isinstance(value, bool) or value in (0, 1):
                return bool(value)
            raise ValueError(value)  # 7 was noise on, as any number but 0
        if kind is int and isinstance(value, float) and not value.is_integer():
            raise ValueError(value)
        return kind(value)
    except (TypeError, ValueError):
        raise InvalidArgumentError(
            f"expected parameter {name} to be a {kind.__name__}; found {_shown(value)}"
        ) from None


def resolve_settings(rospy: Any, options: dict[str, Any]) -> BridgeSettings:
    """Reads the settings: command-line options, else private ROS parameters, else defaults."""
    defaults = BridgeSettings()
    values: dict[str, Any] = {}
    for field in fields(BridgeSettings):
        value = options.get(field.name)
        if value is None:
            value = rospy.get_param("~" + field.name, getattr(defaults, field.name))
        values[field.name] = _convert(field.name, value, type(getattr(defaults, field.name)))
    settings = BridgeSettings(**values)
    settings.validate()
    return settings


class Bridge:
    """Publishes a simulator's state and steps it on commands; see the module's description."""

    def __init__(
        self, ros: Any, simulator: Simulator, settings: BridgeSettings, stop: threading.Event
    ) -> None:
        rospy = ros.rospy
        self.ros = ros
        self.simulator = simulator
        self.settings = settings
        self.stop = stop
        self.lockstep = settings.mode == "lockstep"
        self.max_wheel_speed = simulator.robot.max_wheel_speed
        self.commands = 0
        self.held = topics.HeldCommand()
        self.wheel_speeds = (0.0, 0.0)
        self.first_command_at: float | None = None
        #: Lockstep: control steps ``/clock`` ran on its own before the first command; every
        #: stamp after them is that many steps later than the simulator's time.
        self.idle_steps = 0
        self.idle_tick_at = math.inf
        #: Lockstep: :attr:`idle_steps` when ``/clock`` started running on its own (``None``:
        #: it is not running).
        self._idle_since: int | None = None
        self.goal = simulator.world.goal
        #: The control step after which the robot was first inside the goal disc, if it was.
        self.goal_step: int | None = None
        self._lock = threading.Lock()
        #: Lockstep: when a state that went unanswered goes out again.
        self.unanswered = UnansweredState()
        #: Lockstep: how long each command holds (``command_period``); a ``rospy.Rate`` made at
        #: the reset state counts from its stamp.
        self.hold = TimerHold(
            settings.command_period,
            simulator.control_step_ms / 1000.0,
            origin_ns=stamp_nanoseconds(0.0),
        )
        #: Lockstep: when the bridge steps without a command (``command_deadline``).
        self.deadline = CommandDeadline(
            settings.command_deadline, simulator.control_step_ms / 1000.0
        )
        #: The last state as it went out: each publisher with its message.
        self.last_state: list[tuple[Any, Any]] = []
        #: Lockstep: when the last goal came and how many commands the bridge had taken then.
        self._goal_since: tuple[float, int] | None = None
        self._goals_answered = 0
        self.bag = BagWriter(ros, settings.bag) if settings.bag else None
        #: When a bridge nobody drives gives up (``idle_timeout``).
        self.idle = IdleTimeout(settings.idle_timeout, time.monotonic())
        #: Lockstep: the state topics' subscriptions that connected and have not had the state.
        self.late = LateConnections(graph=lambda: topics_of_nodes(ros), note=rospy.loginfo)
        self._sending_again = False
        self._sensors_layout = self._layout(topics.sensor_names(simulator))
        self._pose_layout = self._layout(["x", "y", "yaw", "time"])
        # Latched: a subscriber that connects late still receives the state awaiting a command
        # (and a recorder on simulated time, which waits for a first /clock, can start).
        self.clock_publisher = self._publisher(topics.CLOCK_TOPIC, ros.Clock)
        self.pose_publisher = self._publisher(topics.POSE_TOPIC, ros.Float64MultiArray)
        self.sensors_publisher = self._publisher(topics.SENSORS_TOPIC, ros.Float64MultiArray)
        self.sensor_data_publisher = None
        if topics.has_sharp_sensors(simulator):
            names = [f"{name} cm" for name in simulator.robot.distance_sensor_names]
            self._sensor_data_layout = self._layout([*names, "checkpoint"])
            self.sensor_data_publisher = self._publisher(
                topics.SENSOR_DATA_TOPIC, ros.Float64MultiArray
            )
        self.standard = StandardPublishers(ros, simulator, self._publisher)
        #: The topics of the sensors' readings: a late subscription gets them after the motion.
        self.sensing = {
            made.resolved_name
            for made in [
                self.sensors_publisher,
                self.sensor_data_publisher,
                *self.standard.range_publishers,
                self.standard.scan_publisher,
            ]
            if made is not None
        }
        # Handed over to every connection, one made as the publishers were advertised too.
        self.late.hold_the_reset_state(self.publish_state)
        self.unanswered.went_out(time.monotonic())
        # No queue limit: in lockstep every command is one step and none may be dropped.
        self.command_subscribers = [
            rospy.Subscriber(
                topics.MOTOR_TOPIC, ros.Float64MultiArray, self.on_motor, tcp_nodelay=True
            ),
            rospy.Subscriber(topics.ACTION_TOPIC, ros.String, self.on_action, tcp_nodelay=True),
            rospy.Subscriber(standard.CMD_VEL_TOPIC, ros.Twist, self.on_cmd_vel, tcp_nodelay=True),
        ]
        self.goal_subscriber = rospy.Subscriber(GOAL_TOPIC, ros.PoseStamped, self.on_goal)
        #: ``/gazebo/reset_simulation`` and ``/gazebo/reset_world`` (``std_srvs/Empty``), as
        #: Gazebo's node offers them, and Stage's ``/reset_positions`` (:mod:`mazesim.ros.resets`).
        self.resets = EpisodeResets(simulator)
        self.reset_services = [
            rospy.Service(
                service_name(kind, ros1=True),
                ros.Empty,
                functools.partial(self.on_reset, kind),
            )
            for kind in RESETS
        ]

    def _publisher(self, topic: str, message_class: Any) -> Any:
        return state_publisher(self.ros, topic, message_class, self.lockstep, self.late, self._sent)

    def _sent(self, sent: tuple[Any, Any], on_the_wire: bool = True) -> None:
        """Notes a message that went out (publisher, message): in the last state and the bag.
        ``on_the_wire``: sent to the subscriptions (not kept back, as ``/tf`` at a stamp it
        went out with)."""
        self.last_state.append(sent)
        if on_the_wire:
            self.late.published(sent[0].resolved_name)
        if self.bag is not None and not self._sending_again:
            self.bag.write(sent[0].resolved_name, sent[1])

    def _layout(self, labels: list[str]) -> Any:
        layout = self.ros.Float64MultiArray().layout
        size = len(labels)
        dimension = self.ros.MultiArrayDimension(label=",".join(labels), size=size, stride=size)
        layout.dim = [dimension]
        return layout

    def _array(self, layout: Any, values: list[float]) -> Any:
        return self.ros.Float64MultiArray(layout=layout, data=values)

    def publish_state(self) -> None:
        """Publishes ``/clock``, ``pose``, ``sensors``, ``sensor_data`` and the standard messages
        (``odom``, ``/tf``, one Range per distance sensor) for the current step."""
        simulator = self.simulator
        self.last_state.clear()
        clock_time = self._clock_time()
        self.clock_publisher.publish(self.ros.Clock(clock=clock_time))
        self.pose_publisher.publish(self._array(self._pose_layout, topics.pose_values(simulator)))
        self.sensors_publisher.publish(
            self._array(self._sensors_layout, topics.sensors_values(simulator))
        )
        if self.sensor_data_publisher is not None:
            self.sensor_data_publisher.publish(
                self._array(self._sensor_data_layout, topics.sensor_data_values(simulator))
            )
        self.standard.publish(clock_time)

    def _clock_time(self) -> Any:
        """The ROS time of the current step: the simulator's, plus the steps ``/clock`` ran on
        its own before the first command (see :meth:`tick_idle_clock`)."""
        nanoseconds = self._stamp()
        return self.ros.rospy.Time(nanoseconds // 10**9, nanoseconds % 10**9)

    def _stamp(self) -> int:
        """The current step's stamp in nanoseconds (1 ns before the first step)."""
        control_step_s = self.simulator.control_step_ms / 1000.0
        return stamp_nanoseconds(self.simulator.time + self.idle_steps * control_step_s)

    def tick_idle_clock(self) -> float:
        """Lockstep: once a state sent again has gone unanswered for ``IDLE_CLOCK_AFTER_S``,
        ``/clock`` runs on its own in real time, one control step at a time, nothing else
        published, until a command comes. Before the first command the robot stands still: a
        controller that waits for simulated time before it starts (``rospy.sleep`` or
        ``rospy.Rate`` with ``/use_sim_time``, as ``teleop_twist_keyboard`` does while it looks
        for a subscriber) can start. Once stepping, a controller that waits for simulated time
        inside a callback (tf2's ``lookup_transform`` with a timeout, whose wait sleeps on a
        ``rospy.Rate`` of simulated time, when the state's ``/tf`` came after its ``scan``) gets
        it. The simulator does not step meanwhile: the run stays the in-process run with the same
        commands, step for step and reading for reading, its stamps later by the steps the clock
        ran (:attr:`idle_steps`, logged at the command and at the end). Returns the seconds until
        the next tick (``inf``: none due)."""
        with self._lock:
            if self.stop.is_set():
                return math.inf
            now = time.monotonic()
            if now < self.idle_tick_at:
                return self.idle_tick_at - now
            if self._idle_since is None:
                self._idle_since = self.idle_steps
                if self.commands:
                    self.ros.rospy.logwarn(
                        "lockstep: step %d's state, sent again, went unanswered; /clock now runs "
                        "on its own in real time, the simulation waiting, until a command comes "
                        "(a controller that waits for simulated time inside a callback, as "
                        "tf2's lookup_transform with a timeout does, can go on)",
                        self.simulator.steps,
                    )
                else:
                    self.ros.rospy.logwarn(
                        "lockstep: the reset state sent again went unanswered; /clock now runs "
                        "on its own in real time, the robot standing still, until the first "
                        "command (a controller that waits for simulated time before its first "
                        "command can start; one that commands at a rospy.Rate slower than the "
                        "control step: run the bridge with --command-period, the rate's period)"
                    )
                    self.hold.start(self._stamp())  # the first tick of a timer on command_period
            self.idle_steps += 1
            self.clock_publisher.publish(self.ros.Clock(clock=self._clock_time()))
            self.idle_tick_at += self.simulator.control_step_ms / 1000.0
            if not self.commands and self.hold.active and not self.hold.holds(self._stamp()):
                # At the controller's tick: its timer fires now (rospy.Timer made in its
                # constructor); the clock waits there for its command before it goes on, so
                # the command comes at this stamp whatever the load, and the run is the same.
                self.idle_tick_at += IDLE_CLOCK_AFTER_S
                self.hold.start(self._stamp())
            return max(self.idle_tick_at - time.monotonic(), 0.0)

    def _stop_idle_clock(self) -> None:
        """A command came: ``/clock`` stops running on its own; says how far it ran, if it did.
        Call with the lock held."""
        self.idle_tick_at = math.inf
        if self._idle_since is None:
            return
        ran, self._idle_since = self.idle_steps - self._idle_since, None
        self.ros.rospy.logwarn(
            "lockstep: the command came after /clock ran %d steps on its own; from here every "
            "stamp is %d steps later than the in-process run's, whose steps and readings this "
            "run keeps",
            ran,
            self.idle_steps,
        )

    def _finished(self) -> bool:
        """Notes the goal after a step; whether the bridge is done (duration, or goal reached)."""
        simulator = self.simulator
        if self.goal is not None and self.goal_step is None:
            x, y, _ = simulator.pose
            goal_x, goal_y, radius = self.goal
            if math.hypot(x - goal_x, y - goal_y) <= radius:
                self.goal_step = simulator.steps
                self.ros.rospy.loginfo(
                    "reached the goal of %s at step %d (%.3f s simulated), at x %.4f m, y %.4f m",
                    simulator.world.name,
                    simulator.steps,
                    simulator.time,
                    x,
                    y,
                )
        if self.settings.stop_at_goal and self.goal_step is not None:
            return True
        duration = self.settings.duration
        return duration > 0.0 and simulator.time >= duration - 1e-9

    def on_reset(self, kind: str, request: Any) -> Any:
        """Answers a call of a reset service: puts the simulator back
        (:class:`~mazesim.ros.resets.EpisodeResets`), the wheels at rest, and publishes the state
        after the reset (in lockstep the state the next command answers) before it answers."""
        with self._lock:
            self.resets.apply(kind)
            if kind == RESET_SIMULATION:
                self.idle_steps = 0
            self.idle_tick_at, self._idle_since = math.inf, None
            self.wheel_speeds = self.held.latest = (0.0, 0.0)
            self.hold.start(self._stamp())  # no tick waits for a command across a reset
            self.standard.previous = None
            self.standard.previous_time = self.simulator.time
            self.ros.rospy.loginfo(
                "%s: %s (step %d, %.3f s simulated); publishing the state after it",
                service_name(kind, ros1=True),
                RESETS[kind],
                self.simulator.steps,
                self.simulator.time,
            )
            self.publish_state()
            self.unanswered.went_out(time.monotonic())
            self.deadline.commanded(time.monotonic())
        return self.ros.EmptyResponse()

    def on_motor(self, message: Any) -> None:
        """Handles a ``motor`` message: ``[left, right]`` in rad/s."""
        self._command_from("motor", message, lambda: topics.motor_command(message.data))

    def on_action(self, message: Any) -> None:
        """Handles an ``action`` message: a primitive action code."""
        self._command_from(
            "action", message, lambda: wheel_speeds(message.data, self.max_wheel_speed)
        )

    def on_goal(self, message: Any) -> None:
        """Notes that a goal came on ``move_base_simple/goal`` (see :meth:`answer_goal`)."""
        with self._lock:
            self._goal_since = (time.monotonic(), self.commands)

    def answer_goal(self) -> None:
        """Lockstep: when a goal came on ``move_base_simple/goal`` (rviz's "2D Nav Goal") and no
        command has come ``GOAL_GRACE_S`` later, publishes the state again, as the ROS 2 bridge
        does after a goal on ``/goal_pose``: a node that drives only once it has a goal ignored
        the states before it and waits for the next, and the bridge for its command (it waited
        for the state sent again after ``RESEND_S``). Before the first command the reset state
        at the current stamp, once stepping the last state as it went out; a node that answers
        at once gets nothing twice. Logs it the first time."""
        with self._lock:
            if self._goal_since is None or self.stop.is_set():
                return
            since, commands = self._goal_since
            if self.commands != commands:
                self._goal_since = None
                return
            if time.monotonic() - since < GOAL_GRACE_S:
                return
            self._goal_since = None
            self._goals_answered += 1
            if self._goals_answered == 1:
                self.ros.rospy.logwarn(
                    "lockstep: a goal came on %s and no command in %g s; publishing the state "
                    "again (step %d), for a node that drives once it has a goal",
                    self.goal_subscriber.resolved_name,
                    GOAL_GRACE_S,
                    self.simulator.steps,
                )
            self._send_state_again()
            self.unanswered.went_out(time.monotonic())

    def on_cmd_vel(self, message: Any) -> None:
        """Handles a ``cmd_vel`` twist: ``linear.x`` in m/s, ``angular.z`` in rad/s."""
        self._command_from(
            standard.CMD_VEL_TOPIC,
            message,
            lambda: standard.twist_wheel_speeds(
                message.linear.x, message.angular.z, self.simulator.robot
            ),
        )

    def _command_from(
        self, topic: str, message: Any, read: Callable[[], tuple[float, float]]
    ) -> None:
        """Applies the wheel speeds ``read`` gives (from ``message``, taken on ``topic``); a bad
        message is logged and keeps the wheel speeds of the last command accepted."""
        with self._lock:
            (left, right), refused = self.held.take(read)
        if refused:
            self.ros.rospy.logwarn(
                "ignored a bad %s message: %s; the robot keeps its wheel speeds for that step",
                topic,
                refused,
            )
        self.command(left, right, taken=(self.ros.rospy.resolve_name(topic), message))

    def command(self, left: float, right: float, taken: tuple[str, Any] | None = None) -> None:
        """Applies wheel speeds: in lockstep, steps once and publishes; else holds them.
        ``taken``: the topic and message they came from, for the bag."""
        with self._lock:
            if self.stop.is_set():
                return
            if taken is not None and self.bag is not None:
                self.bag.write(*taken)
            if self.first_command_at is None:
                self.first_command_at = time.monotonic()
            self._stop_idle_clock()
            self.commands += 1
            self.wheel_speeds = (left, right)
            if not self.lockstep:
                return
            # One step, and with command_period the further steps the command holds until the
            # clock reaches the controller's next tick (TimerHold, the rule of both bridges).
            self.hold.start(self._stamp())
            self._step_held(left, right)
            self.deadline.commanded(time.monotonic())

    def _step_held(self, left: float, right: float) -> None:
        """One step, and with ``command_period`` the further steps the command holds until the
        clock reaches the controller's next tick; then waits for its next command there
        (:class:`~mazesim.ros.lockstep.TimerHold`). Call with the lock held."""
        while not self.stop.is_set():  # Ctrl-C ends a hold of 1e6 s too
            self.simulator.step(left, right)
            self.publish_state()
            if self._finished():
                self.stop.set()
                break
            if not self.hold.holds(self._stamp()):
                self.hold.ended(time.monotonic())
                break
        self.unanswered.went_out(time.monotonic())

    def step_on_skipped_tick(self) -> float:
        """Lockstep with ``command_period``, once a command has been stepped: when no command
        has come ``SKIPPED_TICK_S`` after a hold ended at the controller's tick, the controller
        let that tick go (a node pairing each ``scan`` with the ``/tf`` of its stamp found the
        transform not come yet, the two arriving on connections of their own); holds the last
        command on to its next tick, as a simulator whose clock runs on would, so that its timer
        fires again (:class:`~mazesim.ros.lockstep.TimerHold`). Returns the seconds until such a
        tick is due (``math.inf``: none)."""
        with self._lock:
            now = time.monotonic()
            if self.stop.is_set() or not self.hold.let_go(now):
                return self.hold.wait(now)
            notice = self.hold.holding_on()
            if notice is not None:
                self.ros.rospy.logwarn(notice)
            self.hold.start(self._stamp())
            self._step_held(*self.wheel_speeds)
            return self.hold.wait(time.monotonic())

    def step_on_deadline(self) -> float:
        """Lockstep with ``command_deadline``, once a command has been stepped: when none has
        come within the deadline after a state, one step with the last command held, and so on
        in real time until a command comes (:class:`~mazesim.ros.lockstep.CommandDeadline`), so
        that a controller waiting for simulated time the bridge cannot foresee gets it. Returns
        the seconds until the next such step is due (``math.inf``: none)."""
        with self._lock:
            now = time.monotonic()
            if self.stop.is_set() or not self.deadline.due(now):
                return self.deadline.wait(now)
            notice = self.deadline.stepped(now)
            if notice is not None:
                self.ros.rospy.logwarn(notice)
            self.simulator.step(*self.wheel_speeds)
            self.publish_state()
            self.unanswered.went_out(now)
            if self._finished():
                self.stop.set()
            return self.deadline.wait(time.monotonic())

    def _resend_unanswered(self) -> None:
        """Lockstep: when no command has come ``RESEND_S`` after a state went out while a
        publisher of a command topic is connected (:class:`~mazesim.ros.lockstep.UnansweredState`,
        the rule of both bridges), publishes it again: before the first command the reset state
        (a controller whose first command went out before the bridge listened, or that answers
        only from its second message, gets another; if that goes unanswered too, ``/clock`` runs
        on its own, see :meth:`tick_idle_clock`); once stepping, the last state as it went out
        (same messages, same stamps): a controller that let one state go unanswered gets it
        again, and the run stays the in-process run step for step. Logs it the first time.
        Never while subscriptions that connected late wait for the state (it goes to them from
        :class:`LateConnections`, after which the wait starts again)."""
        with self._lock:
            if self.stop.is_set() or self.late.pending:
                return
            if not self.unanswered.waited_long(time.monotonic()):
                return
            connected = [sub for sub in self.command_subscribers if sub.get_num_connections() > 0]
            if not connected:
                return
            stepped = self.commands > 0
            notice = self.unanswered.resending(
                stepped,
                self.simulator.steps,
                connected[0].resolved_name,
                "run the bridge with --command-period (the rate's period) or in mode realtime",
            )
            if notice is not None:
                self.ros.rospy.logwarn(notice)
            self._send_state_again()
            if self.idle_tick_at == math.inf:
                self.idle_tick_at = time.monotonic() + IDLE_CLOCK_AFTER_S

    def _send_state_again(self) -> None:
        """Sends the state again (a state unanswered, a goal come): before the first command the
        reset state, stamped anew if ``/clock`` ran on its own meanwhile; once stepping, the last
        state as it went out. Never ``/tf`` at a stamp it already went out with: tf2 keeps
        transforms by stamp and warns of the same ones again (``TF_REPEATED_DATA``); a
        subscription that connected since gets them from :class:`LateConnections`. Never a
        ``/clock`` older than the one the clock ran on to. Call with the lock held."""
        if not self.commands:
            self._sending_again = True  # the bag holds each state once
            try:
                self.publish_state()
            finally:
                self._sending_again = False
            return
        for made, message in standard.state_to_send_again(self.last_state):
            if made is self.clock_publisher.made and self._idle_since is not None:
                continue
            made.publish(message)
            self.late.published(made.resolved_name)

    def give_up_when_idle(self) -> bool:
        """Stops the bridge once no command has come and no publisher of a command topic has
        been connected for ``idle_timeout`` seconds (:class:`~mazesim.ros.lockstep.IdleTimeout`),
        saying so; returns whether it did."""
        with self._lock:
            connected = any(sub.get_num_connections() > 0 for sub in self.command_subscribers)
            if not self.idle.look(time.monotonic(), self.commands, connected):
                return False
            self.stop.set()
        self.ros.rospy.logerr(
            "mazesim bridge: %s", self.idle.message("--idle-timeout, or ~idle_timeout,")
        )
        return True

    def finish(self) -> tuple[int, float]:
        """Stops stepping (later commands are ignored), finishes the bag if there is one and
        returns the steps and simulated time."""
        with self._lock:
            self.stop.set()
            if self.bag is not None:
                self.bag.close()
            return self.simulator.steps, self.simulator.time

    def run(self) -> None:
        """Runs until a signal, ROS shutdown or the end of ``duration``."""
        rospy = self.ros.rospy
        if self.lockstep:
            started = time.monotonic()
            wait = 0.1
            while not self.stop.wait(min(wait, 0.1)) and not rospy.is_shutdown():
                if self.commands == 0 and time.monotonic() - started > IDLE_WARNING_S:
                    rospy.logwarn(
                        "lockstep: waiting for a command on %s, %s or %s (one control step "
                        "each); once the reset state sent again goes unanswered, /clock runs on "
                        "its own until the first command, for a controller that waits for "
                        "simulated time (rospy.sleep or rospy.Rate with /use_sim_time) first",
                        rospy.resolve_name(topics.MOTOR_TOPIC),
                        rospy.resolve_name(topics.ACTION_TOPIC),
                        rospy.resolve_name(standard.CMD_VEL_TOPIC),
                    )
                    started = math.inf
                with self._lock:
                    state = [(made.resolved_name, sent) for made, sent in self.last_state]
                    writer = any(sub.get_num_connections() for sub in self.command_subscribers)
                    writers = functools.partial(writers_connected, self.command_subscribers)
                    if self.late.hand_over(state, self.sensing, writer, writers=writers):
                        self.unanswered.went_out(time.monotonic())  # to those connections
                if self.give_up_when_idle():
                    return
                self._resend_unanswered()
                self.answer_goal()
                wait = min(
                    self.tick_idle_clock(), self.step_on_deadline(), self.step_on_skipped_tick()
                )
            return
        pace = RealTimePace(
            self.simulator.control_step_ms / 1000.0 / self.settings.speed, time.monotonic()
        )
        while not self.stop.is_set() and not rospy.is_shutdown():
            if self.give_up_when_idle():
                return
            with self._lock:
                self.simulator.step(*self.wheel_speeds)
                self.publish_state()
                if self._finished():
                    break
            self.stop.wait(pace.stepped(time.monotonic()))


def refuse_several_robots(world: World) -> None:
    """Refuses a world of several robots for the ROS 1 demo, which drives one robot (the bridge
    serves several, each in its namespace: :mod:`mazesim.ros.several`).

    Raises:
        InvalidArgumentError: The world lists more than one robot.
    """
    robots = world.robots
    if len(robots) > 1:
        names = ", ".join(str(robot["name"]) for robot in robots)
        raise InvalidArgumentError(
            f"the ROS 1 demo drives one robot; world {_shown(world.name)} holds {len(robots)} "
            f"({names}): run 'mazesim ros bridge', which serves each robot in its own namespace, "
            "with a controller per robot, or give a world of one robot"
        )


def run_bridge(
    options: dict[str, Any], remappings: list[str], node_name: str = "mazesim_bridge"
) -> int:
    """Runs the bridge node until it is stopped.

    Args:
        options: Settings given on the command line (``None`` values fall back to the private
            ROS parameters, then to the defaults of :class:`BridgeSettings`).
        remappings: ROS remapping arguments such as ``sensors:=/robot1/sensors`` or ``_seed:=3``.
        node_name: The node's name unless a ``__name:=`` remapping overrides it.

    Returns:
        The exit code, 0 once the bridge has stopped, ``IDLE_EXIT_STATUS`` when it gave up with
        no node driving it (``idle_timeout``).
    """
    ros, stop = start_node("mazesim-ros-bridge", node_name, remappings, time_source=True)
    rospy = ros.rospy
    try:
        settings = resolve_settings(rospy, options)
        for field in fields(BridgeSettings):
            echoed = xml_rpc_value(getattr(settings, field.name))
            if echoed is not None:
                rospy.set_param("~" + field.name, echoed)
        world = mazesim.load_world(settings.world)
        several = len(world.robots) > 1
        if several:
            refuse_single_robot_settings(settings, world.name)
        elif settings.stop_at_goal and world.goal is None:
            raise InvalidArgumentError(
                f"parameter stop_at_goal is true but world {_shown(world.name)} has no goal"
            )
        simulator = Simulator(world, robot=settings.robot, seed=settings.seed, noise=settings.noise)
        # Before the bridge listens for commands: a controller that sees it connected finds it.
        rospy.set_param(topics.CONTROL_STEP_PARAM, simulator.control_step_ms)
        bridge: Bridge | SeveralRobotsBridge = (
            SeveralRobotsBridge(ros, simulator, settings, stop)
            if several
            else Bridge(ros, simulator, settings, stop)
        )
    except MazesimError as error:
        rospy.signal_shutdown(f"bad settings: {error}")
        raise
    if isinstance(bridge, SeveralRobotsBridge):
        return _run_several(ros, bridge)
    robot = simulator.robot
    rospy.loginfo(
        "mazesim bridge: world %s, robot %s, seed %d, %s%s; sensors = %s",
        world.name,
        robot.name,
        settings.seed,
        settings.mode,
        "" if bridge.lockstep else f" x{settings.speed:g}",
        ", ".join(topics.sensor_names(simulator)),
    )
    started = time.monotonic()
    try:
        bridge.run()
    finally:
        steps, simulated = bridge.finish()
        # Lockstep counts from the first command: the wait for a controller is not stepping.
        since = bridge.first_command_at if bridge.lockstep else started
        elapsed = time.monotonic() - since if since is not None else 0.0
        rate = steps / elapsed if elapsed > 0 else 0.0
        if bridge.goal is None:
            goal = "no goal in this world"
        elif bridge.goal_step is None:
            goal = "goal not reached"
        else:
            goal = f"goal reached at step {bridge.goal_step}"
        rospy.loginfo(
            "mazesim bridge stopped: %d steps (%.2f s simulated) in %.2f s of stepping, "
            "%.0f steps/s; %s; %d bad messages ignored (their steps kept the wheel speeds); "
            "/clock ran %d steps on its own while no command came; %d steps without a "
            "command (command_deadline); %d ticks let go without a command (command_period)",
            steps,
            simulated,
            elapsed,
            rate,
            goal,
            bridge.held.refused,
            bridge.idle_steps,
            bridge.deadline.steps,
            bridge.hold.skipped,
        )
        rospy.signal_shutdown("mazesim bridge stopped")
    return IDLE_EXIT_STATUS if bridge.idle.expired else 0


def _run_several(ros: Any, bridge: SeveralRobotsBridge) -> int:
    """Runs the bridge on a world of several robots (:mod:`mazesim.ros.several`)."""
    rospy = ros.rospy
    settings = bridge.settings
    rospy.loginfo(
        "mazesim bridge: world %s, %d robots (%s), seed %d, %s%s",
        bridge.simulator.world.name,
        len(bridge.robots),
        ", ".join(robot.namespace for robot in bridge.robots),
        settings.seed,
        settings.mode,
        "" if bridge.lockstep else f" x{settings.speed:g}",
    )
    try:
        bridge.run()
    finally:
        steps, simulated = bridge.finish()
        rospy.loginfo(
            "mazesim bridge stopped: %d steps (%.2f s simulated) of %d robots; %d bad messages "
            "ignored (their steps kept the wheel speeds)",
            steps,
            simulated,
            len(bridge.robots),
            sum(robot.held.refused for robot in bridge.robots),
        )
        rospy.signal_shutdown("mazesim bridge stopped")
    return IDLE_EXIT_STATUS if bridge.idle.expired else 0
