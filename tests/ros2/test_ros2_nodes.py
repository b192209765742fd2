"""The ROS 2 nodes with the bridge, each in its own process over DDS in a private network
namespace: the hierarchical navigator reaches seed-maze's goal in the same steps as in process and
its bag reads back through an independent reader; a timer on simulation time drives a free-running
bridge that ``/sim_control`` steps and runs."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

import mazesim
from mazesim.actions import wheel_speeds
from mazesim.learn import load_policy
from mazesim.ros import topics
from ros2_support import MAZESIM, needs_namespace, needs_ros2, run_in_namespace

pytestmark = [needs_ros2, needs_namespace]


def _in_process_hrl(seed: int) -> tuple[list[list[float]], int]:
    """The shipped navigator on the seed robot without ROS: the poses and the goal step."""
    world = mazesim.load_world("seed-maze")
    assert world.goal is not None
    goal_x, goal_y, radius = world.goal
    simulator = mazesim.Simulator(world, robot="seed", seed=seed)
    policy = load_policy()
    policy.reset(control_step_ms=simulator.control_step_ms)
    poses = [topics.pose_values(simulator)]
    while simulator.steps < 4000:
        values = topics.sensor_data_values(simulator)
        code = policy.act(np.asarray(values[:6]), int(values[6]))
        simulator.step(*wheel_speeds(code, simulator.robot.max_wheel_speed))
        poses.append(topics.pose_values(simulator))
        x, y, _ = simulator.pose
        if math.hypot(x - goal_x, y - goal_y) <= radius:
            return poses, simulator.steps
    raise AssertionError("the navigator did not reach the goal in process")


def _bag_messages(bag: Path) -> dict[str, list[object]]:
    make_reader = pytest.importorskip("mcap.reader").make_reader
    decoder_factory = pytest.importorskip("mcap_ros2.decoder").DecoderFactory
    found: dict[str, list[object]] = {}
    with next(bag.glob("*.mcap")).open("rb") as stream:
        reader = make_reader(stream, decoder_factories=[decoder_factory()])
        for _schema, channel, _message, decoded in reader.iter_decoded_messages():
            found.setdefault(channel.topic, []).append(decoded)
    return found


def test_hrl_navigator_over_ros2_reaches_the_goal_in_the_in_process_steps(tmp_path: Path) -> None:
    out = tmp_path / "demo"
    result = run_in_namespace([], [*MAZESIM, "ros2", "demo", "--out", str(out)])
    assert result.returncode == 0, result.stderr
    poses, goal = _in_process_hrl(seed=0)
    assert f"goal at step {goal}" in result.stdout
    # The bag, read by mcap-ros2-support: every step's pose and reading, message for message.
    bag = _bag_messages(out / "bag")
    assert [list(message.data) for message in bag["/pose"]] == poses  # type: ignore[attr-defined]
    assert len(bag["/sensor_data"]) == len(bag["/clock"]) == goal + 1
    assert {frame.child_frame_id for frame in bag["/tf_static"][0].transforms} >= {  # type: ignore[attr-defined]
        "front", "back", "left", "right", "left_front", "right_front",
    }  # fmt: skip


def test_sim_control_and_a_sim_time_timer_drive_a_free_running_bridge(tmp_path: Path) -> None:
    bag = tmp_path / "free"
    bridge = [
        *MAZESIM, "ros2", "bridge", "--mode", "free", "--paused", "--speed", "0",
        "--bag", str(bag),
    ]  # fmt: skip
    # A node on a 64 ms timer of simulation time (/clock), as use_sim_time gives.
    node = [*MAZESIM, "ros2", "avoid-collision", "--period-ms", "64"]
    control = [sys.executable, "-c", _CONTROL]
    result = run_in_namespace([bridge, node], control, grace=1.0)
    assert result.returncode == 0, result.stderr
    found = _bag_messages(bag)
    clocks = [m.clock.sec * 10**9 + m.clock.nanosec for m in found["/clock"]]  # type: ignore[attr-defined]
    # Paused: the reset state; a word that is no control is refused and steps nothing; "step 4"
    # and "step 3": exactly 7 steps; then "step 1" until the timer node has moved the robot;
    # "run_until 6.4": up to 6.4 s (200 steps in all), then paused again until stopped.
    assert "ignored: expected pause, run, step N (N >= 1) or run_until SECONDS" in result.stderr
    assert clocks[:8] == [1, *(32_000_000 * step for step in range(1, 8))]
    assert clocks[-1] == 6_400_000_000 and len(clocks) == 201
    poses = [list(message.data) for message in found["/pose"]]  # type: ignore[attr-defined]
    # The wheels start at rest: only the timer node's commands can have moved the robot.
    travelled = sum(math.dist(a[:2], b[:2]) for a, b in zip(poses, poses[1:]))
    assert travelled > 0.1, travelled
    assert "avoid_collision: stopped after" in result.stderr


_CONTROL = """
import os, time
from mazesim.ros2 import cdr
from mazesim.ros2.node import Node
from mazesim.ros2.qos import CLOCK, COMMAND, SENSOR
node = Node("sim_control_test")
clock = node.reader("/clock", "rosgraph_msgs/msg/Clock", CLOCK)
pose = node.reader("/pose", "std_msgs/msg/Float64MultiArray", SENSOR)
control = node.writer("/sim_control", "std_msgs/msg/String", COMMAND)
node.announce()
def until(condition, what):
    ceiling = time.monotonic() + 300  # bounds a hang only: each wait ends on its condition
    while not condition():
        assert time.monotonic() < ceiling, what
        time.sleep(0.01)
until(lambda: control.subscribers() and clock.publishers() and pose.publishers(), "discovery")
# The bridge reads this writer once it refuses a word that is no control (it stays paused).
control.publish(cdr.encode_string("hello"))
seen = time.monotonic()
def refused():
    global seen
    path = os.path.join(os.environ["TMPDIR_NS"], "bg0.err")
    with open(path, encoding="utf-8", errors="replace") as stream:
        if "found 'hello'" in stream.read():
            return True
    if time.monotonic() - seen > 1.0:  # sent before the bridge matched this writer: again
        control.publish(cdr.encode_string("hello"))
        seen = time.monotonic()
    return False
until(refused, "the bridge never read /sim_control")
now = 0
def wait_for(target):
    global now
    def reached():
        global now
        for data in clock.take():
            now = cdr.decode_clock(data)
        return now >= target
    until(reached, ("clock", now, target))
    assert now == target, (now, target)
control.publish(cdr.encode_string("step 4"))
wait_for(4 * 32_000_000)
control.publish(cdr.encode_string("step 3"))
wait_for(7 * 32_000_000)
# One step at a time until the timer node's commands have moved the robot (it has started and
# the bridge reads it), however long its start took.
places = set()
def moved():
    places.update(tuple(cdr.decode_float64_array(data)[:3]) for data in pose.take())
    return len(places) > 1
while not moved():
    control.publish(cdr.encode_string("step 1"))
    wait_for(now + 32_000_000)
control.publish(cdr.encode_string("run_until 6.4"))
wait_for(6_400_000_000)
"""
