"""The ROS 1 bridge on a world of several robots: each robot in a namespace of its own.

As the e-puck's ROS 1 driver runs several robots (``multi_epuck.launch`` starts each robot's nodes
in ``<group ns="epuck_robot_0">``), the bridge serves robot ``west`` of the world as
``/west/sensors``, ``/west/pose`` and ``/west/sensor_data`` (robots with Sharp sensors), and reads
its commands on ``/west/motor``, ``/west/action`` and ``/west/cmd_vel``, in the layouts of
:mod:`mazesim.ros.topics` and :mod:`mazesim.ros.standard`; ``/clock`` is one for all, and so is
``control_step_ms``. Its standard messages (:class:`mazesim.ros.standard.StandardPublishers`) are
``/west/odom``, ``/west/ps0``... and ``/west/scan``, in frames named after the namespace
(:func:`mazesim.ros.robots.frame_prefix`: ``west/odom``, ``west/base_link``, ``west/ps0``...), as
the ROS 2 bridge's ``--frame-prefix`` names them; every robot's ``odom`` -> ``base_link`` goes on
the one ``/tf`` in one message per step, and every robot's static frames (``map`` -> ``west/odom``
among them) in the one latched ``/tf_static`` message; ``map`` is one for all. The namespaces are
the ROS 2 bridge's (:func:`mazesim.ros.robots.robot_namespaces`: the robot's name, with what a ROS
name may not hold replaced by ``_``).

In ``lockstep`` the world steps once every robot whose command topics have a publisher connected
has sent its command for the step (:func:`mazesim.ros.robots.next_round`, the rule of both
bridges): a robot nobody drives keeps its wheel speeds (at first, none), and a robot that sends
two commands before the others send one has the second stepped in the next step. A run is the
in-process run of ``Simulator.step_robots`` with the same commands, whatever the order in which
they arrive. When no step has come ``RESEND_S`` seconds after a state went out while a command
publisher is connected, every robot's state goes out again, ``/tf`` aside (it went out at that
stamp already: :func:`mazesim.ros.standard.state_to_send_again`, the one-robot bridge's rule); a
controller that commanded before the bridge listened gets another. A subscription that connects
after the state went out gets it once, in the order it went out, the motion first, when the
node's subscriptions and command publisher have connected (the one-robot bridge's rule,
:class:`mazesim.ros.latched.LateConnections`), ``/tf`` aside (on rospy's latch: a tf2 listener
connecting late has the last transforms at once); the wait before the state goes out again
counts from then. rospy's own latch gave a node that subscribes ``scan`` before ``odom`` the
scan before any odometry, and a node that connected about 5 s after the bridge started had the
state sent again as it connected: such a node of robot ``west`` never ran (a test). In
``realtime`` the world steps on its own with every robot's last wheel speeds.

The single-robot bridge's ``command_period``, ``command_deadline``, ``stop_at_goal`` and ``bag`` and
the reset services are not offered on several robots: the bridge refuses those settings rather than
ignore them.
"""

from __future__ import annotations

import functools
import threading
import time
from collections import deque
from collections.abc import Callable
from typing import Any

from mazesim._core import Simulator
from mazesim.actions import wheel_speeds
from mazesim.errors import InvalidArgumentError, _shown
from mazesim.ros import standard, topics
from mazesim.ros._ros import publisher, topics_of_nodes, writers_connected
from mazesim.ros.latched import LateConnections, Remembered, state_publisher
from mazesim.ros.lockstep import IdleTimeout, RealTimePace, UnansweredState, stamp_nanoseconds
from mazesim.ros.robots import RobotOf, frame_prefix, robot_namespaces, step_rounds

__all__ = ["RobotChannel", "SeveralRobotsBridge", "refuse_single_robot_settings"]

#: Settings of the single-robot bridge a world of several robots does not take, with their
#: value that means "off".
_SINGLE_ROBOT_SETTINGS = {
    "command_period": 0.0,
    "command_deadline": 0.0,
    "stop_at_goal": False,
    "bag": "",
}


def refuse_single_robot_settings(settings: Any, world_name: str) -> None:
    """Refuses the settings only the single-robot bridge serves.

    Raises:
        InvalidArgumentError: One of them is set.
    """
    for name, off in _SINGLE_ROBOT_SETTINGS.items():
        value = getattr(settings, name)
        if value != off:
            raise InvalidArgumentError(
                f"expected parameter {name} left out on world {_shown(world_name)} of several "
                f"robots (the ROS 1 bridge serves it on a world of one robot); found "
                f"{_shown(value)}"
            )


