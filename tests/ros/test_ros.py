"""The ROS 1 bridge: its pure parts, and integration tests against a real master.

The integration tests start ``roscore`` on a free loopback port for each test, run the nodes and
``tests/ros_probe.py`` (rospy allows one node per process) as subprocesses, and check at the end
that no process they started is left. This process never imports rospy.
"""

from __future__ import annotations

import json
import math
import re
import subprocess
import sys
import time
import types
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import mazesim
from mazesim.actions import wheel_speeds
from mazesim.controllers import AvoidCollision
from mazesim.errors import (
    InvalidActionError,
    InvalidArgumentError,
    MazesimError,
    MazesimIOError,
    UnknownNameError,
)
from mazesim.learn import load_policy
from mazesim.replay.ros_bag import read_topics
from mazesim.ros import topics
from mazesim.ros._ros import subscriber_count
from mazesim.ros.bag import BagWriter
from mazesim.ros.bridge import BridgeSettings, resolve_settings
from mazesim.ros.demo import goal_step
from mazesim.ros.local_master import LocalMaster
from mazesim.ros.perform_learning import control_step_value
from ros_support import (
    MAZESIM,
    needs_ros,
    processes_with,
    run_probe,
    spawn_bridge,
    spawn_launch,
    start_probe,
    stop_launch,
    wait_for_subscriber,
)

EPUCK_SENSORS = "ps0,ps1,ps2,ps3,ps4,ps5,ps6,ps7,gs0,gs1,gs2"
STEP_S = 0.032


# --- the parts that need no ROS ------------------------------------------------------------------


def test_motor_command_takes_two_finite_numbers() -> None:
    assert topics.motor_command((1.5, -2.0)) == (1.5, -2.0)
    for bad in ((), (1.0,), (1.0, 2.0, 3.0)):
        with pytest.raises(InvalidActionError, match="2 values"):
            topics.motor_command(bad)
    for bad in ((math.nan, 1.0), (1.0, math.inf), (-math.inf, 0.0)):
        with pytest.raises(InvalidActionError, match="finite"):
            topics.motor_command(bad)


def test_topic_layouts_per_robot() -> None:
    world = mazesim.load_world("seed-maze")
    epuck = mazesim.Simulator(world, robot="e-puck", seed=0)
    assert ",".join(topics.sensor_names(epuck)) == EPUCK_SENSORS
    assert len(topics.sensors_values(epuck)) == 11
    assert not topics.has_sharp_sensors(epuck)
    seed = mazesim.Simulator(world, robot="seed", seed=0)
    assert topics.has_sharp_sensors(seed)
    assert topics.sensor_names(seed) == [
        *("front", "back", "left", "right", "left-front", "right-front"),
        "gs",
    ]
    sensor_data = topics.sensor_data_values(seed)
    assert len(sensor_data) == 7
    assert all(3.0 <= distance <= 40.0 for distance in sensor_data[:6])
    assert sensor_data[6] == float(topics.current_checkpoint(seed))
    x, y, yaw = seed.pose
    assert topics.pose_values(seed) == [x, y, yaw, 0.0]


class _Parameters:
    """Stands in for rospy's parameter server in settings tests."""

    def __init__(self, **values: Any) -> None:
        self.values = {"~" + name: value for name, value in values.items()}

    def get_param(self, name: str, default: Any) -> Any:
        return self.values.get(name, default)


def test_bridge_settings_options_win_over_parameters() -> None:
    rospy = _Parameters(world="arena", seed=4, noise="false", speed=2, mode="realtime")
    settings = resolve_settings(rospy, {"seed": 9, "world": None})
    assert settings == BridgeSettings(
        world="arena", robot="e-puck", seed=9, mode="realtime", speed=2.0, noise=False
    )


@pytest.mark.parametrize(
    ("name", "value"),
    [
        ("mode", "fast"),
        ("speed", 0),
        ("speed", "x"),
        ("duration", -1.0),
        ("seed", 1.5),
        ("stop_at_goal", "maybe"),
        # A parameter's range is the option's: 1e9 s held a command for 31 years; a speed of
        # 1e-12 waited past the clock's range (an internal error); true was seed 1.
        ("command_period", 1e9),
        ("duration", 1e7),
        ("speed", 1e-12),
        ("seed", True),
        ("noise", 7.5),
    ],
)
def test_bad_bridge_parameter_is_named(name: str, value: Any) -> None:
    # A mode no bridge has is the one unknown-name refusal; a bad value of a known kind, the
    # argument refusal.
    refused = UnknownNameError if name == "mode" else InvalidArgumentError
    with pytest.raises(refused, match=f"parameter {name}"):
        resolve_settings(_Parameters(**{name: value}), {})


def test_settings_are_written_back_as_the_parameter_server_holds_them() -> None:
    # A seed of 3e9 (a valid seed) and a file name with a control character ended the bridge in
    # an internal error when written back over XML-RPC (32-bit integers, XML text).
    from mazesim.ros.bridge import xml_rpc_value

    assert xml_rpc_value(3_000_000_000) == "3000000000"
    settings = resolve_settings(_Parameters(seed="3000000000"), {})
    assert settings.seed == 3_000_000_000, "read back as the number"
    assert xml_rpc_value("/tmp/w\x01x.toml") is None
    assert xml_rpc_value("arena") == "arena" and xml_rpc_value(7) == 7 and xml_rpc_value(True)


def test_control_step_of_the_perform_learning_node_is_checked() -> None:
    assert control_step_value("control_step_ms", 32, allow_zero=False) == 32.0
    assert control_step_value("control_step_ms", "64.0", allow_zero=True) == 64.0
    assert control_step_value("control_step_ms", 0, allow_zero=True) == 0.0
    for bad in (0, -32, math.nan, math.inf, "fast", None, True):
        with pytest.raises(InvalidArgumentError, match="parameter control_step_ms"):
            control_step_value("control_step_ms", bad, allow_zero=False)


