"""Issue 37: a profile file's robot keeps its own profile wherever it goes: the demo's recording and
its replay (the run file holds the profile, so it replays after the file changes or is gone), a
world of several robots, an evaluation's recording and a gymnasium env's picture; none of them
rebuilds it from its name."""

from __future__ import annotations

import json
from pathlib import Path

import gymnasium
import numpy as np
import pytest
from robots_world import THREE_ROBOTS

import mazesim
from mazesim import RobotProfile, Simulator
from mazesim.cli import main
from mazesim.errors import RunFormatError
from mazesim.replay.recorder import FleetRecorder
from mazesim.replay.run import load_run


def _big_slow_epuck(folder: Path) -> Path:
    """The e-puck's profile renamed ``big-slow``, with a 0.05 m body and a motor limit of
    3 rad/s, saved as ``big-slow.toml``."""
    text = RobotProfile.builtin("e-puck").to_toml()
    for old, new in (
        ('name = "e-puck"', 'name = "big-slow"'),
        ("body_radius = 0.037", "body_radius = 0.05"),
        ("max_wheel_speed = 6.28", "max_wheel_speed = 3.0"),
    ):
        assert old in text
        text = text.replace(old, new)
    path = folder / "big-slow.toml"
    path.write_text(text)
    return path


def test_a_recorded_demo_replays_with_its_profile_file_after_the_file_is_gone(
    tmp_path: Path,
) -> None:
    path = _big_slow_epuck(tmp_path)
    run_file = tmp_path / "run.json"
    assert main(["demo", "--robot", str(path), "--seconds", "1", "--out", str(tmp_path / "demo"),
                 "--record", str(run_file)]) == 0  # fmt: skip
    values = json.loads(run_file.read_text())
    assert values["version"] == "1.3" and values["robot"] == "big-slow"
    path.unlink()
    run = load_run(run_file)
    assert run.robot_profile == RobotProfile.from_toml(values["robot_profile"])
    assert run.robot_profile.max_wheel_speed == 3.0 and run.robot_profile.body_radius == 0.05
    page = tmp_path / "replay.html"
    assert main(["replay", str(run_file), "-o", str(page)]) == 0
    assert page.exists()


def test_a_builtin_robot_s_run_stays_version_1_0_and_a_name_alone_must_be_builtin(
    tmp_path: Path,
) -> None:
    run_file = tmp_path / "run.json"
    assert main(["demo", "--seconds", "1", "--out", str(tmp_path / "demo"),
                 "--record", str(run_file)]) == 0  # fmt: skip
    values = json.loads(run_file.read_text())
    assert values["version"] == "1.0" and "robot_profile" not in values
    values["robot"] = "big-slow"
    run_file.write_text(json.dumps(values))
    with pytest.raises(RunFormatError, match="robot: expected one of"):
        load_run(run_file)


def test_every_robot_of_a_world_of_several_keeps_a_profile_file_s_profile(tmp_path: Path) -> None:
    path = _big_slow_epuck(tmp_path)
    world_file = tmp_path / "three.toml"
    world_file.write_text(THREE_ROBOTS)  # ann and bob take the simulator's profile, cy e-puck2
    simulator = Simulator(mazesim.load_world(str(world_file)), robot=str(path))
    profiles = [RobotProfile.load(path)] * 2 + [RobotProfile.builtin("e-puck2")]
    assert [simulator.robot_profile(i) for i in range(3)] == profiles
    recorder = FleetRecorder.of_simulator(simulator, "avoid-collision", 0)
    assert [robot for _, robot in recorder.robots] == profiles
    run_file = tmp_path / "three.json"
    assert main(["demo", "--world", str(world_file), "--robot", str(path), "--seconds", "1",
                 "--out", str(tmp_path / "demo"), "--record", str(run_file)]) == 0  # fmt: skip
    path.unlink()
    run = load_run(run_file)
    assert [robot.robot_profile for robot in run.robots] == profiles
    assert run.robots[1].robot_profile.body_radius == 0.05
    assert "profile_toml" not in json.loads(run_file.read_text())["robots"][2]


def test_a_gymnasium_env_simulates_and_draws_a_profile_file_s_robot(tmp_path: Path) -> None:
    path = _big_slow_epuck(tmp_path)
    frames = {}
    for robot in ("e-puck", str(path)):
        env = gymnasium.make("mazesim/EPuckMaze-v0", robot=robot, render_mode="rgb_array")
        env.reset(seed=0)
        assert env.unwrapped._simulator.robot == RobotProfile.load(robot)
        frames[robot] = env.render()
        env.close()
    # The wider body is drawn wider: more of the picture is the robot's.
    assert not np.array_equal(frames["e-puck"], frames[str(path)])


def test_a_vector_env_drives_a_profile_file_s_robot(tmp_path: Path) -> None:
    path = _big_slow_epuck(tmp_path)
    poses = {}
    for robot in ("e-puck", str(path)):
        env = gymnasium.make_vec(
            "mazesim/EPuckMaze-v0", num_envs=2, vectorization_mode="vector_entry_point", robot=robot
        )
        env.reset(seed=0)
        for _ in range(20):
            _, _, _, _, info = env.step(np.ones((2, 2), dtype=np.float32))
        poses[robot] = np.asarray(info["pose"])
        env.close()
    start = np.asarray(mazesim.load_world("seed-maze").start[:2])
    travelled = {robot: np.hypot(*(pose[0, :2] - start)) for robot, pose in poses.items()}
    assert travelled[str(path)] < 0.6 * travelled["e-puck"]  # 3 rad/s against 6.28


def test_an_evaluation_records_a_profile_file_s_robot(tmp_path: Path) -> None:
    path = _big_slow_epuck(tmp_path)
    run_file = tmp_path / "eval.json"
    assert main(["eval", "--robot", str(path), "--episodes", "1", "--events", "truth",
                 "--record", str(run_file)]) == 0  # fmt: skip
    path.unlink()
    assert load_run(run_file).robot_profile.max_wheel_speed == 3.0
