"""The standard ROS messages of the bridge: Range, Odometry, tf and cmd_vel.

The pure conversions run without ROS; the rest runs the bridge against a real master (the
``master`` fixture of conftest.py) and checks what a ROS user's tools would see.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

import mazesim
from mazesim.errors import InvalidActionError, InvalidArgumentError
from mazesim.ros import standard
from mazesim.ros.local_master import LocalMaster
from mazesim.ros.occupancy import occupied_cells
from ros_support import (
    REPO,
    needs_ros,
    processes_with,
    run_probe,
    spawn_bridge,
    spawn_launch,
    stop_launch,
    topic_types,
)

EPUCK = mazesim.RobotProfile.builtin("e-puck")
STEP_S = 0.032


# --- the parts that need no ROS ------------------------------------------------------------------


def test_twist_becomes_wheel_speeds_of_the_profile() -> None:
    radius, half_axle = EPUCK.wheel_radius, EPUCK.axle_length / 2.0
    assert standard.twist_wheel_speeds(0.05, 0.0, EPUCK) == pytest.approx((0.05 / radius,) * 2)
    left, right = standard.twist_wheel_speeds(0.0, 1.0, EPUCK)
    assert (left, right) == pytest.approx((-half_axle / radius, half_axle / radius))
    # Back to the twist: v = r (wl + wr) / 2, w = r (wr - wl) / axle.
    left, right = standard.twist_wheel_speeds(0.04, -0.8, EPUCK)
    assert radius * (left + right) / 2.0 == pytest.approx(0.04)
    assert radius * (right - left) / EPUCK.axle_length == pytest.approx(-0.8)


def test_twist_beyond_the_motors_keeps_its_arc() -> None:
    wanted_left, wanted_right = (
        (0.3 - 2.0 * EPUCK.axle_length / 2) / EPUCK.wheel_radius,
        (0.3 + 2.0 * EPUCK.axle_length / 2) / EPUCK.wheel_radius,
    )
    left, right = standard.twist_wheel_speeds(0.3, 2.0, EPUCK)
    assert max(abs(left), abs(right)) == pytest.approx(EPUCK.max_wheel_speed)
    assert left / right == pytest.approx(wanted_left / wanted_right)
    left, right = standard.twist_wheel_speeds(-5.0, 0.0, EPUCK)
    assert (left, right) == pytest.approx((-EPUCK.max_wheel_speed,) * 2)
    # A huge finite twist overflowed into an infinite speed the limit scaled by 0 into NaN (a
    # lost step in lockstep; the real-time bridge died): it keeps its arc too.
    top = EPUCK.max_wheel_speed
    assert standard.twist_wheel_speeds(1e307, 0.0, EPUCK) == pytest.approx((top, top))
    assert standard.twist_wheel_speeds(-1e308, 0.0, EPUCK) == pytest.approx((-top, -top))
    left, right = standard.twist_wheel_speeds(0.0, 1.7e308, EPUCK)
    assert (left, right) == pytest.approx((-top, top))


@pytest.mark.parametrize(("linear", "angular"), [(math.nan, 0.0), (0.0, math.inf)])
def test_twist_that_is_not_finite_is_refused(linear: float, angular: float) -> None:
    with pytest.raises(InvalidActionError, match="finite .* on cmd_vel"):
        standard.twist_wheel_speeds(linear, angular, EPUCK)


def test_body_velocity_is_in_the_robot_frame() -> None:
    # Heading north (yaw pi/2), 3.2 mm north in 32 ms: 0.1 m/s forward, none sideways.
    velocity = standard.body_velocity((1.0, 1.0, math.pi / 2), (1.0, 1.0032, math.pi / 2), STEP_S)
    assert velocity == pytest.approx((0.1, 0.0, 0.0), abs=1e-12)
    # Pushed west while heading north: leftward in the robot's frame.
    velocity = standard.body_velocity((0.0, 0.0, math.pi / 2), (-0.0032, 0.0, math.pi / 2), STEP_S)
    assert velocity == pytest.approx((0.0, 0.1, 0.0), abs=1e-12)
    # Turning through +-pi counts the short way round.
    velocity = standard.body_velocity((0.0, 0.0, 3.1), (0.0, 0.0, -3.1), STEP_S)
    assert velocity.turn == pytest.approx((2 * math.pi - 6.2) / STEP_S)


def test_sensor_frames_come_from_the_profile() -> None:
    frames = standard.sensor_frames(EPUCK)
    assert [frame.frame for frame in frames] == [f"ps{index}" for index in range(8)]
    for frame, (x, y, yaw) in zip(frames, EPUCK.distance_sensor_poses().tolist()):
        assert (frame.x, frame.y, frame.yaw) == (x, y, yaw)
        assert (frame.min_range, frame.max_range) == (0.0, 0.07)
    seed = standard.sensor_frames(mazesim.RobotProfile.builtin("seed"))
    assert [frame.frame for frame in seed][4:] == ["left_front", "right_front"]
    assert all(frame.max_range == pytest.approx(0.40) for frame in seed)


def test_range_is_the_distance_of_the_reading() -> None:
    # The e-puck's table: 0.02 m -> 383.84, 0.03 m -> 234.93; between rows it interpolates.
    assert EPUCK.distance_from_reading(0, 383.84) == pytest.approx(0.02)
    assert EPUCK.distance_from_reading(3, (383.84 + 234.93) / 2) == pytest.approx(0.025)
    assert EPUCK.distance_from_reading(0, 5000.0) == 0.0  # clamped to the table
    with pytest.raises(InvalidArgumentError, match="below 8, found 8"):
        EPUCK.distance_from_reading(8, 100.0)
    with pytest.raises(InvalidArgumentError, match="finite reading of distance sensor ps0"):
        EPUCK.distance_from_reading(0, math.nan)

    world = mazesim.load_world("seed-maze")
    simulator = mazesim.Simulator(world, robot="e-puck", seed=0, noise=False)
    simulator.set_pose(0.125, 0.125, 0.0)  # the middle of a 0.25 m cell: walls beyond 7 cm
    assert standard.ranges(simulator) == [math.inf] * 8
    # Face the west wall from 2 cm off ps0's and ps7's origin (0.03 m ahead of the centre).
    (west_wall,) = (box for box in world.wall_boxes().tolist() if box[0] < 0.05)
    west_wall_face = west_wall[0] + min(west_wall[2:4]) / 2  # a vertical box: its thickness
    simulator.set_pose(west_wall_face + 0.05, 0.125, math.pi)
    distances = standard.ranges(simulator)
    assert distances[0] == pytest.approx(0.02 / math.cos(0.3008), abs=2e-3)
    assert distances[7] == pytest.approx(0.02 / math.cos(0.2992), abs=2e-3)


def test_yaw_quaternion_turns_about_z() -> None:
    for yaw in (0.0, 1.0, -2.5, math.pi):
        x, y, z, w = standard.yaw_quaternion(yaw)
        assert (x, y) == (0.0, 0.0) and z * z + w * w == pytest.approx(1.0)
        assert 2.0 * math.atan2(z, w) == pytest.approx(yaw)


def test_rviz_config_shows_what_the_bridge_publishes() -> None:
    yaml = pytest.importorskip("yaml", reason="PyYAML comes with ROS 1 (run 'make ros-deps')")
    config = yaml.safe_load((REPO / "ros/mazesim_ros/rviz/mazesim.rviz").read_text())
    manager = config["Visualization Manager"]
    assert manager["Global Options"]["Fixed Frame"] == standard.ODOM_FRAME
    topics = {display["Class"]: [] for display in manager["Displays"]}
    for display in manager["Displays"]:
        topics[display["Class"]].append(display.get("Topic"))
    assert topics["rviz/Odometry"] == ["/" + standard.ODOM_TOPIC]
    assert topics["rviz/Range"] == ["/" + frame.frame for frame in standard.sensor_frames(EPUCK)]
    assert "rviz/TF" in topics


# --- against a real master -----------------------------------------------------------------------

#: Straight on, a turn on the spot, then an arc faster than the motors allow (scaled down).
TWISTS = [[0.05, 0.0]] * 40 + [[0.0, 1.0]] * 30 + [[0.3, 2.0]] * 10


State = tuple[tuple[float, float, float], list[float], float]


def _replay(seed: int, twists: list[list[float]]) -> list[State]:
    """The poses and ranges the in-process simulator has after each twist, start included."""
    simulator = mazesim.Simulator(mazesim.load_world("seed-maze"), robot="e-puck", seed=seed)
    states: list[State] = [(simulator.pose, standard.ranges(simulator), simulator.time)]
    for linear, angular in twists:
        simulator.step(*standard.twist_wheel_speeds(linear, angular, simulator.robot))
        states.append((simulator.pose, standard.ranges(simulator), simulator.time))
    return states


@needs_ros
def test_standard_messages_agree_with_the_simulator(master: LocalMaster, tmp_path: Path) -> None:
    spawn_bridge(master, "--seed", "3")
    commands = tmp_path / "twists.json"
    commands.write_text(json.dumps(TWISTS))
    seen = run_probe(master, "standard", str(commands))

    # The types on each topic, as the master (and `rostopic list -v`) reports them.
    types = topic_types(master)
    assert types["/odom"] == "nav_msgs/Odometry"
    assert types["/tf"] == types["/tf_static"] == "tf2_msgs/TFMessage"
    assert types["/cmd_vel"] == "geometry_msgs/Twist"
    assert all(types[f"/ps{index}"] == "sensor_msgs/Range" for index in range(8))
    assert types["/scan"] == "sensor_msgs/LaserScan"
    assert types["/pose"] == types["/sensors"] == "std_msgs/Float64MultiArray"  # kept as they were

    expected = _replay(3, TWISTS)
    odom, tf = seen["odom"], seen["tf"]
    assert len(odom) == len(tf) == len(expected) == len(TWISTS) + 1
    for row, transform, (pose, _, time) in zip(odom, tf, expected):
        assert (row["frame"], row["child"]) == ("odom", "base_link")
        assert (transform["parent"], transform["child"]) == ("odom", "base_link")
        assert row["stamp"] == transform["stamp"] == pytest.approx(time, abs=1e-9)
        assert row["pose"][:2] == list(pose[:2])  # the simulator's pose, bit for bit
        assert row["pose"][2] == pytest.approx(pose[2], abs=1e-12)
        assert row["z"] == [0.0, 0.0, 0.0]
        assert transform["pose"] == row["pose"]  # tf carries the same transform

    # The twists moved the robot as asked: 0.05 m/s for 40 steps, then 1 rad/s for 30 steps.
    start, straight, turned = (odom[i]["pose"] for i in (0, 40, 70))
    travelled = math.hypot(straight[0] - start[0], straight[1] - start[1])
    assert travelled == pytest.approx(0.05 * 40 * STEP_S, rel=0.02)
    heading = math.atan2(straight[1] - start[1], straight[0] - start[0])
    assert math.remainder(heading - start[2], math.tau) == pytest.approx(0.0, abs=0.01)
    assert math.remainder(turned[2] - straight[2], math.tau) == pytest.approx(0.96, rel=0.02)
    assert math.hypot(turned[0] - straight[0], turned[1] - straight[1]) < 1e-3
    assert odom[20]["twist"] == pytest.approx([0.05, 0.0, 0.0], abs=1e-3)
    assert odom[60]["twist"] == pytest.approx([0.0, 0.0, 1.0], abs=1e-2)

    # One Range per sensor and step, as the in-process simulator's readings give them.
    frames = standard.sensor_frames(EPUCK)
    assert sorted(seen["ranges"]) == sorted(f"/{frame.frame}" for frame in frames)
    for index, frame in enumerate(frames):
        rows = seen["ranges"][f"/{frame.frame}"]
        assert len(rows) == len(expected)
        for row, (_, distances, time) in zip(rows, expected):
            assert row["frame"] == frame.frame and row["radiation_type"] == 1  # INFRARED
            assert (row["min_range"], row["max_range"]) == pytest.approx((0.0, 0.07))
            assert row["range"] == pytest.approx(distances[index], rel=1e-6)  # float32
            assert row["stamp"] == pytest.approx(time, abs=1e-9)
    assert any(math.isfinite(row["range"]) for rows in seen["ranges"].values() for row in rows)

    # The e-puck's sensors as one scan, as the ROS 2 bridge and Webots' e-puck driver build it
    # (a gmapping-style consumer of scan, odom and /tf reads it), stamped with each step.
    assert len(seen["scan"]) == len(expected)
    for row, (_, distances, time) in zip(seen["scan"], expected):
        assert row["frame"] == "laser_scanner" and row["stamp"] == pytest.approx(time, abs=1e-9)
        assert row["angles"] == pytest.approx(
            [-math.radians(150), math.radians(150), math.radians(15)]
        )
        assert row["limits"] == pytest.approx([0.044, 1.035])
        by_name = {frame.frame: distance for frame, distance in zip(frames, distances)}
        assert row["ranges"] == pytest.approx(standard.scan_ranges(by_name), rel=1e-6)

    # The sensor frames on the robot, and the scan's above it, sent once on /tf_static, and the
    # map's frame over odom's, the identity.
    statics = {row["child"]: row for row in seen["tf_static"]}
    assert sorted(statics) == sorted([*(frame.frame for frame in frames), "laser_scanner", "odom"])
    assert statics["odom"]["parent"] == "map"
    assert statics["odom"]["pose"] == [0.0, 0.0, 0.0]
    assert statics["laser_scanner"]["parent"] == "base_link"
    assert statics["laser_scanner"]["height"] == pytest.approx(0.033)
    for frame in frames:
        assert statics[frame.frame]["parent"] == "base_link"
        assert statics[frame.frame]["pose"] == pytest.approx([frame.x, frame.y, frame.yaw])


@needs_ros
def test_view_launch_runs_without_a_display(master: LocalMaster) -> None:
    launch, tag = spawn_launch(
        master, "view.launch", "world:=arena", "speed:=4", DISPLAY="", WAYLAND_DISPLAY=""
    )
    seen = run_probe(master, "count", "pose", "40")  # the robot drives in real time
    assert seen["data"]["pose"][-1][3] > seen["data"]["pose"][0][3]
    types = topic_types(master)
    assert types["/odom"] == "nav_msgs/Odometry" and types["/ps0"] == "sensor_msgs/Range"
    assert stop_launch(launch) == 0
    log = Path(master.log_path("roslaunch")).read_text()
    assert "rviz not started: no display" in log
    assert "Traceback" not in log, log[max(0, log.find("Traceback") - 400) :]
    assert processes_with("MAZESIM_TEST_LAUNCH", tag) == []


def test_every_ros_command_says_what_to_install_without_ros(tmp_path: Path) -> None:
    # As on a machine without Debian's ROS: its folder is not on the path.
    code = (
        "import sys\n"
        "sys.path[:] = [p for p in sys.path if not p.startswith('/usr/lib/python3/')]\n"
        "from mazesim.cli import main\n"
        "sys.exit(main(sys.argv[1:]))\n"
    )
    out = tmp_path / "demo"
    for command in (
        ["ros", "demo", "--out", str(out)],
        ["ros", "bridge"],
        ["ros", "avoid-collision"],
        ["ros", "perform-learning"],
    ):
        result = _run(code, command, tmp_path)
        assert result.returncode == 2, result.stderr
        lines = result.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("mazesim: error: "), result.stderr
        assert "missing rospy (python3-rospy)" in lines[0]
        assert "sensor_msgs (python3-sensor-msgs)" in lines[0]
        assert "make ros-deps" in lines[0] and "apt-get install" in lines[0]
    assert not out.exists()  # no master, no folder: it failed before starting anything
    assert list(tmp_path.iterdir()) == []


def _run(code: str, command: list[str], cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-c", code, *command],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )


def test_demo_command_names_a_missing_ros_tool(tmp_path: Path) -> None:
    code = (
        "import os, sys\n"
        "os.environ['PATH'] = '/nonexistent'\n"  # rospy importable, but no roscore or rosbag
        "from mazesim.cli import main\n"
        "sys.exit(main(sys.argv[1:]))\n"
    )
    result = _run(code, ["ros", "demo", "--out", str(tmp_path / "demo")], tmp_path)
    if "missing rospy" in result.stderr:
        pytest.skip("ROS 1 is not installed (run 'make ros-deps')")
    assert result.returncode == 2, result.stderr
    assert "the 'roscore' command" in result.stderr and "the 'rosbag' command" in result.stderr


@pytest.mark.parametrize(
    ("display", "has_rviz", "expected"),
    [
        (":0", True, "rviz -d {config}"),
        ("", True, "rviz not started: no display"),
        (":0", False, "rviz not started: no 'rviz' command"),
    ],
)
def test_rviz_opens_with_the_saved_config_only_where_it_can(
    tmp_path: Path, display: str, has_rviz: bool, expected: str
) -> None:
    fake_bin = tmp_path / "bin"
    fake_bin.mkdir()
    if has_rviz:  # a stand-in that says how it was started
        rviz = fake_bin / "rviz"
        rviz.write_text('#!/bin/sh\necho "rviz $*"\n')
        rviz.chmod(0o755)
    env = {"PATH": f"{fake_bin}:/usr/bin:/bin", "DISPLAY": display, "WAYLAND_DISPLAY": ""}
    result = subprocess.run(
        [sys.executable, str(REPO / "ros/mazesim_ros/nodes/rviz_if_display"), "__name:=rviz"],
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    assert result.returncode == 0, result.stderr  # never fails the launch
    config = REPO / "ros/mazesim_ros/rviz/mazesim.rviz"
    assert expected.format(config=config) in result.stdout


def test_the_ros_1_demo_refuses_a_world_of_several_robots() -> None:
    from mazesim.ros.bridge import refuse_several_robots

    world = mazesim.World.from_toml(
        'format = "mazesim-world"\nversion = 1\n'
        '[[robots]]\nname = "west"\nx = -0.2\ny = 0.0\n'
        '[[robots]]\nname = "east"\nx = 0.2\ny = 0.0\n'
    )
    with pytest.raises(
        InvalidArgumentError, match=r"holds 2 \(west, east\): run 'mazesim ros bridge'"
    ):
        refuse_several_robots(world)
    refuse_several_robots(mazesim.load_world("seed-maze"))  # one robot: accepted


@needs_ros
def test_a_node_waiting_for_the_map_gets_the_worlds_walls(master: LocalMaster) -> None:
    # rospy.wait_for_message("map", OccupancyGrid), as a planner waits for map_server's map:
    # latched, so it comes however late the node starts.
    spawn_bridge(master, "--world", "seed-maze")
    seen = run_probe(master, "map")
    cells, x0, y0 = occupied_cells(mazesim.load_world("seed-maze"))
    assert seen["frame"] == "map" and seen["resolution"] == pytest.approx(0.01)
    assert (seen["height"], seen["width"]) == cells.shape
    assert seen["origin"] == pytest.approx([x0, y0])
    assert seen["occupied"] == int((cells == 100).sum()) > 0
