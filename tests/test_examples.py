"""Every file in examples/ runs, in its fast mode (MAZESIM_EXAMPLES_FAST=1), and does its job."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

import mazesim
from docs_blocks import run_command
from mazesim.distributed import parse_sweep_config, run_sequential
from mazesim.webots import import_wbt
from ros_support import needs_ros

REPO = Path(__file__).resolve().parent.parent
EXAMPLES = REPO / "examples"
#: A guard against a script that hangs, not a speed requirement.
TIMEOUT_S = 300

#: Every file of examples/, each checked by the test named beside it.
COVERED = {
    "quickstart.py": "test_quickstart_drives_and_prints_pose_collisions_and_readings",
    "batch_loop.py": "test_batch_loop_steps_many_robots_and_restarts_them",
    "world_authoring.py": "test_world_authoring_saves_loads_drives_and_draws",
    "webots/avoid_collision.py": "test_webots_controller_runs_through_mazesim_webots_run",
    "ros_launch.py": "test_ros_launch_reaches_the_goal",
    "sweep.toml": "test_sweep_example_runs_in_a_fast_variant",
    "worlds/two-rooms.toml": "test_two_rooms_world_loads_with_its_goal_and_checkpoint",
    "worlds/boxes.wbt": "test_boxes_wbt_imports_without_warnings",
    "ppo_sb3.py": "test_ppo_sb3_trains_and_evaluates_on_held_out_mazes",
    "marl_ppo.py": "test_marl_ppo_trains_and_compares_with_random_and_hand_rule",
    "her_sb3.py": "test_her_sb3_trains_and_writes_its_held_out_results",
    "learning_tier.py": "test_learning_tier_trains_each_agent_and_tables_them_with_the_baselines",
}


def run_example(argv: list[str], cwd: Path) -> subprocess.CompletedProcess[str]:
    """Runs a command in ``cwd`` with the examples' fast mode on; fails the test on an error."""
    finished = run_command(argv, cwd, TIMEOUT_S)
    assert finished.returncode == 0, f"{argv}:\n{finished.stdout}\n{finished.stderr}"
    return finished


def test_every_example_file_is_covered() -> None:
    files = {
        path.relative_to(EXAMPLES).as_posix()
        for path in EXAMPLES.rglob("*")
        if path.is_file() and "__pycache__" not in path.parts
    }
    assert files == set(COVERED)
    assert all(name in globals() for name in COVERED.values())


def test_quickstart_drives_and_prints_pose_collisions_and_readings(tmp_path: Path) -> None:
    out = run_example([sys.executable, str(EXAMPLES / "quickstart.py")], tmp_path).stdout
    pose = r"after 32\.00 s \(1000 steps\): x [\d.-]+ m, y [\d.-]+ m, yaw [\d.-]+ rad"
    assert re.search(pose, out), out
    travelled = re.search(r"collisions: \d+, distance travelled: ([\d.]+) m", out)
    assert travelled and float(travelled[1]) > 1.0, out  # it drove, and turned at the wall
    assert re.search(r"ps0\.\.ps7 \(raw\):( [\d.]+){8}$", out, flags=re.MULTILINE), out
    assert re.search(r"gs0\.\.gs2 \(raw\):( [\d.]+){3}$", out, flags=re.MULTILINE), out


def test_batch_loop_steps_many_robots_and_restarts_them(tmp_path: Path) -> None:
    out = run_example([sys.executable, str(EXAMPLES / "batch_loop.py")], tmp_path).stdout
    assert re.search(r"^256 robots x 1000 steps", out, flags=re.MULTILINE), out
    travelled = re.search(r"distance travelled per robot: ([\d.]+) m", out)
    assert travelled and float(travelled[1]) > 0.5, out
    counts = re.search(r"restarts after a wall contact: (\d+), barcode crossings: (\d+)", out)
    assert counts and int(counts[1]) > 0 and int(counts[2]) > 0, out  # masked resets happened