class RobotChannel:
    """One robot's topics: its state publishers and command subscribers, in its namespace."""

    def __init__(
        self,
        bridge: SeveralRobotsBridge,
        view: RobotOf,
        namespace: str,
    ) -> None:
        ros = bridge.ros
        self.view = view
        self.namespace = namespace
        self.pending: deque[tuple[float, float]] = deque()
        self.wheel_speeds = (0.0, 0.0)
        self.held = topics.HeldCommand()
        self.layouts = {
            "sensors": bridge.layout(topics.sensor_names(view)),  # type: ignore[arg-type]
            "pose": bridge.layout(["x", "y", "yaw", "time"]),
        }
        self.sensors = bridge.make_publisher(f"{namespace}/{topics.SENSORS_TOPIC}")
        self.pose = bridge.make_publisher(f"{namespace}/{topics.POSE_TOPIC}")
        self.sensor_data = None
        if topics.has_sharp_sensors(view):  # type: ignore[arg-type]
            names = [f"{name} cm" for name in view.robot.distance_sensor_names]
            self.layouts["sensor_data"] = bridge.layout([*names, "checkpoint"])
            self.sensor_data = bridge.make_publisher(f"{namespace}/{topics.SENSOR_DATA_TOPIC}")
        #: ``odom``, the Range topics and ``scan`` in the namespace, frames ``west/odom``...
        self.standard = standard.StandardPublishers(
            ros,
            view,  # type: ignore[arg-type]
            bridge.make_publisher,
            namespace,
            frame_prefix(namespace),
            transforms=False,
        )
        robot = view.robot
        # No queue limit: in lockstep every command is one step and none may be dropped.
        self.subscribers = [
            ros.rospy.Subscriber(
                f"{namespace}/{topics.MOTOR_TOPIC}",
                ros.Float64MultiArray,
                lambda message: bridge.command(
                    self, "motor", lambda: topics.motor_command(message.data)
                ),
                tcp_nodelay=True,
            ),
            ros.rospy.Subscriber(
                f"{namespace}/{topics.ACTION_TOPIC}",
                ros.String,
                lambda message: bridge.command(
                    self, "action", lambda: wheel_speeds(message.data, robot.max_wheel_speed)
                ),
                tcp_nodelay=True,
            ),
            ros.rospy.Subscriber(
                f"{namespace}/{standard.CMD_VEL_TOPIC}",
                ros.Twist,
                lambda message: bridge.command(
                    self,
                    standard.CMD_VEL_TOPIC,
                    lambda: standard.twist_wheel_speeds(message.linear.x, message.angular.z, robot),
                ),
                tcp_nodelay=True,
            ),
        ]

    def driven(self) -> bool:
        """Whether a publisher is connected to one of the robot's command topics."""
        return any(subscriber.get_num_connections() > 0 for subscriber in self.subscribers)

    def publish(self, bridge: SeveralRobotsBridge) -> list[tuple[Any, Any]]:
        """Publishes the robot's state now; returns each publisher with its message."""
        view = self.view
        sent = [
            (self.pose, bridge.array(self.layouts["pose"], topics.pose_values(view))),  # type: ignore[arg-type]
            (self.sensors, bridge.array(self.layouts["sensors"], topics.sensors_values(view))),  # type: ignore[arg-type]
        ]
        if self.sensor_data is not None:
            values = topics.sensor_data_values(view)  # type: ignore[arg-type]
            sent.append((self.sensor_data, bridge.array(self.layouts["sensor_data"], values)))
        for made, message in sent:
            made.publish(message)
        return sent

    def sensing(self) -> list[str]:
        """The topics of the robot's sensors' readings (a late subscription gets them after the
        motion)."""
        made = [self.sensors, self.sensor_data, *self.standard.range_publishers]
        made.append(self.standard.scan_publisher)
        return [one.resolved_name for one in made if one is not None]