def test_the_nodes_wait_for_a_whole_number_of_subscribers() -> None:
    assert subscriber_count(_Parameters(), None) == 1
    assert subscriber_count(_Parameters(wait_for_subscribers=3), None) == 3
    assert subscriber_count(_Parameters(wait_for_subscribers=3), 2) == 2
    for bad in (0, -1, 1.5, "2", True):
        with pytest.raises(InvalidArgumentError, match="parameter wait_for_subscribers"):
            subscriber_count(_Parameters(wait_for_subscribers=bad), None)


def test_goal_step_is_the_first_pose_in_the_goal_disc() -> None:
    world = mazesim.load_world("seed-maze")
    assert world.goal is not None
    goal_x, goal_y, radius = world.goal
    poses = np.array(
        [
            [0.1, 0.1, 0.0, 0.0],
            [goal_x + 1.01 * radius, goal_y, 0.0, 0.032],
            [goal_x + 0.99 * radius, goal_y, 0.0, 0.064],
            [goal_x, goal_y, 0.0, 0.096],
        ]
    )
    assert goal_step(world, poses) == 2
    assert goal_step(world, poses[:2]) is None
    assert goal_step(mazesim.load_world("arena"), poses) is None  # no goal


def test_mazesim_and_its_ros_commands_import_without_rospy() -> None:
    code = (
        "import sys\n"
        "import mazesim, mazesim.cli, mazesim.ros.bridge, mazesim.ros.avoid_collision\n"
        "import mazesim.ros.perform_learning, mazesim.ros.demo\n"
        "mazesim.cli.build_parser()\n"
        "assert 'rospy' not in sys.modules, 'rospy was imported'\n"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr


def test_ros_help_lists_the_nodes(capsys: pytest.CaptureFixture[str]) -> None:
    from mazesim.cli import main

    assert main(["ros", "--help"]) == 0
    help_text = capsys.readouterr().out
    for node in ("bridge", "avoid-collision", "perform-learning", "demo"):
        assert node in help_text
    assert main(["ros", "bridge", "--help"]) == 0
    bridge_help = capsys.readouterr().out
    for option in ("--world", "--robot", "--seed", "--mode", "--speed", "--duration"):
        assert option in bridge_help
    assert "--stop-at-goal" in bridge_help
    assert main(["ros", "perform-learning", "--help"]) == 0
    learning_help = capsys.readouterr().out
    for option in ("--policy", "--control-step-ms", "--wait-for-subscribers"):
        assert option in learning_help
    assert main(["ros", "demo", "--help"]) == 0
    assert "--controller {hrl,avoid-collision}" in capsys.readouterr().out


@needs_ros
def test_hrl_demo_refuses_a_world_its_tables_do_not_know(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from mazesim.cli import main

    out = tmp_path / "demo"
    assert main(["ros", "demo", "--world", "arena", "--out", str(out)]) == 2
    error = capsys.readouterr().err
    assert "learned world 'seed-maze'" in error and "--controller avoid-collision" in error
    assert not out.exists()  # refused before starting anything


def test_the_demos_take_a_robot_profile_file_with_the_sensors_their_node_reads(
    tmp_path: Path,
) -> None:
    # mazesim ros demo ran the built-in seed or e-puck only, where every other command's --robot
    # takes a profile file too.
    epuck = tmp_path / "my-epuck.toml"
    epuck.write_text(mazesim.RobotProfile.builtin("e-puck").to_toml())
    seed = tmp_path / "my-seed.toml"
    seed.write_text(mazesim.RobotProfile.builtin("seed").to_toml())
    assert topics.demo_robot("hrl", None) == "seed"
    assert topics.demo_robot("avoid-collision", None) == "e-puck"
    assert topics.demo_robot("avoid-collision", str(epuck)) == str(epuck.resolve())
    assert topics.demo_robot("hrl", str(seed)) == str(seed.resolve())
    assert topics.demo_robot("avoid-collision", "e-puck2") == "e-puck2"
    with pytest.raises(InvalidArgumentError, match=r"six Sharp distance sensors.*ps0, ps1"):
        topics.demo_robot("hrl", str(epuck))
    with pytest.raises(InvalidArgumentError, match=r"ps0-ps7.*front, back"):
        topics.demo_robot("avoid-collision", str(seed))
    with pytest.raises(MazesimError):
        topics.demo_robot("hrl", str(tmp_path / "missing.toml"))


@needs_ros
def test_ros_demo_runs_a_robot_profile_file(tmp_path: Path) -> None:
    profile = tmp_path / "my-epuck.toml"
    profile.write_text(mazesim.RobotProfile.builtin("e-puck").to_toml())
    out = tmp_path / "demo"
    result = subprocess.run(
        [*MAZESIM, "ros", "demo", "--controller", "avoid-collision", "--robot", str(profile),
         "--world", "arena", "--seconds", "2", "--out", str(out)],
        capture_output=True, text=True, timeout=300, check=False,
    )  # fmt: skip
    assert result.returncode == 0, result.stdout + result.stderr
    assert "62 control steps" in result.stdout or "63 control steps" in result.stdout, result.stdout
    assert (out / "maze.bag").exists()


def test_node_without_rospy_fails_with_one_clear_line() -> None:
    code = (
        "import sys\n"
        "sys.modules['rospy'] = None\n"  # as if ROS were not installed
        "from mazesim.cli import main\n"
        "sys.exit(main(['ros', 'bridge']))\n"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert result.returncode == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("mazesim: error: "), result.stderr
    assert "make ros-deps" in lines[0]


# --- against a real master (the fixture ``master`` is in conftest.py) ---------------------------


def drive(
    master: LocalMaster, tmp_path: Path, commands: list[dict[str, Any]], mode: str = "drive"
) -> dict[str, Any]:
    path = tmp_path / "commands.json"
    path.write_text(json.dumps(commands))
    return run_probe(master, mode, str(path))


def replay(robot: str, seed: int, commands: list[dict[str, Any]]) -> dict[str, list[list[float]]]:
    """What the in-process simulator publishes for the same commands."""
    simulator = mazesim.Simulator(mazesim.load_world("seed-maze"), robot=robot, seed=seed)
    states: dict[str, list[list[float]]] = {"pose": [], "sensors": [], "sensor_data": []}

    def record() -> None:
        states["pose"].append(topics.pose_values(simulator))
        states["sensors"].append(topics.sensors_values(simulator))
        if topics.has_sharp_sensors(simulator):
            states["sensor_data"].append(topics.sensor_data_values(simulator))

    record()
    held = (0.0, 0.0)
    for command in commands:
        if command["steps"] == 0:
            continue
        try:
            if command["topic"] == "motor":
                held = topics.motor_command(command["data"])
            else:
                held = wheel_speeds(command["data"], simulator.robot.max_wheel_speed)
        except MazesimError:
            pass  # a refused command keeps the wheel speeds of the last one accepted
        simulator.step(*held)
        record()
    return states


def drive_in_process(
    controller: str, seed: int, max_steps: int, stop_at_goal: bool, world_name: str = "seed-maze"
) -> tuple[list[list[float]], int | None]:
    """The poses of a run without ROS: the shipped hierarchical policy on the seed robot, fed
    what ``sensor_data`` carries (``hrl``), or avoid-collision on the e-puck. Returns the poses
    (``pose`` rows, the start included) and the step at which the robot reached the goal (None
    without one)."""
    world = mazesim.load_world(world_name)
    goal_x, goal_y, radius = world.goal if world.goal is not None else (math.inf, math.inf, 0.0)
    robot = "seed" if controller == "hrl" else "e-puck"
    simulator = mazesim.Simulator(world, robot=robot, seed=seed)
    policy = load_policy()
    policy.reset(control_step_ms=simulator.control_step_ms)
    avoid = AvoidCollision()
    poses = [topics.pose_values(simulator)]
    reached = None
    while simulator.steps < max_steps:
        if controller == "hrl":
            values = topics.sensor_data_values(simulator)
            code = policy.act(np.asarray(values[:6]), int(values[6]))
            simulator.step(*wheel_speeds(code, simulator.robot.max_wheel_speed))
        else:
            simulator.step(*avoid(simulator.distance_sensors()))
        poses.append(topics.pose_values(simulator))
        x, y, _ = simulator.pose
        if reached is None and math.hypot(x - goal_x, y - goal_y) <= radius:
            reached = simulator.steps
            if stop_at_goal:
                break
    return poses, reached


def assert_poses_of_the_in_process_run(
    rows: list[list[float]], controller: str, seed: int, world_name: str
) -> None:
    """Asserts that ``rows`` (``pose`` messages a probe caught from a lockstep run it joined at
    some step) are the in-process run's poses at the steps their times say, bit for bit, and
    that the robot moved between them: true of any steps the probe catches."""
    steps = [round(row[3] / STEP_S) for row in rows]
    expected, _ = drive_in_process(controller, seed, max(steps), False, world_name)
    assert rows == [expected[step] for step in steps]  # bit for bit
    assert len({tuple(row[:3]) for row in rows}) > 1  # the robot moves


def echoed_data(echo: str) -> list[float]:
    """The ``data`` field of a message printed by ``rostopic echo``."""
    match = re.search(r"^data: (\[.*\])$", echo, flags=re.MULTILINE)
    assert match, echo
    return list(json.loads(match.group(1)))


def motor_commands(count: int, seed: int) -> list[dict[str, Any]]:
    rng = np.random.default_rng(seed)
    # Mostly forward, some turns, some speeds beyond the motor limit (clamped by the bridge).
    speeds = rng.uniform(-3.0, 8.0, size=(count, 2))
    return [{"topic": "motor", "data": [float(a), float(b)], "steps": 1} for a, b in speeds]


@needs_ros
def test_bridge_and_avoid_collision_move_the_robot(master: LocalMaster) -> None:
    spawn_bridge(master, "--world", "seed-maze", "--seed", "3")
    # Two subscribers of its commands, the bridge and the probe below: a node waiting for one
    # could start on the probe's alone and send its first command before the bridge listens,
    # and a lockstep bridge then waits for a command that never comes.
    master.spawn(
        "avoid-collision", [*MAZESIM, "ros", "avoid-collision", "--wait-for-subscribers", "2"]
    )
    run_probe(master, "count", "motor", "1")  # the node drives (its start can take seconds)
    # The probe joins the run at a step that depends on the load: every check below holds for
    # any 60 steps (waiting for 60 /clock messages too, since each topic's connection comes up
    # on its own).
    seen = run_probe(master, "count-with-clock", "pose", "60")

    clock = seen["clock"]
    assert len(clock) >= 60 and clock[-1] > clock[0] and clock == sorted(clock)
    poses = np.array(seen["data"]["pose"])
    assert poses.shape[1] == 4
    np.testing.assert_allclose(np.diff(poses[:, 3]), STEP_S, atol=1e-9)
    assert_poses_of_the_in_process_run(seen["data"]["pose"], "avoid-collision", 3, "seed-maze")
    assert seen["labels"]["pose"] == "x,y,yaw,time"

    # rostopic, as a user would run it; the three calls run side by side to save time.
    calls = {
        "list": ["rostopic", "list", "-v"],
        "sensors": ["rostopic", "echo", "-n", "1", "/sensors"],
        "motor": ["rostopic", "echo", "-n", "1", "/motor"],
    }
    running = {
        name: subprocess.Popen(
            argv, env=master.env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
        )
        for name, argv in calls.items()
    }
    results = {}
    try:
        for name, process in running.items():
            results[name] = process.communicate(timeout=300)
    finally:
        for process in running.values():
            if process.poll() is None:
                process.kill()
                process.communicate()
    for name, process in running.items():
        assert process.returncode == 0, results[name][1]
    output = {name: stdout for name, (stdout, _) in results.items()}

    # "rostopic list -v": " * /topic [type] N publishers" under Published and Subscribed topics.
    published, subscribed = output["list"].split("Subscribed topics:")
    types = dict(re.findall(r"\* (/\w+) \[([\w/]+)\]", published))
    assert types["/sensors"] == types["/pose"] == "std_msgs/Float64MultiArray"
    assert types["/clock"] == "rosgraph_msgs/Clock"
    assert types["/motor"] == "std_msgs/Float64MultiArray"  # the avoid-collision node's
    assert "/sensor_data" not in types  # the e-puck has no Sharp sensors
    assert "* /action [std_msgs/String]" in subscribed
    sensors = output["sensors"]
    assert f'label: "{EPUCK_SENSORS}"' in sensors
    values = echoed_data(sensors)
    assert len(values) == 11
    assert all(0.0 <= value <= 4095.0 for value in values[:8])
    assert all(250.0 <= value <= 1100.0 for value in values[8:])
    left, right = echoed_data(output["motor"])
    assert {left, right} <= {0.0, 3.14, 6.28}


@needs_ros
@pytest.mark.parametrize("mode, resets", [("drive", 1), ("drive-from-second", 2)])
def test_lockstep_trajectory_equals_in_process_simulator(
    master: LocalMaster, tmp_path: Path, mode: str, resets: int
) -> None:
    # drive-from-second leaves the reset state unanswered, as a controller that answers only its
    # second message, or whose first command went out before the bridge listened: the bridge
    # publishes the reset state again, where both once waited for each other.
    commands = motor_commands(150, seed=11)
    spawn_bridge(master, "--seed", "11")
    seen = drive(master, tmp_path, commands, mode)
    expected = replay("e-puck", 11, commands)
    again = resets - 1
    assert seen["data"]["pose"] == expected["pose"][:1] * again + expected["pose"]  # bit for bit
    assert seen["data"]["sensors"] == expected["sensors"][:1] * again + expected["sensors"]
    assert seen["labels"]["sensors"] == EPUCK_SENSORS


@needs_ros
def test_a_state_left_unanswered_goes_out_again_and_the_run_stays_the_in_process_run(
    master: LocalMaster, tmp_path: Path
) -> None:
    # A controller that lets one state go unanswered (a lifecycle node paused and resumed) once
    # waited for the next state while the bridge waited for its command: the ROS 2 bridge sent
    # the last state again, this one did not. Both now share one rule.
    commands = motor_commands(30, seed=7)
    spawn_bridge(master, "--seed", "7")
    seen = drive(master, tmp_path, commands, "drive-skipping")
    expected = replay("e-puck", 7, commands)
    # The state after the 10th command came twice, as it went out; then the run went on.
    assert seen["data"]["pose"] == expected["pose"][:11] + expected["pose"][10:]  # bit for bit
    assert seen["data"]["sensors"] == expected["sensors"][:11] + expected["sensors"][10:]


@needs_ros
def test_a_controller_that_sleeps_on_simulated_time_first_starts_in_lockstep(
    master: LocalMaster, tmp_path: Path
) -> None:
    # teleop_twist_keyboard looks for a subscriber, rospy.sleep(0.5) between looks: on the
    # simulated time the bridge sets, in lockstep, that sleep never ended. /clock now runs on its
    # own once the reset state sent again goes unanswered, the simulator standing still: the
    # run is the in-process run, bit for bit, its clock a whole number of steps later.
    master.set_param("/use_sim_time", True)
    commands = motor_commands(40, seed=5)
    spawn_bridge(master, "--seed", "5")
    seen = drive(master, tmp_path, commands, "drive-after-sleep")
    expected = replay("e-puck", 5, commands)
    # The reset state went out again (5 s without a command) before the clock ran.
    again = len(seen["data"]["pose"]) - len(expected["pose"])
    assert again >= 1
    assert seen["data"]["pose"] == expected["pose"][:1] * again + expected["pose"]  # bit for bit
    assert seen["data"]["sensors"] == expected["sensors"][:1] * again + expected["sensors"]
    ahead = seen["clock"][-1] - 40 * 0.032
    assert ahead >= 0.5 - 0.032 and abs(ahead / 0.032 - round(ahead / 0.032)) < 1e-6


@needs_ros
def test_lockstep_actions_drive_the_seed_robot(master: LocalMaster, tmp_path: Path) -> None:
    # Straight on across the first barcode (about step 128), then turns, spins, backing up.
    codes = ["00"] * 140 + ["44"] * 10 + ["aa"] * 12 + ["88", "bb", "99", "11"] * 5
    commands = [{"topic": "action", "data": code, "steps": 1} for code in codes]
    commands += motor_commands(5, seed=2)  # motor and action commands mix
    spawn_bridge(master, "--robot", "seed", "--seed", "4")
    seen = drive(master, tmp_path, commands)
    expected = replay("seed", 4, commands)
    assert seen["data"]["pose"] == expected["pose"]
    assert seen["data"]["sensors"] == expected["sensors"]
    assert seen["data"]["sensor_data"] == expected["sensor_data"]
    assert seen["labels"]["sensors"] == "front,back,left,right,left-front,right-front,gs"
    assert seen["labels"]["sensor_data"].endswith(",right-front cm,checkpoint")
    assert all(len(row) == 7 for row in seen["data"]["sensor_data"])
    checkpoints = [row[6] for row in seen["data"]["sensor_data"]]
    assert 1.0 in checkpoints  # the crossing of checkpoint 1, arriving


GOAL_LINE = re.compile(
    r"reached the goal of seed-maze at step (\d+) \(([\d.]+) s simulated\), "
    r"at x ([-\d.]+) m, y ([-\d.]+) m"
)


@needs_ros
def test_perform_learning_drives_the_seed_robot_to_the_goal(master: LocalMaster) -> None:
    world = mazesim.load_world("seed-maze")
    assert world.goal is not None
    goal_x, goal_y, radius = world.goal
    bridge = spawn_bridge(
        master, "--robot", "seed", "--seed", "7", "--stop-at-goal", "--duration", "120"
    )
    master.spawn("perform-learning", [*MAZESIM, "ros", "perform-learning"])
    assert bridge.wait(timeout=600) == 0  # it stops by itself: the goal, or 120 s simulated

    # What the bridge reports: the goal reached, where, and that it stopped right there.
    log = Path(master.log_path("bridge")).read_text()
    assert "Traceback" not in log, log[max(0, log.find("Traceback") - 400) :]
    found = GOAL_LINE.search(log)
    assert found, log
    steps, x, y = int(found[1]), float(found[3]), float(found[4])
    assert float(found[2]) == pytest.approx(steps * STEP_S)
    assert math.hypot(x - goal_x, y - goal_y) <= radius
    assert steps < 120.0 / STEP_S
    assert f"mazesim bridge stopped: {steps} steps" in log
    assert f"goal reached at step {steps};" in log
    node_log = Path(master.log_path("perform-learning")).read_text()
    assert "actions of 32 ms" in node_log  # the bridge's control step, read from its parameter

    # The node drove as the policy does in process on the same readings, step for step.
    poses, reached = drive_in_process("hrl", seed=7, max_steps=steps, stop_at_goal=True)
    assert reached == steps
    assert (f"{poses[-1][0]:.4f}", f"{poses[-1][1]:.4f}") == (found[3], found[4])


@needs_ros
def test_perform_learning_with_unusable_tables_fails_clearly(
    master: LocalMaster, tmp_path: Path
) -> None:
    node = master.spawn(
        "perform-learning",
        [*MAZESIM, "ros", "perform-learning", "--policy", str(tmp_path / "no-tables")],
    )
    assert node.wait(timeout=300) == 2
    lines = Path(master.log_path("perform-learning")).read_text().strip().splitlines()
    assert lines[-1].startswith("mazesim: error: "), lines
    assert "policy.json: no such file" in lines[-1]
    assert not any("Traceback" in line for line in lines)


@needs_ros
def test_a_refused_command_steps_with_the_wheel_speeds_before(
    master: LocalMaster, tmp_path: Path
) -> None:
    # As the ROS 2 bridge: a node answering each state with one command, one of them refused,
    # gets the next state, the robot keeping the wheel speeds of the command before.
    bad = [
        {"topic": "motor", "data": [1.0], "steps": 1},
        {"topic": "motor", "data": [], "steps": 1},
        {"topic": "motor", "data": [1.0, 2.0, 3.0], "steps": 1},
        {"topic": "motor", "data": [math.nan, 1.0], "steps": 1},
        {"topic": "motor", "data": [1.0, math.inf], "steps": 1},
        {"topic": "action", "data": "zz", "steps": 1},
        {"topic": "action", "data": "", "steps": 1},
    ]
    good = [
        {"topic": "motor", "data": [2.0, 2.5], "steps": 1},
        {"topic": "motor", "data": [100.0, -100.0], "steps": 1},  # clamped to the motor limit
        {"topic": "action", "data": "00", "steps": 1},
    ]
    commands = [*bad, good[0], *bad, *good[1:]]
    bridge = spawn_bridge(master, "--seed", "6")
    seen = drive(master, tmp_path, commands)
    assert bridge.poll() is None  # still running
    expected = replay("e-puck", 6, commands)
    assert seen["data"]["pose"] == expected["pose"]
    assert len(seen["data"]["pose"]) == len(commands) + 1
    # The refused commands after [2.0, 2.5] drove on with it: the robot moved while they came.
    moving = seen["data"]["pose"][8:16]
    assert all(later[:2] != before[:2] for before, later in zip(moving, moving[1:]))
    log = Path(master.log_path("bridge")).read_text()
    assert log.count("ignored a bad motor message") == 10
    assert log.count("ignored a bad action message") == 4
    assert "keeps its wheel speeds for that step" in log
    assert "Traceback" not in log, log[max(0, log.find("Traceback") - 400) :]


@needs_ros
def test_realtime_mode_follows_the_wall_clock(master: LocalMaster) -> None:
    # The bridge never runs ahead of its schedule: step k at the earliest (k - 1) periods of
    # 8 ms after it started, which is after `started`. (How far it falls behind depends on the
    # load, and it catches up in bursts, so a rate measured over the probe's window is no check.)
    started = time.monotonic()
    spawn_bridge(master, "--mode", "realtime", "--speed", "4")
    seen = run_probe(master, "count", "pose", "100")  # 3.2 simulated s, about 0.8 s of wall clock
    elapsed = time.monotonic() - started
    poses = np.array(seen["data"]["pose"])
    assert np.all(np.diff(poses[:, 3]) > 0)  # no command: it steps on its own
    assert np.all(poses[:, :3] == poses[0, :3])  # no command: the robot stays
    assert poses[-1, 3] <= 4.0 * elapsed + STEP_S  # paced: a free-running bridge is far ahead


@needs_ros
def test_launch_file_runs_and_stops_without_leftovers(master: LocalMaster) -> None:
    launch, tag = spawn_launch(master, "maze.launch", "world:=arena", "seed:=2")
    seen = run_probe(master, "count", "pose", "100")
    poses = np.array(seen["data"]["pose"])
    assert poses[-1, 3] > poses[0, 3]
    # The controller drives the robot as it does in process, whichever 100 steps the probe
    # caught (it joins the run at a step that depends on the load).
    assert_poses_of_the_in_process_run(seen["data"]["pose"], "avoid-collision", 2, "arena")

    assert stop_launch(launch) == 0  # SIGINT, as Ctrl-C
    assert processes_with("MAZESIM_TEST_LAUNCH", tag) == []


@needs_ros
def test_learning_launch_stops_at_the_goal_without_leftovers(
    master: LocalMaster, tmp_path: Path
) -> None:
    bag = tmp_path / "learning.bag"
    launch, tag = spawn_launch(master, "learning.launch", "seed:=2", "record:=true", f"bag:={bag}")
    # The bridge is required: it stops at the goal, and the launch with it.
    assert launch.wait(timeout=300) == 0
    log = Path(master.log_path("roslaunch")).read_text()
    found = GOAL_LINE.search(log)
    assert found, log
    _, reached = drive_in_process("hrl", seed=2, max_steps=int(found[1]), stop_at_goal=True)
    assert reached == int(found[1])
    assert f"goal reached at step {found[1]};" in log
    assert "Traceback" not in log, log[max(0, log.find("Traceback") - 400) :]
    assert processes_with("MAZESIM_TEST_LAUNCH", tag) == []
    # record:=true: the bridge's own bag holds every step, the first ones too.
    steps = int(found[1])
    recorded = read_topics(str(bag), ("/pose", "/action"))
    assert [len(recorded["/pose"]), len(recorded["/action"])] == [steps + 1, steps]
    assert recorded["/pose"][0][3] == 0.0


@needs_ros
@pytest.mark.parametrize(
    ("controller", "seconds", "seed"),
    [("hrl", 60.0, 0), ("avoid-collision", 3.0, 5)],  # hrl: what `make ros-demo` runs
)
def test_recorded_run_plays_back_and_equals_in_process_run(
    tmp_path: Path, controller: str, seconds: float, seed: int
) -> None:
    out = tmp_path / "demo"
    command = [*MAZESIM, "ros", "demo", "--controller", controller, "--out", str(out)]
    command += ["--seconds", str(seconds), "--seed", str(seed)]
    result = subprocess.run(command, capture_output=True, text=True, timeout=300, check=False)
    assert result.returncode == 0, result.stderr
    bag = out / "maze.bag"
    assert str(bag) in result.stdout and (out / "trajectory.png").is_file()
    assert "left behind" not in result.stdout

    # The bridge with the controller node over ROS drove exactly as in process (the hierarchical
    # policy up to the goal, where the bridge stops).
    hrl = controller == "hrl"
    expected, reached = drive_in_process(
        controller, seed, max_steps=math.ceil(seconds / STEP_S), stop_at_goal=hrl
    )
    steps = len(expected) - 1
    if hrl:
        assert reached == steps
        assert f"reached at step {steps} " in result.stdout
    else:
        assert "goal               not reached" in result.stdout

    info = subprocess.run(["rosbag", "info", str(bag)], capture_output=True, text=True, timeout=300)
    assert info.returncode == 0, info.stderr
    counts = {topic: int(n) for topic, n in re.findall(r"(/\w+)\s+(\d+) msgs", info.stdout)}
    # The bridge writes its own bag: every step's state once, every command it took.
    for topic in ("/pose", "/sensors", *(["/sensor_data"] if hrl else [])):
        assert counts[topic] == steps + 1, (counts, steps)
    assert counts["/clock"] >= steps + 1, (counts, steps)  # with ticks before a first command
    assert counts["/action" if hrl else "/motor"] == steps, (counts, steps)
    assert ("/motor" if hrl else "/action") not in counts

    player = LocalMaster(home=str(tmp_path / "play"))
    player.start()
    try:
        probe = start_probe(player.env, "count", "pose", str(steps + 1))
        try:
            wait_for_subscriber(player, "/pose")
            play = subprocess.run(
                [
                    "rosbag",
                    "play",
                    "--quiet",
                    "--wait-for-subscribers",
                    str(bag),
                    "--topics",
                    "/pose",
                ],
                env=player.env,
                capture_output=True,
                text=True,
                timeout=300,
                check=False,
            )
            assert play.returncode == 0, play.stderr
            stdout, stderr = probe.communicate(timeout=300)
        finally:
            if probe.poll() is None:
                probe.kill()
                probe.wait()
        assert probe.returncode == 0, stderr
    finally:
        left_behind = player.close()
    assert left_behind == [] and player.leftovers() == []
    played = json.loads(stdout.strip().splitlines()[-1])["data"]["pose"]
    assert played == expected


@needs_ros
def test_the_bridges_bag_is_named_only_when_finished_and_refuses_a_folder(tmp_path: Path) -> None:
    import rospy
    from std_msgs.msg import String

    ros = types.SimpleNamespace(rospy=rospy)
    with pytest.raises(MazesimIOError, match=r"expected a bag file to write; found the folder"):
        BagWriter(ros, str(tmp_path))
    path = tmp_path / "run.bag"
    writer = BagWriter(ros, str(path))
    writer.write("/note", String(data="one"))
    assert not path.exists() and (tmp_path / "run.bag.active").is_file()  # never half-written
    writer.close()
    writer.close()
    writer.write("/note", String(data="after"))  # ignored once closed
    assert path.is_file() and not (tmp_path / "run.bag.active").exists()
    assert read_topics(str(path), ("/note",))["/note"] == ["one"]


def rate_holds(
    period_s: float, count: int, step_ns: int = 32_000_000, first_ns: int = 1
) -> list[int]:
    """How many control steps each of ``count`` commands holds for a ``rospy.Rate`` made at the
    reset state (stamped 1 ns): from the state it answers (the first stamped ``first_ns``) to
    the first at or after the rate's next tick, 1 ns plus a multiple of the period."""
    period_ns, now, holds = round(period_s * 1e9), first_ns, []
    for _ in range(count):
        tick = 1 + ((now - 1) // period_ns + 1) * period_ns
        steps = 0
        while now < tick:
            now = (now // step_ns + 1) * step_ns
            steps += 1
        holds.append(steps)
    return holds


@needs_ros
def test_a_goal_follower_gets_the_state_again_once_its_goal_came(master: LocalMaster) -> None:
    # A goal follower without actionlib ignores odometry until a goal comes on
    # move_base_simple/goal (rviz's 2D Nav Goal), then answers each odom. The reset state had
    # gone by: it waited for that state sent again 5 s after it went out. The bridge notes the
    # goal and, with no command 0.5 s later, publishes the state again.
    spawn_bridge(master, "--seed", "2", "--duration", str(10 * 0.032))
    seen = run_probe(master, "drive-after-goal", "10")
    assert seen["answered"][0] < 1e-6  # the reset state, stamped 1 ns
    assert seen["answered"][1:] == pytest.approx([step * 0.032 for step in range(1, 10)])
    log = Path(master.log_path("bridge")).read_text()
    assert "a goal came on /move_base_simple/goal and no command" in log


@needs_ros
def test_a_node_making_its_publisher_after_its_subscription_gets_the_state_once_it_has_one(
    master: LocalMaster,
) -> None:
    # A node subscribing odom, loading something for a second, then making its cmd_vel publisher
    # got the latched state before it had one, skipped it, and waited 5 s for the state sent
    # again; a node answering at once lost its first command when the bridge had not connected
    # to its publisher yet. The state waits for a command writer to connect.
    spawn_bridge(master, "--seed", "1", "--duration", str(6 * 0.032))
    seen = run_probe(master, "publisher-after", "6", "1.0")
    log = Path(master.log_path("bridge")).read_text()
    assert seen["answered"] == pytest.approx([1e-9] + [step * 0.032 for step in range(1, 6)]), (
        seen,
        log,
    )
    assert seen["odometry"][: len(seen["answered"])] == seen["answered"], (seen, log)
    assert "publishing the reset state again" not in log


@needs_ros
def test_a_node_started_before_the_bridge_gets_the_reset_state_once_it_has_a_publisher(
    master: LocalMaster,
) -> None:
    # The node subscribed odom before the bridge started: it connected as the bridge advertised
    # its publishers, and the reset state published on the wire reached it before its cmd_vel
    # publisher existed (skipped, then 5 s waiting for the state sent again). The reset state
    # is handed over as to any late connection (the node makes its publisher a second after
    # its subscription connected).
    probe = start_probe(master.env, "publisher-after", "6", "1.0", "connected")
    try:
        wait_for_subscriber(master, "/odom")
        spawn_bridge(master, "--seed", "1", "--duration", str(6 * 0.032))
        out, err = probe.communicate(timeout=600)
    except BaseException:
        probe.kill()
        probe.communicate()
        raise
    assert probe.returncode == 0, out + err
    seen = json.loads(out.strip().splitlines()[-1])
    log = Path(master.log_path("bridge")).read_text()
    assert seen["odometry"][:6] == seen["answered"], (seen, log)  # the reset state once
    assert seen["answered"] == pytest.approx([1e-9] + [step * 0.032 for step in range(1, 6)])
    assert "publishing the reset state again" not in log


@needs_ros
@pytest.mark.parametrize("delay_s", [0.0, 4.0])
def test_a_late_subscription_gets_the_state_once_in_the_order_it_went_out(
    master: LocalMaster, delay_s: float
) -> None:
    # A recorder of pose connected before the driver, and a Bug-like node whose scan subscription
    # connects before its odom one and skips scans until an odometry has come. rospy's latch gave
    # the node the scan first: it skipped it and answered the state sent again 5 s later.
    # Started delay_s after the recorder, the node connects about 5 s after the bridge did (a
    # slow start under load): the reset state went out again as it connected, counted from the
    # bridge's start and not from the hand-over (the recorder had it twice, or the node answered
    # it twice and ran a step behind).
    spawn_bridge(master, "--seed", "3", "--duration", str(10 * 0.032))
    recorder = start_probe(master.env, "count", "pose", "11")
    try:
        wait_for_subscriber(master, "/pose")
        time.sleep(delay_s)
        seen = run_probe(master, "scan-with-odom", "10")
        log = Path(master.log_path("bridge")).read_text()
        print(log, *connection_lines(master), sep="\n")  # shown in full if an assertion fails
        assert seen["answered"] == pytest.approx(
            [1e-9] + [step * 0.032 for step in range(1, 10)]
        ), (seen, log)
        assert seen["scans"][: len(seen["answered"])] == seen["answered"], (seen, log)  # each once
    except BaseException:
        recorder.kill()  # not left running (and its pipes open) for later tests to find
        recorder.communicate()
        raise
    out, err = recorder.communicate(timeout=600)
    assert recorder.returncode == 0, out + err
    poses = json.loads(out.strip().splitlines()[-1])["data"]["pose"]
    assert [round(pose[3] / 0.032) for pose in poses] == list(range(11))  # each state once
    assert "publishing the reset state again" not in log


def connection_lines(master: LocalMaster) -> list[str]:
    """What rospy logged of each connection added or removed, in every node's log file."""
    return [
        f"{path.name}: {line}"
        for path in sorted(Path(master.log_path("bridge")).parent.rglob("*.log"))
        for line in path.read_text(errors="replace").splitlines()
        if "adding connection" in line or "removing connection" in line
    ]


@needs_ros
def test_the_bridge_reads_each_node_s_topics_from_the_master(
    master: LocalMaster, monkeypatch: pytest.MonkeyPatch
) -> None:
    # The late hand-over waits for every subscription the master lists for a node.
    from mazesim.ros._ros import require_ros, topics_of_nodes

    recorder = start_probe(master.env, "count", "pose", "1")
    try:
        wait_for_subscriber(master, "/pose")
        monkeypatch.setenv("ROS_MASTER_URI", master.uri)
        subscribed, published = topics_of_nodes(require_ros())
        names = [node for node, topics in subscribed.items() if "/pose" in topics]
        assert [subscribed[node] for node in names] == [{"/pose", "/clock"}]
        assert "/rosout" in published[names[0]]  # every rospy node publishes its log
    finally:
        recorder.kill()
        recorder.communicate()


def commands_on_sim_time(
    master: LocalMaster, tmp_path: Path, seed: int, *bridge_options: str
) -> tuple[list[dict[str, Any]], Path]:
    """Sets ``/use_sim_time``, starts the bridge with noise seed ``seed`` and the options, and
    writes 20 motor commands of that seed to a file; returns them and the file."""
    master.set_param("/use_sim_time", True)
    commands = motor_commands(20, seed=seed)
    path = tmp_path / "commands.json"
    path.write_text(json.dumps(commands))
    spawn_bridge(master, "--seed", str(seed), *bridge_options)
    return commands, path


@needs_ros
def test_a_controller_at_a_rospy_rate_drives_in_lockstep_with_command_period(
    master: LocalMaster, tmp_path: Path
) -> None:
    # A controller commanding at rospy.Rate(10) on simulated time stepped once and then slept
    # for a tick that never came: time moved on commands only. With --command-period each
    # command holds until the clock reaches the rate's next tick (the ROS 2 bridge's rule):
    # the run is the in-process run holding each command over those steps, bit for bit.
    commands, path = commands_on_sim_time(master, tmp_path, 4, "--command-period", "0.1")
    seen = run_probe(master, "drive-at-rate", "0.1", str(path))
    holds = rate_holds(0.1, len(commands))
    assert holds[:3] == [4, 3, 3] and holds[7] == 4  # the tick at 0.8 s falls on a step
    held = [command for command, steps in zip(commands, holds) for _ in range(steps)]
    expected = replay("e-puck", 4, held)
    assert len(seen["data"]["pose"]) == sum(holds) + 1
    assert seen["data"]["pose"] == expected["pose"]  # bit for bit
    assert seen["data"]["sensors"] == expected["sensors"]


@needs_ros
def test_a_tick_let_go_holds_the_last_command_on_to_the_next_tick(
    master: LocalMaster, tmp_path: Path
) -> None:
    # A node pairing each scan with the /tf of its stamp at each tick of a rospy.Timer (a SLAM
    # front-end) found, at a tick, the scan come and its transform not yet, the two arriving on
    # connections of their own: it let the tick go, and the clock waited for a command (3 runs
    # of 5 stalled with --command-period). The bridge now holds the last command on to the next
    # tick once SKIPPED_TICK_S pass without one: the in-process run with it held over both.
    commands, path = commands_on_sim_time(master, tmp_path, 5, "--command-period", "0.1")
    commands = commands[:8]
    path.write_text(json.dumps(commands))
    seen = run_probe(master, "drive-letting-a-tick-go", "0.1", str(path), "3")
    ticks = rate_holds(0.1, len(commands) + 1)
    holds = [*ticks[:2], ticks[2] + ticks[3], *ticks[4:]]  # the third command's two periods
    held = [command for command, steps in zip(commands, holds) for _ in range(steps)]
    expected = replay("e-puck", 5, held)
    assert seen["data"]["pose"] == expected["pose"]  # bit for bit
    assert seen["data"]["sensors"] == expected["sensors"]


@needs_ros
def test_a_controller_on_a_rospy_timer_drives_in_lockstep_with_command_period(
    master: LocalMaster, tmp_path: Path
) -> None:
    # A controller whose commands go out from a rospy.Timer(rospy.Duration(0.1)) made in its
    # constructor, on simulated time still at zero (its ticks at the multiples of 0.1 s, 1 ns
    # before the bridge's): without --command-period it sent 1 command of 20 in lockstep and
    # waited for a tick that never came; with it, the run is the in-process run holding each
    # command until the timer's next tick, bit for bit.
    commands, path = commands_on_sim_time(master, tmp_path, 6, "--command-period", "0.1")
    # The clock runs on its own once the reset state, sent again, goes unanswered, and waits at
    # the timer's first tick (0.128 s, 4 steps standing still) for its command.
    holds = rate_holds(0.1, len(commands), first_ns=4 * 32_000_000)
    assert holds[:3] == [3, 3, 3]
    seen = run_probe(master, "drive-on-timer", "0.1", str(path), str(sum(holds) + 1))
    held = [command for command, steps in zip(commands, holds) for _ in range(steps)]
    expected = replay("e-puck", 6, held)
    poses, sensors = seen["data"]["pose"], seen["data"]["sensors"]
    # The reset state as often as the probe received it: a probe whose subscriptions connected
    # only after the state was sent again (a loaded machine) has it once, from the hand-over to
    # late subscriptions, so how many copies it holds says nothing of the bridge.
    again = len(poses) - len(expected["pose"])
    assert again >= 0
    assert poses == expected["pose"][:1] * again + expected["pose"]  # bit for bit
    assert sensors == expected["sensors"][:1] * again + expected["sensors"]
    # What the timer needs, whatever the load: the reset state went out again unanswered, then
    # /clock ran on its own to the timer's first tick (4 steps) and waited there.
    log = Path(master.log_path("bridge")).read_text()
    assert "publishing the reset state again" in log
    assert "/clock now runs on its own" in log
    assert seen["clock"][-1] == pytest.approx((4 + sum(holds)) * 0.032)


@needs_ros
def test_a_controller_sleeping_after_each_command_drives_with_a_command_deadline(
    master: LocalMaster, tmp_path: Path
) -> None:
    # A controller that sleeps 0.1 s of simulated time after each command (rospy.sleep, counted
    # from whenever it starts, so no period the bridge is given foresees its ticks) stepped the
    # bridge once and slept on a clock that moved on commands only. With --command-deadline the
    # bridge steps on with the last command held once none has come within the deadline.
    master.set_param("/use_sim_time", True)
    commands = motor_commands(10, seed=4)
    path = tmp_path / "commands.json"
    path.write_text(json.dumps(commands))
    spawn_bridge(master, "--seed", "4", "--command-deadline", "0.2")
    seen = run_probe(master, "drive-sleeping", "0.1", str(path))
    poses = seen["data"]["pose"]
    # Each sleep of 0.1 s spans at least three 32 ms steps: some steps came without a command.
    assert len(poses) >= 3 * len(commands)
    # Every step is the in-process step with the last command held: each recorded pose is the
    # simulator's after one step with the command before, or with the next command.
    simulator = mazesim.Simulator(mazesim.load_world("seed-maze"), robot="e-puck", seed=4)
    assert topics.pose_values(simulator) == poses[0]
    speeds = [topics.motor_command(command["data"]) for command in commands]
    current = -1
    for pose in poses[1:]:
        before = simulator.snapshot()
        if current >= 0:
            simulator.step(*speeds[current])
            if topics.pose_values(simulator) == pose:
                continue
            simulator.restore(before)
        current += 1
        assert current < len(speeds), pose
        simulator.step(*speeds[current])
        assert topics.pose_values(simulator) == pose  # bit for bit
    assert current == len(speeds) - 1
