"""Sweeps and evaluations on Ray: config errors, Ray equals one by one, no loss on a dead worker."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import mazesim
from mazesim.cli import main
from mazesim.distributed import (
    Setting,
    SweepConfig,
    TaskOutput,
    evaluate_episodes,
    load_sweep_config,
    parse_sweep_config,
    run_sequential,
    run_sweep,
    train_and_evaluate,
)
from mazesim.distributed.episodes import split_episodes
from mazesim.distributed.output import RUNS_DIR, remove_leftovers, write_run_folder
from mazesim.errors import (
    InvalidArgumentError,
    MazesimIOError,
    UnknownNameError,
    WorldFormatError,
)
from mazesim.learn.learning_curve import CURVE_VALUES

REPO = Path(__file__).resolve().parents[2]
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"

#: The grid of both test sweeps: 4 settings x 2 seeds.
GRID = """seed = [0, 1]
learning_rate = [0.1, 0.3]
epsilon = [0.05, 0.3]
maze_size = 3"""

#: The grid for flat Q-learning, each setting small enough to train in a fraction of a second.
SMALL_SWEEP = f"""
[sweep]
name = "small"
max_retries = 1

[grid]
trainer = "flat-q"
{GRID}
envs = 8
steps = 150
episode_steps = 120
eval_episodes = 6
"""

#: The same grid for mazesim's hierarchical navigator, with budgets that only a test would use.
HRL_SWEEP = f"""
[sweep]
name = "hrl-small"

