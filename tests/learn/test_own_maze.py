"""Issue 37: one's own maze, end to end. A world the navigator cannot learn is refused before
training with what to change; a trained navigator keeps the world file it learned, so the
command ``mazesim train`` prints works as printed; long comparisons show where they differ."""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

import pytest

import mazesim
from mazesim.cli import main
from mazesim.episodes import learning_problems
from mazesim.errors import PolicyFormatError, UnknownNameError
from mazesim.learn.schema import differing
from mazesim.learn.tables import load_policy
from mazesim.maze import CellMaze, navigator_problems

#: A small, quick training: 32 robots, 16,000 env-steps of the lower level.
QUICK = ["--envs", "32", "--steps", "16000", "--no-progress"]
#: A quicker one: the flat baseline, 4 robots for 10,000 steps each.
FLAT = ["--flat", "--envs", "4", "--steps", "40k", "--no-progress"]

WALLED = '''format = "mazesim-world"
version = 1
name = "walled"

[grid]
cell_size = 0.25
wall_thickness = 0.01
map = """
+--+--+--+
|S    |G |
+  +--+  +
|     |  |
+--+--+--+
"""
'''


def _corridor() -> mazesim.World:
    """4 x 4, seed 3, first draw: one corridor from the start to the goal, no junction."""
    return mazesim.generate_maze(4, 4, seed=3, junction=False)


def test_the_generated_4_by_4_maze_of_seed_3_now_has_checkpoints() -> None:
    assert _corridor().checkpoints() == []
    maze = mazesim.generate_maze(4, 4, seed=3)
    assert len(maze.checkpoints()) > 0
    assert navigator_problems(maze) == []


def test_the_problems_of_a_world_say_what_to_change() -> None:
    (corridor,) = navigator_problems(_corridor())
    assert "no barcode checkpoints" in corridor and "mazesim.generate_maze" in corridor
    walled = navigator_problems(mazesim.World.from_toml(WALLED, source="walled.toml"))
    assert any("cannot be reached from the start" in p and "open a way" in p for p in walled)
    assert any("no barcode checkpoints" in p for p in walled)
    no_goal = WALLED.replace("|S    |G |", "|S    |  |")
    assert any(
        "no goal" in p for p in navigator_problems(mazesim.World.from_toml(no_goal, source="x"))
    )
    assert "no [grid] cell maze" in navigator_problems(mazesim.load_world("arena"))[0]
    assert navigator_problems(mazesim.load_world("seed-maze")) == []


#: A maze drawn by hand with two junctions and no checkpoints, away from the origin.
DRAWN = '''format = "mazesim-world"
version = 1

[grid]
origin = [1.0, 2.0]
map = """
+--+--+--+
|S       |
+  +  +--+
|  |    G|
+  +--+  +
|        |
+--+--+--+
"""
'''