def test_world_authoring_saves_loads_drives_and_draws(tmp_path: Path) -> None:
    run_example([sys.executable, str(EXAMPLES / "world_authoring.py"), "made"], tmp_path)
    world = mazesim.load_world(tmp_path / "made" / "my-maze.toml")
    assert world.name == "my-maze"
    assert world.goal is not None and len(world.checkpoints()) == 1
    picture = (tmp_path / "made" / "my-maze.png").read_bytes()
    assert picture.startswith(b"\x89PNG") and len(picture) > 10_000


def test_webots_controller_runs_through_mazesim_webots_run(tmp_path: Path) -> None:
    controller = EXAMPLES / "webots" / "avoid_collision.py"
    world = EXAMPLES / "worlds" / "boxes.wbt"
    argv = ["mazesim", "webots", "run", str(controller), "--world", str(world), "--seconds", "5"]
    run_example([*argv, "--out", "run"], tmp_path)
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["distance_m"] > 0.1, summary


@needs_ros
def test_ros_launch_reaches_the_goal(tmp_path: Path) -> None:
    out = run_example([sys.executable, str(EXAMPLES / "ros_launch.py"), "2"], tmp_path).stdout
    assert re.search(r"learning\.launch seed:=2: goal reached at step \d+", out), out


def test_sweep_example_runs_in_a_fast_variant(tmp_path: Path) -> None:
    text = (EXAMPLES / "sweep.toml").read_text()
    sweep = parse_sweep_config(text, source="sweep.toml", base_dir=EXAMPLES)
    assert len(sweep.settings) >= 4
    assert {setting.params["trainer"] for setting in sweep.settings} == {"hrl"}
    # The same grid with tiny budgets: every setting trains, evaluates and is written out.
    budgets = {"steps": 20, "envs": 8, "higher_episodes": 2, "episode_steps": 50}
    budgets["eval_episodes"] = 2
    for key, value in budgets.items():
        text, count = re.subn(rf"^{key} = .*$", f"{key} = {value}", text, flags=re.MULTILINE)
        assert count == 1, key
    fast = parse_sweep_config(text, source="sweep.toml", base_dir=EXAMPLES)
    summary = run_sequential(fast, tmp_path / "sweep", threads=1)
    assert [run["status"] for run in summary.runs] == ["ok"] * len(fast.settings)
    assert (tmp_path / "sweep" / "sweep.png").stat().st_size > 10_000


def test_two_rooms_world_loads_with_its_goal_and_checkpoint() -> None:
    world = mazesim.load_world(EXAMPLES / "worlds" / "two-rooms.toml")
    assert world.name == "two-rooms"
    assert world.goal is not None
    (checkpoint,) = world.checkpoints()
    assert checkpoint["code"] == "10110"
    sim = mazesim.Simulator(world, robot="e-puck", seed=0)
    for _ in range(50):
        sim.step(3.0, 3.0)
    assert sim.pose[0] > world.start[0] + 0.05


def test_boxes_wbt_imports_without_warnings() -> None:
    world, report = import_wbt(EXAMPLES / "worlds" / "boxes.wbt")
    assert report["warnings"] == []
    assert report["robot"] is not None
    assert len(report["obstacles"]) == 8  # the arena's four walls, three boxes and a wall
    assert report["basic_time_step_ms"] == 16
    assert world.basic_time_step_ms == 16


def test_ppo_sb3_trains_and_evaluates_on_held_out_mazes(tmp_path: Path) -> None:
    pytest.importorskip("stable_baselines3", reason="needs mazesim[sb3] (make sb3-deps)")
    for task in ("mazesim/MazeFixed-v1", "mazesim/UnseenMaze-v2", "mazesim/UnseenMazeGuided-v0"):
        argv = [sys.executable, str(EXAMPLES / "ppo_sb3.py"), "--task", task, "--out", "run"]
        out = run_example(argv, tmp_path).stdout
        pattern = rf"{task} seed 0: \d+ env-steps in \d+ s .*success on 4 held-out episodes: \d+ %"
        assert re.search(pattern, out), out
        assert (tmp_path / "run" / "progress.csv").read_text().count("\n") >= 2
        assert (tmp_path / "run" / "model.zip").stat().st_size > 1000
        assert (tmp_path / "run" / "curve.png").read_bytes()[:4] == b"\x89PNG"
    argv = [sys.executable, str(EXAMPLES / "ppo_sb3.py"), "--plot", "run", "run"]
    run_example([*argv, "--picture", "both.png"], tmp_path)
    assert (tmp_path / "both.png").read_bytes()[:4] == b"\x89PNG"