[grid]
trainer = "hrl"
{GRID}
envs = 4
steps = 40
higher_episodes = 4
episode_steps = 60
eval_episodes = 3
"""


def arrays_of(run_folder: Path) -> dict[str, bytes]:
    with np.load(run_folder / "tables.npz", allow_pickle=False) as archive:
        return {name: archive[name].tobytes() for name in archive.files}


# --- configuration -------------------------------------------------------------------------


def test_example_sweep_expands_to_2_budgets_x_2_seeds() -> None:
    sweep = load_sweep_config(REPO / "examples" / "sweep.toml")
    assert len(sweep.settings) == 4
    assert len({setting.group for setting in sweep.settings}) == 2
    assert list(sweep.axes) == ["steps", "seed"]
    assert [setting.seed for setting in sweep.settings[:2]] == [0, 1]
    assert sweep.settings[0].label == "steps=4000"


def test_ids_are_stable_whatever_the_order_of_keys_and_values() -> None:
    one = parse_sweep_config("[grid]\nseed = [0, 1]\nepsilon = [0.1, 0.2]\n")
    other = parse_sweep_config("[grid]\nepsilon = [0.2, 0.1]\nseed = [1, 0]\n")
    assert sorted(s.id for s in one.settings) == sorted(s.id for s in other.settings)
    assert len({s.id for s in one.settings}) == 4
    assert one.settings[0].id.endswith("-s0") and one.settings[1].id.endswith("-s1")
    assert one.settings[0].group == one.settings[1].group


@pytest.mark.parametrize(
    ("text", "error", "match"),
    [
        ("[grid]\nlearning_rate = 0.7\n", InvalidArgumentError, r"grid.learning_rate.*\(0, 0.5\]"),
        ("[grid]\nenvs = [8, 'many']\n", InvalidArgumentError, r"grid.envs\[1\].*'many'"),
        ("[grid]\nseed = []\n", InvalidArgumentError, "at least one value"),
        ("[grid]\nseed = [1, 1]\n", InvalidArgumentError, "distinct"),
        ("[grid]\nnoise = 1\n", InvalidArgumentError, "true or false"),
        ("[grid]\nlerning_rate = 0.1\n", UnknownNameError, "lerning_rate.*learning_rate"),
        ("[sweeps]\nname = 'x'\n", UnknownNameError, "'sweeps'"),
        ("[sweep]\nmax_retries = -1\n", InvalidArgumentError, "sweep.max_retries"),
        ("[grid\nseed = 1\n", InvalidArgumentError, "not a valid TOML file.*line 1"),
        ("[grid]\nworld = 'no-such-world'\n", UnknownNameError, "no-such-world.*seed-maze"),
        ("[grid]\nworld = 'arena'\n", InvalidArgumentError, "with a goal"),
        ("[grid]\nworld = 'seed-maze'\nmaze_size = 4\n", InvalidArgumentError, "one"),
        ("[grid]\ntrainer = 'deep-q'\n", UnknownNameError, "trainer.*hrl, baseline, flat-q"),
        (
            "[grid]\ntrainer = 'hrl'\ncollision_penalty = 1.0\n",
            InvalidArgumentError,
            r"grid.collision_penalty: trainer 'hrl' does not use it",
        ),
        (
            "[grid]\ntrainer = ['flat-q', 'baseline']\nhigher_episodes = 20\n",
            InvalidArgumentError,
            r"grid.higher_episodes: trainer 'flat-q' does not use it",
        ),
        ("[grid]\ntrainer = 'hrl'\nnoise = false\n", InvalidArgumentError, "noise = true only"),
        ("[grid]\nlearning_rate = 1" + "0" * 400 + "\n", InvalidArgumentError, "learning_rate"),
        (
            "[grid]\ntrainer = 'flat-q'\n"
            + "".join(f"{key} = {list(range(1, 2001))}\n" for key in ("seed", "maze_seed", "envs")),
            InvalidArgumentError,
            r"grid: expected at most 100000 settings, found 8000000000 \(2000 maze_seed x 2000",
        ),
    ],
)
def test_config_errors_are_the_packages_own(text: str, error: type, match: str) -> None:
    with pytest.raises(error, match=match):
        parse_sweep_config(text, source="bad.toml")


def test_missing_sweep_file_and_its_cli_error(tmp_path: Path, capsys: Any) -> None:
    with pytest.raises(MazesimIOError, match="nope.toml"):
        load_sweep_config(tmp_path / "nope.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("[grid]\nepsilon = 2\n")
    assert main(["sweep", str(bad), "--out", str(tmp_path / "out")]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("mazesim: error: ")
    assert "grid.epsilon" in lines[0]
    assert not (tmp_path / "out").exists()


def test_a_world_file_that_is_not_text_is_a_world_format_error(tmp_path: Path) -> None:
    picture = tmp_path / "maze.png"
    picture.write_bytes(b"\x89PNG\r\n\x1a\n\x00\x00")
    with pytest.raises(WorldFormatError, match=r"expected the world of .*grid.world in UTF-8 text"):
        parse_sweep_config(f"[grid]\nworld = '{picture}'\n", source="bad.toml")


@pytest.mark.parametrize("command", ["sweep", "eval"])
def test_help_does_not_import_ray(command: str) -> None:
    code = (
        f"import sys\nfrom mazesim.cli import main\nassert main(['{command}', '--help']) == 0\n"
        "assert 'ray' not in sys.modules, 'ray imported'\n"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert "--address ADDR" in result.stdout and "local" in result.stdout
    if command == "sweep":
        assert "learning_rate" in result.stdout


def test_auto_trains_the_hierarchical_navigator_with_its_own_defaults() -> None:
    setting = parse_sweep_config("[grid]\nseed = 3\n").settings[0]
    assert setting.params["trainer"] == "hrl"
    assert setting.params["learning_rate"] is None and setting.params["epsilon"] is None


# --- tasks and the output folder, without Ray ----------------------------------------------


def test_a_task_is_the_same_with_1_or_2_threads() -> None:
    setting = parse_sweep_config(SMALL_SWEEP).settings[0]
    one, two = train_and_evaluate(setting, 1), train_and_evaluate(setting, 2)
    assert one.files["tables.npz"] == two.files["tables.npz"]
    assert one.files["curves.csv"] == two.files["curves.csv"]
    assert one.result["env_steps"] == 8 * 150
    metadata = json.loads(one.files["run.json"])
    assert metadata["setting"]["id"] == setting.id
    # "flat-q" is the one flat learner under its former name: a table per checkpoint context.
    checkpoints = metadata["tables"]["checkpoint_ids"][0]
    assert metadata["tables"]["flat_q"] == [(1 + 2 * checkpoints) * 4096, 12]


@pytest.mark.parametrize("trainer", ["hrl", "baseline"])
def test_navigator_trainers_are_the_same_with_1_or_2_threads(trainer: str) -> None:
    text = HRL_SWEEP.replace('trainer = "hrl"', f'trainer = "{trainer}"')
    if trainer == "baseline":
        unused = ("higher_episodes",)  # the flat learner has no higher level
        text = "\n".join(line for line in text.splitlines() if not line.startswith(unused))
    setting = parse_sweep_config(text).settings[0]
    one, two = train_and_evaluate(setting, 1), train_and_evaluate(setting, 2)
    assert one.files["tables.npz"] == two.files["tables.npz"]
    assert one.files["curves.csv"] == two.files["curves.csv"]
    assert one.result["eval_env_steps"] == 3 * 60  # no 3 x 3 maze is solved by so little training
    assert one.result["mean_steps"] == 60.0  # the failed episodes at their limit
    tables = json.loads(one.files["run.json"])["tables"]
    if trainer == "hrl":
        assert tables["lower_q"] == [4, 12288, 12] and tables["higher_q"][1] == 4
        # the lower level's 4 x 40 env-steps, then 4 higher-level episodes of at most 60 steps
        assert 4 * 40 + 4 <= one.result["env_steps"] <= 4 * 40 + 4 * 60
        # The learning curve of ``mazesim train``: one lower-level round, then the higher level
        # each time episodes end, up to its 4 episodes.
        curves = [row.split(",") for row in one.files["curves.csv"].decode().splitlines()]
        assert tuple(curves[0]) == ("stage", *CURVE_VALUES)
        assert [row[:3] for row in curves[1:2]] == [["lower", "1", "160.0"]]
        assert {row[0] for row in curves[2:]} == {"higher"} and curves[-1][1] == "4"
    else:
        assert set(tables) == {"flat_q", "checkpoint_ids"} and one.result["env_steps"] == 4 * 40


def test_run_folders_appear_whole_and_replace_older_ones(tmp_path: Path) -> None:
    write_run_folder(str(tmp_path), "abc-s0", {"a.txt": b"old", "b.txt": b"old"})
    write_run_folder(str(tmp_path), "abc-s0", {"a.txt": b"new"})
    folder = tmp_path / RUNS_DIR / "abc-s0"
    assert sorted(os.listdir(folder)) == ["a.txt"] and (folder / "a.txt").read_bytes() == b"new"
    assert os.listdir(tmp_path / RUNS_DIR) == ["abc-s0"]
    with pytest.raises(InvalidArgumentError, match="plain file name"):
        write_run_folder(str(tmp_path), "abc-s1", {"../escape": b""})
    (tmp_path / RUNS_DIR / ".abc-s2.x.partial").mkdir()
    remove_leftovers(str(tmp_path))
    assert os.listdir(tmp_path / RUNS_DIR) == ["abc-s0"]


def test_episode_split_covers_every_episode_once() -> None:
    plan = split_episodes(10, 3)
    assert plan == [(0, 3), (3, 3), (6, 4)]
    assert split_episodes(2, 8) == [(0, 1), (1, 1)]


# --- on a local Ray instance ----------------------------------------------------------------


@pytest.fixture(scope="module")
def local_ray() -> Any:
    pytest.importorskip("ray")
    from mazesim.distributed.cluster import ray_session

    with ray_session(cpus=2) as ray:
        yield ray


def same_runs_on_ray_and_alone(sweep: SweepConfig, folder: Path) -> list[Path]:
    """Runs ``sweep`` on Ray into ``folder/ray`` and one by one into ``folder/alone``, checks
    that every run is ok and wrote the same tables and curves both ways, and returns the folders
    of the Ray runs."""
    on_ray = run_sweep(sweep, folder / "ray")
    alone = run_sequential(sweep, folder / "alone")
    assert [run["status"] for run in on_ray.runs] == ["ok"] * 8
    assert [run["status"] for run in alone.runs] == ["ok"] * 8
    for setting in sweep.settings:
        ray_folder = folder / "ray" / RUNS_DIR / setting.id
        alone_folder = folder / "alone" / RUNS_DIR / setting.id
        assert arrays_of(ray_folder) == arrays_of(alone_folder)
        for name in ("tables.npz", "curves.csv"):
            assert (ray_folder / name).read_bytes() == (alone_folder / name).read_bytes()
    return [folder / "ray" / RUNS_DIR / setting.id for setting in sweep.settings]


def test_sweep_on_ray_gives_the_same_tables_as_one_by_one(local_ray: Any, tmp_path: Path) -> None:
    sweep = parse_sweep_config(SMALL_SWEEP)
    same_runs_on_ray_and_alone(sweep, tmp_path)
    results = json.loads((tmp_path / "ray" / "results.json").read_text())
    assert results["counts"] == {"ok": 8, "failed": 0, "pending": 0}
    assert results["ray"]["cluster_cpus"] == 2.0
    assert len((tmp_path / "ray" / "results.csv").read_text().splitlines()) == 9
    assert (tmp_path / "ray" / "sweep.png").read_bytes().startswith(PNG_MAGIC)
    # Run again into the same folder: every finished run is kept, none is trained again.
    again = run_sweep(sweep, tmp_path / "ray")
    assert all(run["reused"] for run in again.runs) and again.env_steps == 0


def test_hrl_sweep_on_ray_gives_the_same_tables_as_one_by_one(
    local_ray: Any, tmp_path: Path
) -> None:
    sweep = parse_sweep_config(HRL_SWEEP)
    for ray_folder in same_runs_on_ray_and_alone(sweep, tmp_path):
        assert sorted(arrays_of(ray_folder)) == [
            "checkpoint_ids",
            "higher_q",
            "higher_visits",
            "lower_q",
            "lower_visits",
        ]
    # The hyperparameters reach the learner: other rates and seeds, other tables.
    first, other_seed, other_rate = (
        arrays_of(tmp_path / "alone" / RUNS_DIR / sweep.settings[i].id)["lower_q"]
        for i in (0, 1, 4)
    )
    assert first != other_seed and first != other_rate


class FaultyTask:
    """Kills its worker on the first attempt of one setting, on every attempt of another, and
    raises in a third; runs the real task otherwise."""

    def __init__(self, markers: Path, crash_once: str, crash_always: str, raises: str) -> None:
        self.markers, self.crash_once = markers, crash_once
        self.crash_always, self.raises = crash_always, raises

    def __call__(self, setting: Setting, threads: int) -> TaskOutput:
        marker = self.markers / f"{setting.id}.attempt"
        attempts = int(marker.read_text()) + 1 if marker.exists() else 1
        marker.write_text(str(attempts))
        if setting.id == self.crash_always or (setting.id == self.crash_once and attempts == 1):
            os._exit(1)  # the worker process dies mid-task, as if killed
        if setting.id == self.raises:
            raise RuntimeError("the trainer gave up")
        return train_and_evaluate(setting, threads)


def test_a_worker_killed_mid_task_loses_nothing(local_ray: Any, tmp_path: Path) -> None:
    local_ray.cloudpickle.register_pickle_by_value(sys.modules[__name__])
    sweep = parse_sweep_config(SMALL_SWEEP)
    ids = [setting.id for setting in sweep.settings]
    markers = tmp_path / "markers"
    markers.mkdir()
    task = FaultyTask(markers, crash_once=ids[1], crash_always=ids[2], raises=ids[3])
    summary = run_sweep(sweep, tmp_path / "out", task=task)
    status = {run["id"]: run["status"] for run in summary.runs}
    assert status == {i: "failed" if i in (ids[2], ids[3]) else "ok" for i in ids}
    assert (markers / f"{ids[1]}.attempt").read_text() == "2"  # died once, retried once
    assert (markers / f"{ids[2]}.attempt").read_text() == "2"  # max_retries = 1
    assert (markers / f"{ids[3]}.attempt").read_text() == "1"  # an exception is not retried
    errors = {run["id"]: run["error"] for run in summary.runs}
    assert "died" in errors[ids[2]].lower() or "crash" in errors[ids[2]].lower()
    assert errors[ids[3]] == "RuntimeError: the trainer gave up"
    runs = sorted(os.listdir(tmp_path / "out" / RUNS_DIR))
    assert runs == sorted(i for i in ids if status[i] == "ok")
    results = json.loads((tmp_path / "out" / "results.json").read_text())
    assert results["counts"] == {"ok": 6, "failed": 2, "pending": 0}


def test_evaluation_spread_over_ray_equals_one_batch(local_ray: Any) -> None:
    from mazesim.learn.episode_ranges import NavigatorEpisodes
    from mazesim.learn.tables import load_policy

    policy = load_policy(None)
    world = mazesim.load_world("seed-maze")
    evaluate = NavigatorEpisodes(
        kind="hierarchical",
        world_tomls=(world.to_toml(),),
        episodes_per_world=5,
        seed=3,
        events="truth",
        max_steps=300,
        checkpoint_ids=(tuple(policy.checkpoint_ids),),
        lower_q=policy.lower_q,
        higher_q=None if policy.higher_q is None else policy.higher_q[None],
    )
    whole = evaluate(0, 5)
    spread = evaluate_episodes(evaluate, 5, chunks=3)
    assert [r.episode for r in whole] == list(range(5))
    assert spread == whole


def test_sweep_command_on_ray_and_without(local_ray: Any, tmp_path: Path, capsys: Any) -> None:
    config = tmp_path / "small.toml"
    config.write_text(SMALL_SWEEP.replace("seed = [0, 1]", "seed = 0"))
    assert main(["sweep", str(config), "--out", str(tmp_path / "ray"), "--quiet"]) == 0
    printed = capsys.readouterr().out
    assert "learning_rate=0.3, epsilon=0.05" in printed and "env-steps" in printed
    assert main(["sweep", str(config), "--out", str(tmp_path / "seq"), "--sequential"]) == 0
    assert "[4/4] ok" in capsys.readouterr().out
    for folder in ("ray", "seq"):
        results = json.loads((tmp_path / folder / "results.json").read_text())
        assert results["counts"]["ok"] == 4


def test_eval_spread_over_ray_equals_eval_without(
    local_ray: Any, capsys: Any, tmp_path: Path
) -> None:
    arguments = ["eval", "--episodes", "3", "--events", "both", "--json", "--seed", "4"]
    outputs = []
    for run, address in (("alone", []), ("ray", ["--address", "local"])):
        files = ["--trace", str(tmp_path / f"{run}.txt"), "--plot", str(tmp_path / f"{run}.png")]
        assert main([*arguments, *files, *address]) == 0
        outputs.append(json.loads(capsys.readouterr().out))
    alone, on_ray = outputs
    assert on_ray == alone
    assert alone["episodes"] == 3 and alone["robust_decoder"]["episodes"] == 3
    for suffix in ("txt", "png"):
        assert (tmp_path / f"ray.{suffix}").read_bytes() == (
            tmp_path / f"alone.{suffix}"
        ).read_bytes()


def test_eval_in_unseen_mazes_adapts_once_and_ships_the_tables(
    local_ray: Any, monkeypatch: Any
) -> None:
    from mazesim.distributed.episodes import ray_spreader
    from mazesim.learn import evaluate as hrl_evaluate
    from mazesim.learn.tables import load_policy

    monkeypatch.setattr(hrl_evaluate, "ADAPT_EPISODES", 6)
    trained: list[int] = []
    train_higher = hrl_evaluate.train_higher

    def counted(*args: Any, **kwargs: Any) -> Any:
        trained.append(1)
        return train_higher(*args, **kwargs)

    monkeypatch.setattr(hrl_evaluate, "train_higher", counted)
    policy = load_policy(None)
    worlds = hrl_evaluate.unseen_mazes(3, seed=2)
    options: dict[str, Any] = {"seed": 2, "sources": ("truth",), "max_steps": 800}
    alone = hrl_evaluate.evaluate_navigator(policy, worlds, 2, **options)
    spread = ray_spreader("local")
    on_ray = hrl_evaluate.evaluate_navigator(policy, worlds, 2, spread=spread, **options)
    assert trained == [1, 1] and alone["truth"].adapted and on_ray["truth"].adapted
    assert on_ray == alone
    assert on_ray["truth"].decisions  # the higher level chose sub-tasks on the way
    assert len(on_ray["truth"].world_success) == 3 and on_ray["truth"].env_steps > 0
