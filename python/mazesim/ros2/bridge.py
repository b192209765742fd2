"""The ROS 2 bridge node: a simulator behind the e-puck's standard ROS 2 topics.

Lockstep (the default): each command on ``/cmd_vel``, ``/motor`` or ``/action`` advances one
control step, then the state topics go out stamped with the new simulation time, ``/clock`` last.
Before the first command the bridge publishes the reset state once (stamped 1 ns), after a writer
on one of its command topics has matched and a grace period has passed. Free-running: the bridge
steps on its own at ``speed`` (see :mod:`mazesim.ros2.clock`), with the last commanded wheel
speeds. Topics and QoS: :mod:`mazesim.ros2.state`; the page ``docs/ros2.md``.
"""

from __future__ import annotations

import dataclasses
import math
import signal
import sys
import threading
import time
from typing import Any

from mazesim._core import Simulator
from mazesim.actions import wheel_speeds
from mazesim.errors import InvalidActionError, InvalidArgumentError, MazesimError
from mazesim.ros import standard, topics
from mazesim.ros2 import cdr, network
from mazesim.ros2.bag import BagRecorder
from mazesim.ros2.clock import SIM_CONTROL_TOPIC, FreeRunning, stamp_nanoseconds
from mazesim.ros2.node import Node, Reader
from mazesim.ros2.qos import COMMAND
from mazesim.ros2.state import StateTopics

__all__ = ["BridgeSettings", "Ros2Bridge", "run_bridge"]

NODE_NAME = "mazesim_bridge"
#: Seconds between a command writer matching and the reset state going out.
READY_GRACE_S = 0.5
TWIST = "geometry_msgs/msg/Twist"
TWIST_STAMPED = "geometry_msgs/msg/TwistStamped"
STRING = "std_msgs/msg/String"
FLOAT64_ARRAY = "std_msgs/msg/Float64MultiArray"


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

    def validate(self) -> None:
        """Raises :class:`InvalidArgumentError` on a setting the bridge cannot run."""
        if self.mode not in ("lockstep", "free"):
            raise InvalidArgumentError(f"expected mode lockstep or free; found {self.mode!r}")
        if not (math.isfinite(self.speed) and self.speed >= 0.0):
            raise InvalidArgumentError(
                f"expected a speed >= 0 (0: as fast as possible); found {self.speed}"
            )
        if self.stop_after < 0:
            raise InvalidArgumentError(f"expected stop_after >= 0; found {self.stop_after}")


