"""The report's controllers and the hierarchical navigator as ROS 2 nodes.

- ``perform_learning``: the report's Alg. 5 over ROS 2. It answers each ``/sensor_data`` reading
  (the ``seed`` robot's six distances in cm and the checkpoint) with the action code the shipped
  hierarchical policy chooses, on ``/action``; in lockstep the bridge and the node drive the robot
  step for step as the policy does in process.
- ``avoid_collision``: the report's Alg. 1 on the e-puck: ``/sensors`` in, ``/motor`` out. It
  answers each reading, or, with a period, fires on a timer of simulation time (``/clock``), as a
  ROS 2 node with ``use_sim_time`` does: that is how it drives a free-running bridge.

Each node creates its readers before its command writer, as the bridge's lockstep start expects.
"""

from __future__ import annotations

import functools
import signal
import sys
import threading
from collections.abc import Callable
from typing import Any

import numpy as np

from mazesim.controllers import AvoidCollision
from mazesim.errors import InvalidArgumentError
from mazesim.ros import topics
from mazesim.ros2 import cdr, network
from mazesim.ros2.node import Node, Reader
from mazesim.ros2.qos import CLOCK, COMMAND, SENSOR

__all__ = ["run_avoid_collision", "run_perform_learning", "stop_on_signals"]

FLOAT64_ARRAY = "std_msgs/msg/Float64MultiArray"
STRING = "std_msgs/msg/String"
CLOCK_TYPE = "rosgraph_msgs/msg/Clock"


def leaves_signals_as_found(run: Callable[..., int]) -> Callable[..., int]:
    """Makes ``run`` (a node or the bridge, which may set SIGINT's and SIGTERM's handlers with
    :func:`stop_on_signals`) put back the handlers it found when it ends, however it ends: a
    process that goes on afterwards (a caller of the command line's ``main``) keeps its Ctrl-C."""

    @functools.wraps(run)
    def wrapper(*args: Any, **kwargs: Any) -> int:
        found = [(number, signal.getsignal(number)) for number in (signal.SIGINT, signal.SIGTERM)]
        try:
            return run(*args, **kwargs)
        finally:
            for number, handler in found:
                if handler is not None and signal.getsignal(number) is not handler:
                    signal.signal(number, handler)

    return wrapper


def stop_on_signals() -> threading.Event:
    """An event set by SIGINT or SIGTERM."""
    stop = threading.Event()

    def on_signal(number: int, frame: Any) -> None:
        stop.set()

    signal.signal(signal.SIGINT, on_signal)
    signal.signal(signal.SIGTERM, on_signal)
    return stop


def _spin(node: Node, stop: threading.Event, handle: Callable[[], None]) -> None:
    """Calls ``handle`` as the node's readers receive until ``stop`` is set, then closes it."""
    try:
        from cyclonedds.core import InstanceState, ReadCondition, SampleState, ViewState, WaitSet

        waitset = WaitSet(node.participant)
        mask = SampleState.Any | ViewState.Any | InstanceState.Any
        for reader in node.readers:
            waitset.attach(ReadCondition(reader.dds, mask))
        while not stop.is_set():
            waitset.wait(100_000_000)
            handle()
    finally:
        node.close()


@leaves_signals_as_found
def run_perform_learning(
    distro: str,
    policy_path: str | None = None,
    control_step_ms: float = 32.0,
    network_wide: bool = False,
    stop: threading.Event | None = None,
) -> int:
    """Runs the perform-learning node until stopped; returns the exit code.

    Args:
        distro: The ROS 2 distribution to speak.
        policy_path: A folder of trained tables, or ``None`` for the shipped ones.
        control_step_ms: The bridge's control step (32 ms for the ``seed`` robot).
        network_wide: Discover over the network rather than this machine only.
        stop: Stops the node when set (SIGINT and SIGTERM by default).
    """
    from mazesim.learn import load_policy

    policy = load_policy(policy_path)
    policy.reset(control_step_ms=control_step_ms)
    stop = stop or stop_on_signals()
    node = Node(
        "perform_learning", distro, network.discovery_from_environment(network=network_wide)
    )
    readings = node.reader(f"/{topics.SENSOR_DATA_TOPIC}", FLOAT64_ARRAY, SENSOR)
    action = node.writer(f"/{topics.ACTION_TOPIC}", STRING, COMMAND)
    node.announce()
    answered = 0

    def handle() -> None:
        nonlocal answered
        for data in readings.take():
            values = cdr.decode_float64_array(data)
            if len(values) != 7:
                print(
                    f"perform_learning: ignored sensor_data of {len(values)} values",
                    file=sys.stderr,
                )
                continue
            code = policy.act(np.asarray(values[:6], dtype=np.float64), int(values[6]))
            action.publish(cdr.encode_string(code))
            answered += 1

    _spin(node, stop, handle)
    print(f"perform_learning: stopped after {answered} actions", file=sys.stderr, flush=True)
    return 0


@leaves_signals_as_found
def run_avoid_collision(
    distro: str,
    period_ms: float = 0.0,
    network_wide: bool = False,
    stop: threading.Event | None = None,
    namespace: str = "",
) -> int:
    """Runs the avoid-collision node until stopped; returns the exit code.

    Args:
        distro: The ROS 2 distribution to speak.
        period_ms: 0: answer each ``/sensors`` reading (lockstep); else a timer of simulation
            time (``/clock``) with this period, using the latest reading.
        network_wide: Discover over the network rather than this machine only.
        stop: Stops the node when set (SIGINT and SIGTERM by default).
        namespace: The robot's namespace (``"/west"``) in a world of several robots, whose
            ``sensors`` and ``motor`` it uses; ``""`` for a world of one.
    """
    if not period_ms >= 0.0:
        raise InvalidArgumentError(f"expected a timer period >= 0 ms; found {period_ms}")
    controller = AvoidCollision()
    stop = stop or stop_on_signals()
    node = Node("avoid_collision", distro, network.discovery_from_environment(network=network_wide))
    sensors = node.reader(f"{namespace}/{topics.SENSORS_TOPIC}", FLOAT64_ARRAY, SENSOR)
    clock: Reader | None = node.reader("/clock", CLOCK_TYPE, CLOCK) if period_ms else None
    motor = node.writer(f"{namespace}/{topics.MOTOR_TOPIC}", FLOAT64_ARRAY, COMMAND)
    node.announce()
    latest: list[float] | None = None
    next_tick_ns = 0
    sent = 0

    def command(values: list[float]) -> None:
        nonlocal sent
        left, right = controller(np.asarray(values[:8], dtype=np.float64))
        motor.publish(cdr.encode_float64_multi_array(("left", "right"), [left, right]))
        sent += 1

    def handle() -> None:
        nonlocal latest, next_tick_ns
        for data in sensors.take():
            latest = cdr.decode_float64_array(data)
            if clock is None:
                command(latest)
        if clock is None:
            return
        for data in clock.take():
            now = cdr.decode_clock(data)
            if latest is not None and now >= next_tick_ns:
                command(latest)
                next_tick_ns = now + round(period_ms * 1e6)

    _spin(node, stop, handle)
    print(f"avoid_collision: stopped after {sent} commands", file=sys.stderr, flush=True)
    return 0
