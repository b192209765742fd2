"""The ROS 1 bridge on a world of several robots: each robot served in its own namespace (the
ROS 2 bridge's names), one /clock, lockstep over every driven robot; driven by a real rospy node."""

from __future__ import annotations

import json
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import mazesim
from mazesim.actions import wheel_speeds
from mazesim.errors import InvalidArgumentError
from mazesim.ros import standard, topics
from mazesim.ros.local_master import LocalMaster
from mazesim.ros.lockstep import stamp_nanoseconds
from mazesim.ros.robots import frame_prefix, next_round, robot_namespaces
from ros_support import needs_ros, run_probe, spawn_bridge, topic_types

DRIVER = Path(__file__).with_name("several_driver.py")

THREE_ROBOTS = """
format = "mazesim-world"
version = 1
name = "three-in-a-box"

[[walls]]
center = [0.0, 0.3]
size = [1.0, 0.01]

[[walls]]
center = [0.0, -0.3]
size = [1.0, 0.01]

[[robots]]
name = "west"
x = -0.3
y = 0.0

[[robots]]
name = "east-1"
x = 0.3
y = 0.0
yaw = 3.141592653589793

[[robots]]
name = "north"
x = 0.0
y = 0.2
yaw = 1.5707963267948966
"""


def _commands() -> list[list[list | None]]:
    """Per step, one command per robot: west on motor, east-1 on action then cmd_vel, north
    nobody drives."""
    steps: list[list[list | None]] = []
    for step in range(12):
        east = ["action", "00" if step < 6 else "aa"] if step % 2 else ["cmd_vel", [0.05, 0.8]]
        steps.append([["motor", [3.0 + 0.1 * step, 2.0]], east, None])
    return steps


def _in_process(world: mazesim.World, steps: list[list[list | None]]) -> list[list[list[float]]]:
    simulator = mazesim.Simulator(world, seed=0)
    robot = simulator.robot
    poses: list[list[list[float]]] = [[] for _ in range(simulator.num_robots)]

    def note() -> None:
        for index in range(simulator.num_robots):
            x, y, yaw = simulator.robot_state(index)["pose"]
            poses[index].append([x, y, yaw, simulator.time])

    note()
    speeds = [(0.0, 0.0)] * simulator.num_robots
    for entry in steps:
        for index, command in enumerate(entry):
            if command is None:
                continue
            topic, value = command
            if topic == "motor":
                speeds[index] = topics.motor_command(value)
            elif topic == "action":
                speeds[index] = wheel_speeds(value, robot.max_wheel_speed)
            else:
                speeds[index] = standard.twist_wheel_speeds(value[0], value[1], robot)
        simulator.step_robots(np.array(speeds, dtype=np.float64))
        note()
    return poses


def test_lockstep_waits_for_every_driven_robot_and_skips_the_undriven() -> None:
    from collections import deque

    west: deque[tuple[float, float]] = deque([(1.0, 1.0), (2.0, 2.0)])
    east: deque[tuple[float, float]] = deque()
    nobody: deque[tuple[float, float]] = deque()
    # east is driven and has sent nothing: the world waits.
    assert next_round([west, east, nobody], [True, True, False]) is None
    east.append((3.0, 3.0))
    assert next_round([west, east, nobody], [True, True, False]) == [(1.0, 1.0), (3.0, 3.0), None]
    # west's second command waits for east's next.
    assert next_round([west, east, nobody], [True, True, False]) is None
    assert list(west) == [(2.0, 2.0)]
    # Nothing waiting at all: no step, even with nobody driven.
    assert next_round([deque(), deque()], [False, False]) is None


def test_the_single_robot_settings_are_refused_on_several_robots() -> None:
    from mazesim.ros.bridge import BridgeSettings
    from mazesim.ros.several import refuse_single_robot_settings

    refuse_single_robot_settings(BridgeSettings(), "three")  # defaults: accepted
    for name, value in (("command_period", 0.1), ("stop_at_goal", True), ("bag", "a.bag")):
        settings = BridgeSettings(**{name: value})  # type: ignore[arg-type]
        with pytest.raises(InvalidArgumentError, match=f"expected parameter {name} left out"):
            refuse_single_robot_settings(settings, "three")


def _beside_bridge(
    master: LocalMaster, bridge_arguments: list[str], *program: str
) -> tuple[Any, dict[str, str]]:
    """Runs the bridge with ``bridge_arguments`` and the Python ``program`` (its arguments) until
    the program ends: what it printed last (JSON) and the topics' types the master knew then."""
    bridge = spawn_bridge(master, *bridge_arguments)
    try:
        ran = subprocess.run(
            [sys.executable, *program],
            env=master.env,
            capture_output=True,
            text=True,
            timeout=300,
            check=False,
        )
        assert ran.returncode == 0, ran.stdout + ran.stderr
        return json.loads(ran.stdout.strip().splitlines()[-1]), topic_types(master)
    finally:
        bridge.terminate()
        bridge.wait(timeout=60)


