"""Issue 37: the own-maze recipe (docs/own-maze.md) runs as printed, and what the page says the
commands print is what they print."""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import mazesim
from docs_blocks import console_commands, parse_blocks, run_command
from mazesim.maze import CellMaze

REPO = Path(__file__).resolve().parents[2]
PAGE = REPO / "docs" / "own-maze.md"
#: A guard against a command that hangs, not a speed requirement.
COMMAND_TIMEOUT_S = 900
NUMBERS = {"one": 1, "two": 2, "three": 3, "four": 4}


def _blocks() -> tuple[list[str], str]:
    """The recipe's commands and the output the page shows for ``mazesim show``."""
    blocks = parse_blocks(PAGE, PAGE.read_text(encoding="utf-8"), REPO)
    (recipe,) = [block for block in blocks if block.language == "console"]
    (shown,) = [block for block in blocks if block.language == "text"]
    return console_commands(recipe.text).splitlines(), shown.text


def test_the_recipe_is_five_commands_that_make_train_evaluate_and_watch() -> None:
    commands, _ = _blocks()
    assert len(commands) == 5
    assert [shlex.split(command)[:2] for command in commands[1:]] == [
        ["mazesim", "show"],
        ["mazesim", "train"],
        ["mazesim", "eval"],
        ["mazesim", "eval"],
    ]


def test_the_recipe_runs_as_printed(tmp_path: Path) -> None:
    commands, shown = _blocks()
    printed = []
    for command in commands:
        finished = run_command(["bash", "-e", "-c", command], tmp_path, COMMAND_TIMEOUT_S)
        assert finished.returncode == 0, f"{command}\n{finished.stdout}\n{finished.stderr}"
        printed.append(finished.stdout)
    make, show, train, evaluate, watch = printed
    assert make == ""
    assert show == shown
    # The command train ends with is the recipe's next one, up to the options it adds.
    advised = train.splitlines()[-1]
    assert advised == "evaluate it with: mazesim eval --policy my-navigator"
    assert commands[3].startswith(advised.split(": ", 1)[1])
    # The page's measured success is this run's (the run is deterministic).
    success = re.search(r"success rate\s+([\d.]+)%", evaluate)
    assert success is not None, evaluate
    reached = round(float(success.group(1)) * 20 / 100)
    page = PAGE.read_text(encoding="utf-8")
    assert f"reached the goal in {reached} of the 20 episodes" in page
    ratio = re.search(r"mean path ratio\s+([\d.]+)", evaluate)
    clean = re.search(r"without collision\s+([\d.]+)%", evaluate)
    assert ratio is not None and clean is not None, evaluate
    contacts = "no wall contact" if float(clean.group(1)) == 100.0 else "wall contacts"
    assert f"(path ratio {ratio.group(1)}, {contacts};" in " ".join(page.split())
    assert (tmp_path / "my-run.html").read_text(encoding="utf-8").lstrip().startswith("<!")
    assert "my-run.html" in watch


def _drawn_map() -> str:
    """The hand-drawn world file the page shows (its one ``toml`` block)."""
    blocks = parse_blocks(PAGE, PAGE.read_text(encoding="utf-8"), REPO)
    (drawn,) = [block for block in blocks if block.language == "toml"]
    assert drawn.is_world
    return drawn.text


def test_the_hand_drawn_maze_has_junctions_and_learns_once_its_checkpoints_are_pasted(
    tmp_path: Path,
) -> None:
    page = " ".join(PAGE.read_text(encoding="utf-8").split())
    promised = re.search(r"every way into every junction \(here (\d+),", page)
    assert promised is not None
    count = int(promised.group(1))
    junctions = re.search(r"has (\w+) junctions \(cells with three ways out\)", page)
    assert junctions is not None
    sides = CellMaze(mazesim.World.from_toml(_drawn_map())).open_sides().sum(axis=2)
    assert NUMBERS[junctions.group(1)] == int((sides >= 3).sum()) > 0
    (tmp_path / "drawn.toml").write_text(_drawn_map(), encoding="utf-8")
    # As drawn: no checkpoints, so train refuses it and names the command that prints them.
    train = run_command(
        ["mazesim", "train", "--world", "drawn.toml", "--out", "nav"], tmp_path, COMMAND_TIMEOUT_S
    )
    assert train.returncode == 2, train.stdout + train.stderr
    assert train.stderr.rstrip().endswith("that this command prints: mazesim show drawn.toml")
    assert not (tmp_path / "nav").exists()
    shown = run_command(["mazesim", "show", "drawn.toml"], tmp_path, COMMAND_TIMEOUT_S)
    assert shown.returncode == 0, shown.stderr
    assert f"these {count} [[checkpoints]]" in shown.stdout
    tables = shown.stdout.split("\n\n", 1)[1]
    assert tables.startswith("[floor]\n")
    assert tables.count("[[checkpoints]]") == count
    # Pasted at the end of the file, as the message says: the navigator can learn it.
    with (tmp_path / "drawn.toml").open("a", encoding="utf-8") as file:
        file.write("\n" + tables)
    again = run_command(["mazesim", "show", "drawn.toml"], tmp_path, COMMAND_TIMEOUT_S)
    assert again.returncode == 0, again.stderr
    said = f"{count} checkpoints and a goal in reach"
    assert said in again.stdout
    assert f"`{said}`" in page
