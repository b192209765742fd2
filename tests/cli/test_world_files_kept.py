"""One rule for every command that writes a world file: an existing one (a file its user edits) is
kept unless ``--force``; a device such as ``/dev/stdout`` is written. The commands are found from
the parser (an output option whose metavar is ``WORLD_FILE``), so a new one meets the rule."""

from __future__ import annotations

import argparse
from collections.abc import Iterator
from pathlib import Path

import pytest

import mazesim
from mazesim.cli import build_parser, main

WBT = Path(__file__).resolve().parents[2] / "examples" / "worlds" / "boxes.wbt"

#: How each command that writes a world file is run, writing into the path given.
RUNS = {
    "worlds": lambda out: ["worlds", "--export", "arena", "--out", out],
    "import-wbt": lambda out: ["import-wbt", str(WBT), "--out", out],
}


def _options(
    parser: argparse.ArgumentParser, words: tuple[str, ...] = ()
) -> Iterator[tuple[str, argparse.Action, argparse.ArgumentParser]]:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                yield from _options(sub, (*words, name))
        elif action.option_strings:
            yield " ".join(words), action, parser


def test_every_command_writing_a_world_file_is_found_and_has_force() -> None:
    writers = set()
    for command, action, parser in _options(build_parser()):
        written = "world file" in (action.help or "") and "write" in (action.help or "")
        if action.metavar == "WORLD_FILE" or (written and "--out" in action.option_strings):
            assert action.metavar == "WORLD_FILE", (command, action.option_strings)
            writers.add(command)
            forces = [a for a in parser._actions if "--force" in a.option_strings]
            assert forces, f"mazesim {command} writes a world file and has no --force"
    assert writers == set(RUNS)


@pytest.mark.parametrize("command", sorted(RUNS))
def test_an_existing_world_file_is_kept_unless_forced(
    command: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    mine = tmp_path / "mine.toml"
    mine.write_text("# my own maze, edited by hand\n")
    assert main(RUNS[command](str(mine))) == 2
    error = capsys.readouterr().err
    assert "exists: name another file, or add --force to overwrite it" in error
    assert mine.read_text() == "# my own maze, edited by hand\n"
    link = tmp_path / "link.toml"
    link.symlink_to(mine)
    assert main(RUNS[command](str(link))) == 2
    assert mine.read_text() == "# my own maze, edited by hand\n"
    assert main([*RUNS[command](str(mine)), "--force"]) == 0
    assert len(mazesim.load_world(str(mine)).wall_boxes()) > 0
    fresh = tmp_path / "fresh.toml"
    assert main(RUNS[command](str(fresh))) == 0
    assert fresh.read_text().startswith('format = "mazesim-world"')


@pytest.mark.parametrize("command", sorted(RUNS))
def test_a_device_is_written_without_force(command: str) -> None:
    assert main(RUNS[command]("/dev/null")) == 0