def test_ppo_sb3_takes_task_options_and_records_a_video_of_a_held_out_episode(
    tmp_path: Path,
) -> None:
    pytest.importorskip("stable_baselines3", reason="needs mazesim[sb3] (make sb3-deps)")
    pytest.importorskip("imageio", reason="needs mazesim[video]")
    script = [sys.executable, str(EXAMPLES / "ppo_sb3.py"), "--task", "mazesim/MazeFixed-v1"]
    argv = [*script, "--option", "goal_reward=20", "--out", "run", "--video", "run.gif"]
    out = run_example(argv, tmp_path).stdout
    frames = re.search(r"video of the first held-out episode \((\d+) frames\): run.gif", out)
    assert frames is not None and int(frames.group(1)) >= 2, out
    assert (tmp_path / "run.gif").read_bytes()[:6] == b"GIF89a"
    # The option reaches the task: a typo of one is refused by the env, naming the one meant.
    typo = run_command([*script, "--option", "goal_rewrd=20", "--out", "typo"], tmp_path, TIMEOUT_S)
    assert typo.returncode != 0
    assert "did you mean 'goal_reward' for 'goal_rewrd'" in typo.stderr


def test_her_sb3_trains_and_writes_its_held_out_results(tmp_path: Path) -> None:
    pytest.importorskip("stable_baselines3", reason="needs mazesim[sb3] (make sb3-deps)")
    task = "mazesim/UnseenMazeGoal-v0"
    argv = [sys.executable, str(EXAMPLES / "her_sb3.py"), "--task", task, "--out", "run"]
    out = run_example(argv, tmp_path).stdout  # fast mode: 300 env-steps, 2 held-out episodes
    pattern = rf"{task} seed 0: 300 env-steps in \d+ s; success on 2 held-out episodes: \d+ %"
    assert re.search(pattern, out), out
    results = json.loads((tmp_path / "run" / "results.json").read_text())
    assert results["task"] == task and results["steps"] == 300
    assert [step for step, _ in results["curve"]] == [150, 300]  # held out every 150 steps
    assert all(0.0 <= rate <= 1.0 for _, rate in results["curve"])
    assert results["success"] == results["curve"][-1][1]
    assert results["wall_seconds"] > 0 and len(results["load_average"]) == 3
    assert (tmp_path / "run" / "curve.png").read_bytes()[:4] == b"\x89PNG"


def test_learning_tier_trains_each_agent_and_tables_them_with_the_baselines(
    tmp_path: Path,
) -> None:
    pytest.importorskip("sb3_contrib", reason="needs mazesim[sb3] (make sb3-deps)")
    script = [sys.executable, str(EXAMPLES / "learning_tier.py")]
    for agent in ("ppo", "recurrent", "curriculum"):
        argv = [*script, "train", "--agent", agent, "--maze-size", "4", "--out", f"runs/{agent}"]
        out = run_example(argv, tmp_path).stdout  # fast mode: 512 env-steps, 4 held-out mazes
        pattern = rf"{agent} seed 0: 512 env-steps in \d+ s; success on 4 held-out mazes: "
        assert re.search(pattern + r"4x4 \d+ %, 5x5 \d+ %", out), out
        results = json.loads((tmp_path / "runs" / agent / "results.json").read_text())
        assert results["env_steps"] == 512 and results["maze_size"] == [4, 4]
        assert [step for step, _ in results["curve"]] == [256, 512]
        assert set(results["held_out"]) == {"4x4", "5x5"}
        assert results["wall_seconds"] > 0 and len(results["load_average"]) == 3
        if agent == "curriculum":  # it starts on 3 x 3 mazes
            assert results["stages"][0] == [0, [3, 3]]
    argv = [*script, "baselines", "--maze-size", "4", "--out", "runs/baselines"]
    out = run_example(argv, tmp_path).stdout
    assert re.search(
        r"^frontier explorer seed 2: success on 4 held-out mazes: 4x4 \d+ %", out, re.M
    )
    out = run_example([*script, "table", "runs", "--picture", "curves.png"], tmp_path).stdout
    rows = [line for line in out.splitlines() if line.startswith("| ")]
    assert rows[0].startswith("| agent | seeds | success 4x4")
    agents = {row.split(" | ")[0][2:] for row in rows[1:]}
    assert agents == {
        "ppo",
        "recurrent",
        "curriculum",
        "wall follower",
        "frontier explorer",
        "random",
    }
    assert (tmp_path / "curves.png").read_bytes()[:4] == b"\x89PNG"