def _drive(master: LocalMaster, world_file: Path, *arguments: str) -> tuple[Any, dict[str, str]]:
    """Runs the bridge on ``world_file`` and the driver with ``arguments`` until the driver ends:
    what the driver printed last (JSON) and the topics' types the master knew then."""
    return _beside_bridge(master, ["--world", str(world_file)], str(DRIVER), *arguments)


@needs_ros
def test_every_robot_is_served_in_its_namespace_and_runs_as_in_process(
    master: LocalMaster, tmp_path: Path
) -> None:
    world_file = tmp_path / "three.toml"
    world_file.write_text(THREE_ROBOTS)
    world = mazesim.load_world(str(world_file))
    namespaces = robot_namespaces([str(robot["name"]) for robot in world.robots])
    assert namespaces == ["/west", "/east_1", "/north"]  # the ROS 2 bridge's names
    steps = _commands()
    commands_file = tmp_path / "commands.json"
    commands_file.write_text(json.dumps(steps))
    served, kinds = _drive(master, world_file, json.dumps(namespaces), str(commands_file))
    for namespace in namespaces:
        assert kinds[f"{namespace}/sensors"] == "std_msgs/Float64MultiArray"
        assert kinds[f"{namespace}/cmd_vel"] == "geometry_msgs/Twist"
        assert kinds[f"{namespace}/motor"] == "std_msgs/Float64MultiArray"
        assert kinds[f"{namespace}/action"] == "std_msgs/String"
    assert kinds["/clock"] == "rosgraph_msgs/Clock"
    assert "/sensors" not in kinds and "/cmd_vel" not in kinds  # nothing outside a namespace
    expected = _in_process(world, steps)
    assert served == expected  # bit for bit, every robot, every step
    # The undriven robot stood still while the others moved.
    assert served[2][0][:3] == served[2][-1][:3]
    assert served[0][-1][:2] != served[0][0][:2] and served[1][-1][:2] != served[1][0][:2]


@needs_ros
def test_realtime_steps_every_robot_with_its_last_command(
    master: LocalMaster, tmp_path: Path
) -> None:
    """In realtime mode the world steps on its own: the robot commanded once drives on with
    that command, the robot nobody drives stands, and ``/clock`` runs for both."""
    world_file = tmp_path / "three.toml"
    world_file.write_text(THREE_ROBOTS)
    namespaces = ["/west", "/east_1", "/north"]
    commands_file = tmp_path / "commands.json"
    commands_file.write_text(json.dumps([[["motor", [4.0, 4.0]], None, None]] * 10))
    (west, _, north), _ = _beside_bridge(
        master,
        ["--world", str(world_file), "--mode", "realtime"],
        str(DRIVER),
        json.dumps(namespaces),
        str(commands_file),
    )
    assert west[-1][3] > west[0][3] and north[-1][3] > north[0][3]  # simulated time ran
    assert west[-1][0] > west[0][0]  # driven along +x
    assert north[-1][:3] == north[0][:3]  # never commanded: stands


@needs_ros
def test_every_robot_publishes_odom_and_tf_in_frames_named_after_its_namespace(
    master: LocalMaster, tmp_path: Path
) -> None:
    """Each robot's ``odom`` in its namespace, its frames ``<robot>/odom``, ``<robot>/base_link``
    ... on the one ``/tf`` and ``/tf_static``, as tf2 reads them: the in-process run's poses."""
    world_file = tmp_path / "three.toml"
    world_file.write_text(THREE_ROBOTS)
    world = mazesim.load_world(str(world_file))
    namespaces = robot_namespaces([str(robot["name"]) for robot in world.robots])
    names = [namespace.strip("/") for namespace in namespaces]
    assert [frame_prefix(namespace) for namespace in namespaces] == [f"{n}/" for n in names]
    assert frame_prefix("") == ""  # a world of one robot: its frames as they are
    steps = _commands()[:6]
    commands_file = tmp_path / "commands.json"
    commands_file.write_text(json.dumps(steps))
    frames = standard.sensor_frames(mazesim.Simulator(world, seed=0).robot_profile(0))
    sensors = [frames[0].frame, frames[-1].frame]
    served, kinds = _drive(
        master, world_file, json.dumps(namespaces), str(commands_file), json.dumps(sensors)
    )
    for namespace in namespaces:
        assert kinds[f"{namespace}/odom"] == "nav_msgs/Odometry"
        assert kinds[f"{namespace}/{sensors[0]}"] == "sensor_msgs/Range"
    assert kinds["/tf"] == kinds["/tf_static"] == "tf2_msgs/TFMessage"
    assert "/odom" not in kinds and "/west/tf" not in kinds  # one /tf, no robot outside
    expected = _in_process(world, steps)
    assert served["poses"] == expected
    for index, name in enumerate(names):
        odoms = [
            [f"{name}/odom", f"{name}/base_link", x, y, *standard.yaw_quaternion(yaw)[2:]]
            + [stamp_nanoseconds(seconds)]
            for x, y, yaw, seconds in expected[index]
        ]
        assert served["odom"][index] == odoms  # bit for bit, every step
        assert served["tf"][index] == [pytest.approx(odom[2:6], abs=1e-12) for odom in odoms]
        by_frame = {frame.frame: frame for frame in frames}
        assert (
            served["static"][index]
            == [
                pytest.approx([0.0, 0.0, 0.0, 1.0], abs=1e-12),  # map -> <robot>/odom
                *(
                    pytest.approx(
                        [
                            by_frame[s].x,
                            by_frame[s].y,
                            *standard.yaw_quaternion(by_frame[s].yaw)[2:],
                        ],
                        abs=1e-12,
                    )
                    for s in sensors
                ),
            ]
        )
    # The robots moved apart: tf2 kept each robot's frames its own.
    assert served["tf"][0][-1] != served["tf"][1][-1]


