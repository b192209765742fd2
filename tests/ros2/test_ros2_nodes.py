"""The ROS 2 nodes with the bridge, each in its own process over DDS in a private network
namespace: the hierarchical navigator reaches seed-maze's goal in the same steps as in process and
its bag reads back through an independent reader; a timer on simulation time drives a free-running
bridge; ``/sim_control`` steps a paused one."""

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
    result = run_in_namespace([], [*MAZESIM, "ros2", "demo", "--out", str(out)], timeout=120)
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


def test_timer_on_simulation_time_drives_a_free_running_bridge(tmp_path: Path) -> None:
    bag = tmp_path / "free"
    bridge = [
        *MAZESIM, "ros2", "bridge", "--mode", "free", "--speed", "0", "--stop-after", "200",
        "--bag", str(bag),
    ]  # fmt: skip
    node = [*MAZESIM, "ros2", "avoid-collision", "--period-ms", "64"]
    # The node runs in the background; the bridge in front ends after 200 steps.
    result = run_in_namespace([node], bridge, timeout=90, grace=2.0)
    assert "stopped after 200 steps" in result.stderr, result.stderr
    poses = [list(message.data) for message in _bag_messages(bag)["/pose"]]  # type: ignore[attr-defined]
    assert len(poses) == 201
    # The wheels start at rest: only the node's commands can have moved the robot.
    travelled = sum(math.dist(a[:2], b[:2]) for a, b in zip(poses, poses[1:]))
    assert travelled > 0.1, travelled
    assert "avoid_collision: stopped after" in result.stderr


def test_sim_control_steps_a_paused_bridge(tmp_path: Path) -> None:
    bag = tmp_path / "paused"
    bridge = [
        *MAZESIM, "ros2", "bridge", "--mode", "free", "--paused", "--speed", "0",
        "--bag", str(bag),
    ]  # fmt: skip
    control = [sys.executable, "-c", _CONTROL]
    result = run_in_namespace([bridge], control, timeout=60, grace=1.0)
    assert result.returncode == 0, result.stderr
    clocks = _bag_messages(bag)["/clock"]
    # The reset state, then exactly the 7 steps asked for, then nothing while paused.
    assert len(clocks) == 8, len(clocks)


_CONTROL = """
import time
from mazesim.ros2 import cdr
from mazesim.ros2.node import Node
from mazesim.ros2.qos import COMMAND
node = Node("sim_control_test")
control = node.writer("/sim_control", "std_msgs/msg/String", COMMAND)
node.announce()
deadline = time.monotonic() + 20
while not control.subscribers() and time.monotonic() < deadline:
    time.sleep(0.01)
time.sleep(0.3)
for text in ("step 4", "step 3"):
    control.publish(cdr.encode_string(text))
    time.sleep(0.5)
"""