def test_bench_sb3_prints_both_training_rates_and_their_ratio(tmp_path: Path) -> None:
    pytest.importorskip("stable_baselines3", reason="needs mazesim[sb3] (make sb3-deps)")
    argv = [sys.executable, str(REPO / "benches" / "bench_sb3.py"), "--task"]
    argv += ["mazesim/MazeFixed-v1", "--envs", "16", "--n-steps", "16", "--batch", "128"]
    argv += ["--dummy-steps", "256", "--fast-steps", "512", "--rounds", "1"]
    out = run_example(argv, tmp_path).stdout
    assert re.search(r"DummyVecEnv x 8 single envs +[\d,]+ env-steps/s", out), out
    assert re.search(r"make_vec_env, 16 envs \(batch\) +[\d,]+ env-steps/s", out), out
    assert re.search(r"ratio +\d+\.\d x", out), out


def test_marl_ppo_trains_and_compares_with_random_and_hand_rule(tmp_path: Path) -> None:
    pytest.importorskip("torch", reason="needs mazesim[sb3] (make sb3-deps)")
    pytest.importorskip("pettingzoo", reason="needs mazesim[marl] (make marl-deps)")
    argv = [sys.executable, str(EXAMPLES / "marl_ppo.py"), "--task", "maze_goals_v0"]
    argv += ["--steps", "600", "--envs", "4", "--rollout", "50", "--eval-envs", "4"]
    out = run_example([*argv, "--out", "run"], tmp_path).stdout
    assert re.search(r"^maze_goals_v0 seed 0: 600 robot-steps in \d+ s", out, re.MULTILINE), out
    for name in ("ppo", "random", "hand rule"):
        assert re.search(rf"^  {name}: mean return -?[\d.]+, at goal [\d.]+", out, re.MULTILINE)
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["robot_steps"] == 600 and set(summary["evaluation"]) == {
        "ppo",
        "random",
        "hand rule",
    }
    assert all(found["episodes"] == 4 for found in summary["evaluation"].values())
    assert (tmp_path / "run" / "curve.png").read_bytes().startswith(b"\x89PNG")
    assert (tmp_path / "run" / "progress.csv").read_text().startswith("robot_steps,return,measure")


@pytest.mark.parametrize("name", ["ppo_sb3.py", "her_sb3.py", "learning_tier.py"])
@pytest.mark.parametrize("missing", ["torch", "stable_baselines3"])
def test_an_sb3_example_without_its_extra_says_what_to_install(name: str, missing: str) -> None:
    # A newcomer running the README's PPO example before `make sb3-deps` got Python's bare
    # "No module named 'torch'": the example now imports mazesim's SB3 adapter first, whose
    # refusal names the extra, for pip and for a checkout.
    hide = f"import sys, runpy; sys.modules[{missing!r}] = None; "
    run = f"runpy.run_path({str(EXAMPLES / name)!r}, run_name='__main__')"
    done = subprocess.run(
        [sys.executable, "-c", hide + run], capture_output=True, text=True, timeout=TIMEOUT_S
    )
    assert done.returncode != 0
    last = done.stderr.strip().splitlines()[-1]
    assert last.startswith("mazesim.errors.MissingDependencyError:"), done.stderr[-2000:]
    assert missing in last and 'pip install "mazesim[sb3]"' in last and "make sb3-deps" in last