class SeveralRobotsBridge:
    """Publishes each robot of a simulator in its namespace and steps the world on their
    commands; see the module's description."""

    def __init__(self, ros: Any, simulator: Simulator, settings: Any, stop: threading.Event):
        self.ros = ros
        self.simulator = simulator
        self.settings = settings
        self.stop = stop
        self.lockstep = settings.mode == "lockstep"
        self.commands = 0
        self.first_command_at: float | None = None
        self.goal_step: int | None = None
        self.goal = None
        self._lock = threading.Lock()
        self.unanswered = UnansweredState()
        #: When a bridge nobody drives gives up (``idle_timeout``).
        self.idle = IdleTimeout(settings.idle_timeout, time.monotonic())
        self.last_state: list[tuple[Any, Any]] = []
        #: Lockstep: the state topics' subscriptions that connected and have not had the state
        #: (the one-robot bridge's rule: once, in the order it went out).
        self.late = LateConnections(graph=lambda: topics_of_nodes(ros), note=ros.rospy.loginfo)
        self.clock_publisher = self.make_publisher(topics.CLOCK_TOPIC, ros.Clock)
        namespaces = robot_namespaces(simulator.robot_names)
        self.robots = [
            RobotChannel(self, RobotOf(simulator, index), namespace)
            for index, namespace in enumerate(namespaces)
        ]
        # Every robot's transforms in one message: a latched topic keeps only the last one.
        # On rospy's own latch, not handed over late: tf2 keeps transforms by stamp, so a
        # listener connecting late needs the last ones at once, whatever else it has had (handed
        # over with the rest, a listener whose /tf connection came after the others' hand-over
        # had the next step first and never the reset state's transforms: a lookup at its stamp
        # failed). /tf is never sent again (state_to_send_again), so nothing comes twice.
        self.tf_publisher = Remembered(
            publisher(ros, standard.TF_TOPIC, ros.TFMessage, synchronous=self.lockstep, latch=True),
            self._sent,
        )
        static = [made for robot in self.robots for made in robot.standard.static_transforms()]
        self.tf_static_publisher = ros.rospy.Publisher(
            standard.TF_STATIC_TOPIC, ros.TFMessage, queue_size=1, latch=True
        )
        self.tf_static_publisher.publish(ros.TFMessage(transforms=static))
        self.map_publisher = standard.latched_map(ros, simulator.world)
        self.sensing = {topic for robot in self.robots for topic in robot.sensing()}
        # Handed over to every connection, one made as the publishers were advertised too.
        self.late.hold_the_reset_state(self.publish_state)
        self.unanswered.went_out(time.monotonic())

    def make_publisher(self, topic: str, message_class: Any = None) -> Any:
        """A latched publisher, synchronous in lockstep (every subscriber gets every step); in
        lockstep a late subscription gets the state once, in the order it went out
        (:class:`~mazesim.ros.latched.LateConnections`). What it publishes goes in the last
        state."""
        kind = message_class if message_class is not None else self.ros.Float64MultiArray
        return state_publisher(self.ros, topic, kind, self.lockstep, self.late, self._sent)

    def _sent(self, sent: tuple[Any, Any], on_the_wire: bool = True) -> None:
        """Notes a message that went out (publisher, message) in the last state."""
        self.last_state.append(sent)
        if on_the_wire:
            self.late.published(sent[0].resolved_name)

    def layout(self, labels: list[str]) -> Any:
        layout = self.ros.Float64MultiArray().layout
        size = len(labels)
        layout.dim = [self.ros.MultiArrayDimension(label=",".join(labels), size=size, stride=size)]
        return layout

    def array(self, layout: Any, values: list[float]) -> Any:
        return self.ros.Float64MultiArray(layout=layout, data=values)

    def publish_state(self) -> None:
        """Publishes ``/clock``, every robot's standard messages, ``/tf`` with every robot's
        transform, then every robot's state, for the current step."""
        nanoseconds = stamp_nanoseconds(self.simulator.time)
        stamp = self.ros.rospy.Time(nanoseconds // 10**9, nanoseconds % 10**9)
        clock = self.ros.Clock(clock=stamp)
        self.last_state = []
        self.clock_publisher.publish(clock)
        moved = [made for robot in self.robots for made in robot.standard.publish(stamp)]
        self.tf_publisher.publish(self.ros.TFMessage(transforms=moved))
        for robot in self.robots:
            robot.publish(self)

    def command(
        self, robot: RobotChannel, topic: str, read: Callable[[], tuple[float, float]]
    ) -> None:
        """Takes one command of ``robot``; a bad one is logged and keeps its last wheel speeds
        (:class:`~mazesim.ros.topics.HeldCommand`), still one command."""
        with self._lock:
            if self.stop.is_set():
                return
            command, refused = robot.held.take(read)
            if refused:
                self.ros.rospy.logwarn(
                    "ignored a bad %s/%s message: %s; the robot keeps its wheel speeds for "
                    "that step",
                    robot.namespace,
                    topic,
                    refused,
                )
            if self.first_command_at is None:
                self.first_command_at = time.monotonic()
            self.commands += 1
            if not self.lockstep:
                robot.wheel_speeds = command
                return
            robot.pending.append(command)
            self._step_pending()

    def _step_pending(self) -> None:
        """Lockstep: steps while every driven robot has a command waiting. Call with the lock."""
        step_rounds(self.robots, self.stop, self._step)

    def _step(self) -> None:
        import numpy as np

        speeds = np.array([robot.wheel_speeds for robot in self.robots], dtype=np.float64)
        self.simulator.step_robots(speeds)
        self.publish_state()
        self.unanswered.went_out(time.monotonic())
        duration = self.settings.duration
        if duration > 0.0 and self.simulator.time >= duration - 1e-9:
            self.stop.set()

    def _resend_unanswered(self) -> None:
        """Lockstep: the state again when none answered it (see the module's description)."""
        with self._lock:
            if self.stop.is_set() or self.late.pending:
                return  # connections waiting for the state get it from LateConnections
            if not self.unanswered.waited_long(time.monotonic()):
                return
            waiting = [robot for robot in self.robots if robot.driven() and not robot.pending]
            if not waiting:
                return
            notice = self.unanswered.resending(
                self.simulator.steps > 0,
                self.simulator.steps,
                f"{waiting[0].namespace}/{topics.MOTOR_TOPIC}",
                "answer each robot's state with one command",
            )
            if notice is not None:
                self.ros.rospy.logwarn(notice)
            for made, message in standard.state_to_send_again(self.last_state):
                made.publish(message)
                self.late.published(made.resolved_name)
            self.unanswered.went_out(time.monotonic())

    def _hand_over(self) -> None:
        """Lockstep: the state to the subscriptions that connected late, once, in the order it
        went out (:class:`~mazesim.ros.latched.LateConnections`); the wait before the state goes
        out again counts from it."""
        with self._lock:
            state = [(made.resolved_name, message) for made, message in self.last_state]
            subscribers = [sub for robot in self.robots for sub in robot.subscribers]
            writer = any(robot.driven() for robot in self.robots)
            writers = functools.partial(writers_connected, subscribers)
            if self.late.hand_over(state, self.sensing, writer, writers=writers):
                self.unanswered.went_out(time.monotonic())

    def finish(self) -> tuple[int, float]:
        """Stops stepping; returns the steps and simulated time."""
        with self._lock:
            self.stop.set()
            return self.simulator.steps, self.simulator.time

    def give_up_when_idle(self) -> bool:
        """Stops the bridge once no robot has had a command and no publisher of a command topic
        has been connected for ``idle_timeout`` seconds (:class:`~mazesim.ros.lockstep.IdleTimeout`,
        the one-robot bridge's rule), saying so; returns whether it did."""
        with self._lock:
            connected = any(robot.driven() for robot in self.robots)
            if not self.idle.look(time.monotonic(), self.commands, connected):
                return False
            self.stop.set()
        self.ros.rospy.logerr(
            "mazesim bridge: %s", self.idle.message("--idle-timeout, or ~idle_timeout,")
        )
        return True

    def run(self) -> None:
        """Runs until a signal, ROS shutdown, the end of ``duration`` or ``idle_timeout``."""
        rospy = self.ros.rospy
        if self.lockstep:
            while not self.stop.wait(0.1) and not rospy.is_shutdown():
                if self.give_up_when_idle():
                    return
                self._hand_over()
                self._resend_unanswered()
            return
        pace = RealTimePace(
            self.simulator.control_step_ms / 1000.0 / self.settings.speed, time.monotonic()
        )
        while not self.stop.is_set() and not rospy.is_shutdown():
            if self.give_up_when_idle():
                return
            with self._lock:
                self._step()
            self.stop.wait(pace.stepped(time.monotonic()))