def test_a_maze_drawn_by_hand_is_told_the_checkpoints_to_paste(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    drawn = tmp_path / "drawn.toml"
    drawn.write_text(DRAWN)
    (problem,) = navigator_problems(mazesim.load_world(str(drawn)))
    assert "the grey [floor] of generated mazes" in problem
    assert "these 3 [[checkpoints]]" in problem and "at the end of the world file" in problem
    tables = problem.split("\n\n", 1)[1]
    assert tables.startswith("[floor]\nreflectance = 0.36\n\n[[checkpoints]]\nid = 1\n")
    assert main(["show", str(drawn), "-o", str(tmp_path / "drawn.png")]) == 0
    assert tables in capsys.readouterr().out
    # The refusal of train, one line, says which command prints them.
    args = ["train", "--world", str(drawn), "--out", str(tmp_path / "run"), *QUICK]
    assert main(args) == 2
    refusal = capsys.readouterr().err
    assert refusal.rstrip().endswith(f"that this command prints: mazesim show {drawn}")
    assert len(refusal.splitlines()) == 1
    # Pasted as told, the navigator can learn the maze, its codes before its junctions.
    drawn.write_text(DRAWN + "\n" + tables + "\n")
    world = mazesim.load_world(str(drawn))
    assert navigator_problems(world) == []
    assert world.floor_background == 0.36
    # The same checkpoints, and no second [floor] now that the world has one.
    assert world.junction_checkpoints() == tables.split("\n\n", 1)[1] + "\n"
    maze = CellMaze(world)
    for checkpoint in world.checkpoints():
        x, y = checkpoint["center"]
        assert 1.0 < x < 1.75 and 2.0 < y < 2.75
        # Just ahead of each code, along its reading direction, lies a junction.
        ahead = 0.6 * maze.cell_size
        yaw = float(checkpoint["yaw"])
        column, row = maze.cell_at(x + ahead * math.cos(yaw), y + ahead * math.sin(yaw))
        assert len(maze.openings((int(column), int(row)))) >= 3


def test_a_maze_without_a_junction_is_told_to_open_one() -> None:
    corridor = WALLED.replace("|S    |G |", "|S     G |").replace("+  +--+  +", "+--+--+--+")
    world = mazesim.World.from_toml(corridor, source="corridor.toml")
    assert world.junction_checkpoints() == ""
    (problem,) = [p for p in navigator_problems(world) if "checkpoints" in p]
    assert "no junction" in problem and "open a wall of the [grid] map" in problem


@pytest.mark.parametrize(
    ("start", "said"),
    [
        ("x = 0.0\ny = 0.0", "with its centre 0.0050 m inside a wall"),
        ("x = 5.0\ny = 5.0", "its start (5, 5) is outside the maze, which spans x 0 to 0.75"),
    ],
)
def test_a_start_on_a_wall_or_outside_the_maze_is_a_problem(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], start: str, said: str
) -> None:
    text = mazesim.generate_maze(3, 3, seed=1).to_toml()
    assert "[start]\nx = 0.125\ny = 0.125" in text
    world = tmp_path / "moved.toml"
    world.write_text(text.replace("[start]\nx = 0.125\ny = 0.125", f"[start]\n{start}"))
    (problem,) = navigator_problems(mazesim.load_world(str(world)))
    assert said in problem and "move the [start] pose" in problem
    assert main(["show", str(world), "-o", str(tmp_path / "moved.png")]) == 0
    assert f"the navigator cannot learn it: {problem}" in capsys.readouterr().out


def _moved(start: str | None, row: str) -> mazesim.World:
    """The 3 x 3 maze of seed 1 with its [start] pose moved (deleted for None) and its S row
    (the bottom row, ``|S       |``) redrawn."""
    text = mazesim.generate_maze(3, 3, seed=1).to_toml()
    pose = "[start]\nx = 0.125\ny = 0.125\nyaw = 0.0\n"
    assert pose in text and "|S       |" in text
    text = text.replace(pose, "" if start is None else f"[start]\n{start}\nyaw = 0.0\n")
    return mazesim.World.from_toml(text.replace("|S       |", row), source="moved.toml")


def test_a_start_pose_without_an_s_starts_in_the_cell_holding_it() -> None:
    world = _moved("x = 0.375\ny = 0.125", "|        |")
    assert CellMaze(world).start_cell == (1, 2)
    assert navigator_problems(world) == []


def test_a_start_on_the_line_between_two_cells_is_told_their_centres() -> None:
    (problem,) = navigator_problems(_moved("x = 0.25\ny = 0.125", "|        |"))
    assert problem == (
        "its start (0.25, 0.125) is on the line between the cells (column 0, row 2) and "
        "(column 1, row 2), so it is in none of them: move the [start] pose to a cell's centre, "
        "(0.125, 0.125) or (0.375, 0.125)"
    )
    # On the S's edge, the S decides.
    assert CellMaze(_moved("x = 0.25\ny = 0.125", "|S       |")).start_cell == (0, 2)


def test_an_s_moved_away_from_the_start_pose_is_a_problem() -> None:
    (problem,) = navigator_problems(_moved("x = 0.125\ny = 0.125", "|      S |"))
    assert "the S of the [grid] map is in (column 2, row 2)" in problem
    assert "delete the [start] table to start at the S" in problem
    assert navigator_problems(_moved(None, "|      S |")) == []


def test_a_goal_farther_than_an_episode_can_drive_is_refused_before_training(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    world = tmp_path / "big.toml"
    mazesim.generate_maze(20, 20, seed=7).save(str(world))
    (problem,) = learning_problems(mazesim.load_world(str(world)))
    assert problem.startswith("its goal is 46.75 m from the start along the cells, about 11,328")
    assert "more than the 4000 an episode lasts (16.5 m)" in problem
    assert main(["show", str(world), "-o", str(tmp_path / "big.png")]) == 0
    assert f"the navigator cannot learn it: {problem}" in capsys.readouterr().out
    out = tmp_path / "run"
    assert main(["train", "--world", str(world), "--out", str(out), *QUICK]) == 2
    assert problem in capsys.readouterr().err and not out.exists()
    assert learning_problems(mazesim.load_world("seed-maze")) == []


@pytest.mark.parametrize("flat", [False, True])
def test_a_world_the_navigator_cannot_learn_is_refused_before_training(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], flat: bool
) -> None:
    world = tmp_path / "corridor.toml"
    _corridor().save(str(world))
    out = tmp_path / "run"
    args = ["train", "--world", str(world), "--out", str(out), *QUICK]
    assert main([*args, *(["--flat"] if flat else [])]) == 2
    error = capsys.readouterr().err
    assert "the navigator cannot learn world 'maze-4x4-seed3'" in error
    assert "no barcode checkpoints" in error and str(world) in error
    assert not out.exists()