def _motor_speeds(data: bytes) -> tuple[float, float]:
    return topics.motor_command(cdr.decode_float64_array(data))


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
        self.simulator = simulator
        self.settings = settings
        self.node = node or Node(
            NODE_NAME,
            settings.distro,
            network.discovery_from_environment(network=settings.network),
        )
        self.state = StateTopics(simulator, settings.distro)
        self.writers = [self.node.writer(t.name, t.msgtype, t.qos) for t in self.state.topics]
        static = self.state.static_topic()
        self.static_writer = self.node.writer(static.name, static.msgtype, static.qos)
        jazzy = settings.distro != "humble"
        self.cmd_vel = self.node.reader(
            "/" + standard.CMD_VEL_TOPIC, TWIST_STAMPED if jazzy else TWIST, COMMAND
        )
        self._decode_twist = cdr.decode_twist_stamped if jazzy else cdr.decode_twist
        self.motor = self.node.reader("/" + topics.MOTOR_TOPIC, FLOAT64_ARRAY, COMMAND)
        self.action = self.node.reader("/" + topics.ACTION_TOPIC, STRING, COMMAND)
        self.control: Reader | None = None
        if settings.mode == "free":
            self.control = self.node.reader(SIM_CONTROL_TOPIC, STRING, COMMAND)
        self.node.announce()
        self.bag = BagRecorder(settings.bag, settings.distro) if settings.bag else None
        self.goal = simulator.world.goal
        self.goal_step: int | None = None
        self.stop = threading.Event()
        self.rejected = 0
        self.wheel_speeds = (0.0, 0.0)
        self.published_steps = 0
        self._waitset = self._make_waitset()

    def _make_waitset(self) -> Any:
        from cyclonedds.core import InstanceState, ReadCondition, SampleState, ViewState, WaitSet

        waitset = WaitSet(self.node.participant)
        mask = SampleState.Any | ViewState.Any | InstanceState.Any
        for reader in self.node.readers:
            waitset.attach(ReadCondition(reader.dds, mask))
        return waitset

    def _send(self, writer: Any, nanoseconds: int, data: bytes) -> None:
        writer.publish(data)
        if self.bag is not None:
            self.bag.write(writer.topic, writer.msgtype, nanoseconds, data)

    def publish_static(self) -> None:
        """Publishes ``/tf_static`` (transient local: late subscribers get it too)."""
        nanoseconds = stamp_nanoseconds(self.simulator.time)
        data = self.state.static_transforms(cdr.stamp_of(nanoseconds))
        self._send(self.static_writer, nanoseconds, data)

    def publish_state(self, step_seconds: float) -> None:
        """Publishes every state topic for the current step, ``/clock`` last."""
        nanoseconds = stamp_nanoseconds(self.simulator.time)
        encoded = self.state.messages(cdr.stamp_of(nanoseconds), step_seconds)
        for writer, data in zip(self.writers, encoded):
            self._send(writer, nanoseconds, data)
        self.published_steps += 1

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
        """One control step with these wheel speeds, then the state topics."""
        self.simulator.step(left, right)
        self.publish_state(self.simulator.control_step_ms / 1000.0)
        self._note_goal()

    def commands(self) -> list[tuple[float, float]]:
        """The wheel speeds of every command received since the last call; bad ones are
        counted, reported on stderr and skipped."""
        speeds: list[tuple[float, float]] = []
        for data in self.cmd_vel.take():
            self._accept(speeds, self._twist_speeds, data)
        for data in self.motor.take():
            self._accept(speeds, _motor_speeds, data)
        for data in self.action.take():
            self._accept(speeds, self._action_speeds, data)
        return speeds

    def _twist_speeds(self, data: bytes) -> tuple[float, float]:
        return standard.twist_wheel_speeds(*self._decode_twist(data), self.state.robot)

    def _action_speeds(self, data: bytes) -> tuple[float, float]:
        return wheel_speeds(cdr.decode_string(data), self.state.robot.max_wheel_speed)

    def _accept(self, speeds: list[tuple[float, float]], read: Any, data: bytes) -> None:
        try:
            speeds.append(read(data))
        except (MazesimError, ValueError, KeyError) as error:
            self.rejected += 1
            print(f"mazesim ros2 bridge: ignored a command: {error}", file=sys.stderr, flush=True)

    def wait_for_driver(self) -> None:
        """Lockstep: waits until a command writer has matched, then the grace period."""
        readers = (self.cmd_vel, self.motor, self.action)
        while not self.stop.is_set():
            if any(reader.publishers() for reader in readers):
                self.stop.wait(READY_GRACE_S)
                return
            self.stop.wait(0.02)

    def run(self) -> None:
        """Runs until stopped (a signal, ``stop_after`` or the goal)."""
        self.publish_static()
        if self.settings.mode == "lockstep":
            self.wait_for_driver()
            if not self.stop.is_set():
                self.publish_state(0.0)
            while not self.stop.is_set():
                self._waitset.wait(100_000_000)
                for left, right in self.commands():
                    self.step(left, right)
                    if self.stop.is_set():
                        break
            return
        self._run_free()

    def _run_free(self) -> None:
        control_step_s = self.simulator.control_step_ms / 1000.0
        pace = FreeRunning(self.settings.speed, control_step_s, self.settings.paused)
        self.publish_state(0.0)
        while not self.stop.is_set():
            assert self.control is not None
            for data in self.control.take():
                try:
                    pace.control(cdr.decode_string(data))
                except InvalidActionError as error:
                    self.rejected += 1
                    print(f"mazesim ros2 bridge: ignored: {error}", file=sys.stderr, flush=True)
            for speeds in self.commands():
                self.wheel_speeds = speeds
            delay = pace.due(self.simulator.time, control_step_s)
            if delay is None:
                self._waitset.wait(50_000_000)
                continue
            if delay > 0.0:
                self._waitset.wait(int(delay * 1e9))
                continue
            self.step(*self.wheel_speeds)
            pace.stepped()

    def close(self) -> None:
        """Finishes the bag and leaves the DDS domain."""
        if self.bag is not None:
            self.bag.close()
            self.bag = None
        self.node.close()


def run_bridge(settings: BridgeSettings) -> int:
    """Runs the bridge from the command line until SIGINT/SIGTERM, ``stop_after`` or the goal.

    Returns:
        The exit code, 0 once the bridge has stopped.
    """
    settings.validate()
    import mazesim

    world = mazesim.load_world(settings.world)
    if settings.stop_at_goal and world.goal is None:
        raise InvalidArgumentError(f"--stop-at-goal: world {world.name!r} has no goal")
    simulator = Simulator(world, robot=settings.robot, seed=settings.seed, noise=settings.noise)
    bridge = Ros2Bridge(simulator, settings)

    def on_signal(number: int, frame: Any) -> None:
        bridge.stop.set()

    signal.signal(signal.SIGINT, on_signal)
    signal.signal(signal.SIGTERM, on_signal)
    started = time.monotonic()
    print(
        f"mazesim ros2 bridge: {settings.robot} in {world.name}, ROS 2 {settings.distro}, "
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
    print(
        f"mazesim ros2 bridge: stopped after {simulator.steps} steps "
        f"({simulator.time:.3f} s simulated, {time.monotonic() - started:.1f} s wall clock), "
        f"{goal}",
        file=sys.stderr,
        flush=True,
    )
    return 0
