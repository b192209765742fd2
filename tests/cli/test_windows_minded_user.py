"""Issue 37: a user used to Windows or macOS on Linux. Paths with spaces and non-ASCII letters in
the commands mazesim prints for copying, text files from Windows editors (a byte-order mark,
UTF-16, Latin-1), and paths written with Windows' backslashes."""

from __future__ import annotations

import argparse
import codecs
import shlex
from pathlib import Path

import pytest

import mazesim
from mazesim.cli import build_parser, main
from mazesim.distributed.config import load_sweep_config
from mazesim.errors import PolicyFormatError
from mazesim.webots.keyboard import read_keys

SWEEP = """[sweep]
name = "bom"

[grid]
seed = [0, 1]
"""


def _printed_command(output: str, opening: str) -> list[str]:
    """The words of the command that follows ``opening`` on a line of ``output``, as a shell
    splits them."""
    (line,) = [line for line in output.splitlines() if opening in line]
    return shlex.split(line.split(opening, 1)[1].rstrip(")"))


def test_show_prints_a_train_command_that_a_shell_runs_with_a_spaced_path(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    world = "Mes labyrinthes ü/maze 1.toml"
    (tmp_path / "Mes labyrinthes ü").mkdir()
    mazesim.generate_maze(4, 4, seed=3).save(world)
    assert main(["show", world, "-o", "maze.png"]) == 0
    words = _printed_command(capsys.readouterr().out, "can learn it (")
    assert words == ["mazesim", "train", "--world", world]


def test_worlds_export_prints_a_show_command_that_a_shell_runs(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    assert main(["worlds", "--export", "seed-maze", "--out", "my maze.toml"]) == 0
    words = _printed_command(capsys.readouterr().out, "edit it, then: ")
    assert words == ["mazesim", "show", "my maze.toml"]


def test_a_maze_without_checkpoints_names_a_show_command_a_shell_runs(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    world = "my maze ü.toml"
    layout = mazesim.MazeLayout(checkpoints=False)
    mazesim.generate_maze(4, 4, seed=3, layout=layout).save(world)
    assert main(["train", "--world", world, "--out", "nav"]) == 2
    error = capsys.readouterr().err
    words = _printed_command(error, "that this command prints: ")
    assert words == ["mazesim", "show", world]


def test_a_byte_order_mark_is_not_part_of_a_text_file(tmp_path: Path) -> None:
    keys = tmp_path / "keys.txt"
    keys.write_bytes(codecs.BOM_UTF8 + b"0.5 UP 1.0\r\n2.0 LEFT 0.5\r\n")
    plain = tmp_path / "plain.txt"
    plain.write_bytes(b"0.5 UP 1.0\n2.0 LEFT 0.5\n")
    assert [vars(press) for press in read_keys(keys).presses] == [
        vars(press) for press in read_keys(plain).presses
    ]
    sweep = tmp_path / "sweep.toml"
    sweep.write_bytes(codecs.BOM_UTF8 + SWEEP.replace("\n", "\r\n").encode())
    assert load_sweep_config(sweep).name == "bom"


@pytest.mark.parametrize(
    ("encoding", "found"),
    [
        ("utf-16", "found UTF-16 text (it starts with the byte-order mark FF FE)"),
        ("latin-1", "found a byte 0xE8 that is not UTF-8"),
    ],
)
def test_a_text_file_in_another_encoding_says_to_save_it_as_utf8(
    tmp_path: Path, encoding: str, found: str
) -> None:
    keys = tmp_path / "keys.txt"
    keys.write_text("# flèche\n0.5 UP 1.0\n", encoding=encoding)
    with pytest.raises(mazesim.InvalidArgumentError) as refused:
        read_keys(keys)
    assert found in str(refused.value)
    assert "save it as UTF-8" in str(refused.value)


@pytest.mark.parametrize(
    ("encoding", "found"),
    [
        ("utf-16", "found UTF-16 text (it starts with the byte-order mark FF FE)"),
        ("latin-1", "found a byte 0xE8 that is not UTF-8"),
    ],
)
@pytest.mark.parametrize("kind", ["world", "robot profile"])
def test_a_world_or_profile_in_another_encoding_says_to_save_it_as_utf8(
    tmp_path: Path, encoding: str, found: str, kind: str
) -> None:
    """The core reads world and robot profile files: it names the encoding it found, as the
    package's own text readers do, instead of "stream did not contain valid UTF-8"."""
    source = tmp_path / "source.toml"
    if kind == "world":
        mazesim.generate_maze(3, 3, seed=1).save(str(source))
    else:
        source.write_text(mazesim.RobotProfile.builtin("e-puck").to_toml(), encoding="utf-8")
    text = "# flèche\n" + source.read_text(encoding="utf-8")
    other = tmp_path / "other.toml"
    other.write_text(text, encoding=encoding)
    with pytest.raises(mazesim.MazesimError) as refused:
        if kind == "world":
            mazesim.load_world(other)
        else:
            mazesim.RobotProfile.load(other)
    assert found in str(refused.value)
    assert "save it as UTF-8" in str(refused.value)


@pytest.mark.parametrize("command", ["show", "demo"])
def test_a_path_with_windows_backslashes_gets_the_path_meant(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    monkeypatch: pytest.MonkeyPatch,
    command: str,
) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "maps").mkdir()
    mazesim.generate_maze(3, 3, seed=1).save("maps/maze.toml")
    world = ["maps\\maze.toml"] if command == "show" else ["--world", "maps\\maze.toml"]
    assert main([command, *world]) == 2
    error = capsys.readouterr().err
    assert "folders are separated by '/' here, not by '\\' as on Windows" in error
    assert "did you mean 'maps/maze.toml'?" in error


def test_a_missing_controller_written_with_backslashes_gets_the_path_meant(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "controllers").mkdir()
    (tmp_path / "controllers" / "wander.py").write_text("pass\n", encoding="utf-8")
    assert main(["webots", "run", "controllers\\wander.py", "--seconds", "1"]) == 2
    error = capsys.readouterr().err
    assert "folders are separated by '/' here, not by '\\' as on Windows" in error
    assert error.rstrip().endswith("/controllers/wander.py'?")


#: What a command-line option that names a file or folder to write is called.
WRITTEN = {"out", "html", "video", "record", "trace", "plot"}


def _written_options() -> list[tuple[str, str, argparse.Action]]:
    """(command, option, action) of every option of every command that names what it writes."""
    found = []

    def walk(parser: argparse.ArgumentParser) -> None:
        for action in parser._actions:
            if isinstance(action, argparse._SubParsersAction):
                for chosen in dict.fromkeys(action.choices.values()):
                    walk(chosen)
            elif action.option_strings and action.dest in WRITTEN:
                found.append((parser.prog, action.option_strings[-1], action))

    walk(build_parser())
    return found


def test_every_option_that_names_what_is_written_refuses_windows_backslashes() -> None:
    """One door, :func:`mazesim._paths.output_path`, which every written path's type passes:
    ``-o out\\maze.png`` would write a file of that name beside the folder ``out``."""
    options = _written_options()
    assert {("mazesim train", "--out"), ("mazesim show", "--out"), ("mazesim demo", "--html")} <= {
        (command, option) for command, option, _ in options
    }
    for command, option, action in options:
        if action.type is None:  # read as text, then checked as a written file when it runs
            assert (command, option) == ("mazesim worlds", "--out")
            continue
        with pytest.raises(argparse.ArgumentTypeError) as refused:
            action.type("results\\run.mp4")
        assert "folders are separated by '/' here" in str(refused.value), (command, option)


@pytest.mark.parametrize(
    "arguments",
    [
        ["show", "maps/maze.toml", "-o", "out\\maze.png"],
        ["worlds", "--export", "seed-maze", "--out", "out\\maze.toml"],
    ],
)
def test_a_file_to_write_named_with_backslashes_is_refused_naming_the_path_meant(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    monkeypatch: pytest.MonkeyPatch,
    arguments: list[str],
) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "maps").mkdir()
    (tmp_path / "out").mkdir()
    mazesim.generate_maze(3, 3, seed=1).save("maps/maze.toml")
    assert main(arguments) == 2
    error = capsys.readouterr().err
    meant = arguments[-1].replace("\\", "/")
    assert (
        f"folders are separated by '/' here, not by '\\' as on Windows: did you mean {meant!r}?"
        in error
    )
    assert sorted(p.name for p in tmp_path.iterdir()) == ["maps", "out"]  # nothing written
    assert not any((tmp_path / "out").iterdir())


def test_a_navigator_folder_written_with_backslashes_gets_the_path_meant(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """The navigator's folder says it as world files and controllers do."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "runs" / "navigator").mkdir(parents=True)
    assert main(["eval", "--policy", "runs\\navigator", "--episodes", "1"]) == 2
    error = capsys.readouterr().err
    assert "folders are separated by '/' here, not by '\\' as on Windows" in error
    assert "did you mean 'runs/navigator'?" in error
    with pytest.raises(mazesim.MazesimError, match="did you mean 'runs/navigator'"):
        mazesim.learn.load_policy("runs\\navigator")


@pytest.mark.parametrize(
    ("encoding", "found"),
    [
        ("utf-8-sig", None),
        ("utf-16", "found UTF-16 text (it starts with the byte-order mark FF FE)"),
    ],
)
def test_a_navigators_metadata_saved_by_a_windows_editor(
    tmp_path: Path, encoding: str, found: str | None
) -> None:
    """policy.json opened and saved again in a Windows editor: read with its byte-order mark as
    every text reader of mazesim's reads one, or refused naming the encoding (the metadata
    reader called the first "not valid JSON (truncated or corrupt?)" and the second "'utf-8'
    codec can't decode byte 0xff")."""
    from mazesim.learn import load_policy, save_policy

    folder = tmp_path / "nav"
    policy = load_policy()
    save_policy(policy, folder)
    metadata = folder / "policy.json"
    metadata.write_text(metadata.read_text(encoding="utf-8"), encoding=encoding)
    if found is None:
        loaded = load_policy(folder)
        assert (loaded.world_sha256, loaded.training) == (policy.world_sha256, policy.training)
        return
    with pytest.raises(PolicyFormatError) as refused:
        load_policy(folder)
    assert found in str(refused.value) and "save it as UTF-8" in str(refused.value)