def test_differing_shows_where_two_long_values_differ() -> None:
    common = '{"lower": {"shape": [4096, 12], "dtype": "float64"}, ' * 6
    expected = common + '"higher": {"shape": [14, 4], "dtype": "float64"}}'
    found = common + '"higher": {"shape": [0], "dtype": "float64"}}'
    text = differing(expected, found)
    assert "[14, 4]" in text and "[0]" in text
    first = len(common) + len('"higher": {"shape": [') + 1
    assert f"from character {first} on" in text
    assert text.count("...") == 2  # both cut before the difference; the rest of each fits
    assert differing("[1, 2]", "[1, 3]") == "expected [1, 2], found [1, 3]"


def test_a_mismatched_table_description_names_the_difference(tmp_path: Path) -> None:
    from mazesim.learn.tables import save_policy

    policy = load_policy()
    save_policy(policy, tmp_path)
    meta = json.loads((tmp_path / "policy.json").read_text())
    meta["tables"]["arrays"]["higher"]["dtype"] = "int64"
    (tmp_path / "policy.json").write_text(json.dumps(meta))
    with pytest.raises(PolicyFormatError) as raised:
        load_policy(tmp_path)
    message = str(raised.value)
    assert '"higher": {"shape": [14, 4], "dtype": "float64"}' in message
    assert '"higher": {"shape": [14, 4], "dtype": "int64"}' in message


def test_a_navigator_keeps_its_world_file_and_eval_finds_it(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    mazesim.generate_maze(4, 4, seed=3).save("my-maze.toml")
    assert main(["train", "--world", "my-maze.toml", "--out", "nav", *FLAT]) == 0
    printed = capsys.readouterr().out
    assert printed.splitlines()[-1] == "evaluate it with: mazesim eval --policy nav"
    policy = load_policy("nav")
    assert policy.world_file == str(tmp_path / "my-maze.toml")
    # From another folder, the printed command (with the folder's path) still works.
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    short = ["--episodes", "2", "--max-steps", "200"]
    assert main(["eval", "--policy", "../nav", *short, "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["episodes"] == 2
    os.remove(tmp_path / "my-maze.toml")
    with pytest.raises(UnknownNameError) as raised:
        load_policy("../nav").learned_world()
    assert str(tmp_path / "my-maze.toml") in str(raised.value)
    assert "--world FILE" in str(raised.value)
    assert main(["eval", "--policy", "../nav", *short]) == 2
    assert "no longer there" in capsys.readouterr().err


def test_the_shipped_navigator_names_a_builtin_world_and_no_file() -> None:
    policy = load_policy()
    assert policy.world_file is None
    assert policy.learned_world().name == "seed-maze"


def test_the_hrl_demo_in_a_new_maze_says_it_trains_and_when_time_ran_out(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    from mazesim.cli.demo import HRL_DEFAULT_SECONDS
    from mazesim.episodes import MAX_STEPS
    from mazesim.learn.subtasks import CONTROL_STEP_MS

    assert HRL_DEFAULT_SECONDS == MAX_STEPS * CONTROL_STEP_MS / 1000
    monkeypatch.chdir(tmp_path)
    mazesim.generate_maze(4, 4, seed=3).save("my-maze.toml")
    args = ["demo", "--controller", "hrl", "--world", "my-maze.toml", "--no-progress"]
    assert main([*args, "--seconds", "5", "--out", "short"]) == 0
    printed = capsys.readouterr().out
    assert printed.startswith("training the higher level in maze-4x4-seed3 first")
    assert "goal reached       no: the time limit of 5 simulated seconds ended the run" in printed
    assert "--seconds 10" in printed and "s training the higher level" in printed
    summary = json.loads((tmp_path / "short" / "summary.json").read_text())
    assert summary["goal_reached"] is False and summary["steps"] == 79