#: A node with a writer on /west/motor that never commands: it records every /tf stamp and every
#: /west/pose time for 7.5 s, past the bridge's resend wait.
_SILENT_WRITER = """
import json, time
import rospy
from std_msgs.msg import Float64MultiArray
from tf2_msgs.msg import TFMessage
rospy.init_node("silent_writer", disable_signals=True)
seen = {"tf": [], "pose": []}
stamp = lambda m: m.transforms[0].header.stamp.to_nsec()
rospy.Subscriber("/tf", TFMessage, lambda m: seen["tf"].append(stamp(m)))
rospy.Subscriber("/west/pose", Float64MultiArray, lambda m: seen["pose"].append(m.data[3]))
motor = rospy.Publisher("/west/motor", Float64MultiArray, queue_size=1)
deadline = time.monotonic() + 60.0  # the state again comes 5 s after the hand-over to it
while len(seen["pose"]) < 2 and time.monotonic() < deadline:
    time.sleep(0.05)
time.sleep(0.5)  # a /tf sent with it would have come by now
print(json.dumps(seen))
"""


@needs_ros
def test_a_state_sent_again_on_several_robots_leaves_tf_out(
    master: LocalMaster, tmp_path: Path
) -> None:
    # The reset state went unanswered while a command writer was connected: the bridge sends
    # it again 5 s after it went out to the writer, every robot's topics but /tf, which went out
    # at that stamp already (tf2 warns TF_REPEATED_DATA of a transform again at one stamp), as
    # the one-robot bridge.
    world_file = tmp_path / "three.toml"
    world_file.write_text(THREE_ROBOTS)
    seen, _ = _beside_bridge(master, ["--world", str(world_file)], "-c", _SILENT_WRITER)
    log = Path(master.log_path("bridge")).read_text()
    assert "publishing the reset state again" in log, log
    assert len(seen["pose"]) >= 2 and set(seen["pose"]) == {0.0}, seen  # the reset state, again
    assert seen["tf"] == [1], seen  # once, at the reset state's stamp (1 ns)


@needs_ros
def test_a_node_connecting_late_on_several_robots_gets_the_state_once_in_order(
    master: LocalMaster, tmp_path: Path
) -> None:
    # The one-robot bridge's rule for late subscriptions (LateConnections), on several robots:
    # a Bug-like node of robot west, whose scan subscription connects before its odom one and
    # that skips scans until an odometry has come, started about 5 s after the bridge (a slow
    # start under load). rospy's latch gave it the scan at once, before any odometry, and the
    # reset state went out again as it connected (counted from the bridge's start).
    world_file = tmp_path / "three.toml"
    world_file.write_text(THREE_ROBOTS)
    spawn_bridge(master, "--world", str(world_file), "--seed", "3", "--duration", str(10 * 0.032))
    deadline = time.monotonic() + 120.0
    while "/west/scan" not in topic_types(master):
        assert time.monotonic() < deadline, "the bridge did not come up"
        time.sleep(0.05)
    time.sleep(4.0)
    seen = run_probe(master, "scan-with-odom", "10", namespace="/west")
    log = Path(master.log_path("bridge")).read_text()
    assert seen["answered"] == pytest.approx([1e-9] + [step * 0.032 for step in range(1, 10)]), (
        seen,
        log,
    )
    assert seen["scans"][: len(seen["answered"])] == seen["answered"], (seen, log)  # each once
    assert "publishing the reset state again" not in log, log
    assert "lockstep: the state handed to late subscriptions" in log, log
