"""Issue 15: every command given hostile arguments ends with exit 2 and one line, never a traceback.

The commands and their options are discovered from the parser, so a new command or option is
tested without being listed here. Each run is a subprocess with a time limit and a 4 GiB
address-space cap. Arguments that make a run quick (``--seconds 1``) come first; the hostile
value comes last, so it wins.
"""

from __future__ import annotations

import argparse
import os
import resource
import stat
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import IO

import pytest

from mazesim.cli import build_parser, main
from ros_support import needs_ros

REPO = Path(__file__).resolve().parents[2]
WBT = REPO / "tests" / "data" / "webots-worlds" / "e-puck.R2023b.wbt"
MEMORY_CAP = 4 * 1024**3
#: A ceiling that tells a hang from a slow start on a loaded machine.
TIME_LIMIT_S = 300
#: Runs at once (each mostly waits for its imports).
PARALLEL_RUNS = 4

#: Numbers no option accepts: too large for any count, negative, not a number, infinite.
HOSTILE_NUMBERS = ("1" + "0" * 40, "-5", "nan", "inf", "1e400")
#: Inputs that cannot be read as what they should be.
HOSTILE_INPUTS = ("", "missing", "folder", "unreadable", "garbage")
#: Places no output folder (``--out DIR``) can be made at.
HOSTILE_OUTPUTS = ("", "a-file", "under-a-file")
#: Places no output file (``--trace FILE``) can be written to.
HOSTILE_OUTPUT_FILES = ("", "folder", "under-a-file")
#: Arguments that keep a valid run short, by command.
QUICK = {
    "demo": ["--seconds", "1"],
    "worlds": ["--export", "arena"],
    "bench": ["--envs", "1", "--blocks", "1", "--block-steps", "100", "--threads", "1"],
    "barcode-study": ["--readings", "1", "--envs", "1", "--thresholds", "1.4", "--speeds", "3"],
    "webots run": ["--seconds", "1"],
    "sweep": ["--sequential", "--quiet"],
    "eval": ["--episodes", "1", "--events", "truth", "--max-steps", "50"],
    "transfer-study": ["--axes", "latency", "--episodes", "1", "--max-steps", "50", "--no-pairs"],
    "ros bridge": ["--duration", "1"],
    "ros demo": ["--seconds", "1"],
    "ros2 bridge": ["--mode", "free", "--speed", "0", "--stop-after", "1"],
    "ros2 demo": ["--steps", "1", "--controller", "avoid-collision"],
}
#: Options that name outputs (the others taking paths are inputs).
OUTPUT_OPTIONS = {"--out", "--trace", "--plot", "--html", "--video", "--record"}
#: Options that take a name or an address, not a path or a number.
NAME_OPTIONS = {"--robot", "--name", "--address", "--export", "remappings"}

SMALL_SWEEP = """
[sweep]
name = "small"

[grid]
trainer = "flat-q"
seed = 0
maze_size = 3
envs = 2
steps = 20
episode_steps = 20
eval_episodes = 1
"""
CONTROLLER = """
from controller import Robot
robot = Robot()
while robot.step(64) != -1:
    pass
"""


def _commands(
    parser: argparse.ArgumentParser, words: list[str]
) -> Iterator[tuple[str, argparse.ArgumentParser]]:
    subparsers = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    if not subparsers:
        yield " ".join(words), parser
        return
    for name, child in subparsers[0].choices.items():
        yield from _commands(child, [*words, name])


def _value_options(parser: argparse.ArgumentParser) -> Iterator[argparse.Action]:
    for action in parser._actions:
        if action.nargs == 0 or isinstance(action, argparse._HelpAction) or action.choices:
            continue
        yield action


def _kind(action: argparse.Action) -> str:
    names = set(action.option_strings or [action.dest])
    if names & NAME_OPTIONS:
        return "name"
    if names & OUTPUT_OPTIONS:
        return "output" if action.metavar == "DIR" else "output file"
    return "input" if action.type is None else "number"


#: How many hostile values each option of a kind gets (rotating through the kind's values).
VALUES_PER_OPTION = {"number": 1, "input": 2, "output": 3, "output file": 3, "name": 1}
VALUES = {
    "number": HOSTILE_NUMBERS,
    "input": HOSTILE_INPUTS,
    "output": HOSTILE_OUTPUTS,
    "output file": HOSTILE_OUTPUT_FILES,
    "name": ("",),
}


def _hostile_sets(
    parser: argparse.ArgumentParser, turns: dict[str, int]
) -> list[tuple[argparse.Action | None, str]]:
    """(argument, hostile value) pairs of one command; (None, value) for an unknown option.

    Each kind's values are dealt out in turn across all commands (``turns`` counts them), so
    every value is tried somewhere.
    """
    sets: list[tuple[argparse.Action | None, str]] = [(None, "--no-such-option")]
    for action in _value_options(parser):
        kind = _kind(action)
        values = VALUES[kind]
        for _ in range(VALUES_PER_OPTION[kind]):
            sets.append((action, values[turns.get(kind, 0) % len(values)]))
            turns[kind] = turns.get(kind, 0) + 1
    return sets


COMMANDS = dict(_commands(build_parser(), []))
_TURNS: dict[str, int] = {}
HOSTILE_SETS = {command: _hostile_sets(COMMANDS[command], _TURNS) for command in sorted(COMMANDS)}


@pytest.fixture(scope="module")
def files(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    folder = tmp_path_factory.mktemp("hostile-files")
    made = {
        "folder": folder / "a-folder",
        "unreadable": folder / "unreadable.toml",
        "garbage": folder / "garbage.toml",
        "a-file": folder / "a-file",
        "sweep": folder / "sweep.toml",
        "controller": folder / "controller.py",
    }
    made["fifo"] = folder / "no-writer.fifo"
    os.mkfifo(made["fifo"])
    made["folder"].mkdir()
    made["unreadable"].write_text("[world]\n")
    made["unreadable"].chmod(0)
    made["garbage"].write_bytes(bytes(range(256)) * 8)
    made["a-file"].write_text("not a folder\n")
    made["sweep"].write_text(SMALL_SWEEP)
    made["controller"].write_text(CONTROLLER)
    made["run"] = folder / "run.json"
    recorded = subprocess.run(
        [sys.executable, "-m", "mazesim", "demo", "--seconds", "1", "--out", str(folder / "demo")]
        + ["--record", str(made["run"])],
        capture_output=True,
        text=True,
        check=False,
    )
    assert recorded.returncode == 0, recorded.stderr
    return made


def _value(value: str, files: dict[str, Path], tmp_path: Path) -> str:
    if value == "missing":
        return str(tmp_path / "no-such-thing.toml")
    if value == "under-a-file":
        return str(files["a-file"] / "inside")
    if value in files:
        return str(files[value])
    return value


def _positionals(command: str, files: dict[str, Path]) -> dict[str, str]:
    """Valid values of the commands' positional arguments."""
    return {
        "file": str(WBT),
        "controller": str(files["controller"]),
        "config": str(files["sweep"]),
        "run_file": str(files["run"]),
        "world": "arena",
    }


def _limit_memory() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_CAP, MEMORY_CAP))


@dataclass
class Ending:
    """How a run ended: its exit code and error output, or None when it was stopped."""

    arguments: list[str]
    returncode: int | None
    stderr: str


def run_limited(runs: list[tuple[list[str], Path]], log_folder: Path) -> list[Ending]:
    """Runs ``mazesim ARGUMENTS`` in ``folder`` for each run, a few at a time, each in a
    subprocess under the memory cap, stopped after the time limit.

    The subprocesses are started from this thread alone (``preexec_fn`` is not safe beside other
    threads), and write their error output to files, so no pipe needs a reader.
    """
    endings: list[Ending | None] = [None] * len(runs)
    waiting = list(enumerate(runs))
    running: list[tuple[int, subprocess.Popen[bytes], IO[bytes], float]] = []
    while waiting or running:
        while waiting and len(running) < PARALLEL_RUNS:
            index, (arguments, folder) = waiting.pop(0)
            stderr = open(log_folder / f"stderr-{index}.txt", "w+b")  # noqa: SIM115
            process = subprocess.Popen(
                [sys.executable, "-m", "mazesim", *arguments],
                stdin=subprocess.DEVNULL,
                stdout=subprocess.DEVNULL,
                stderr=stderr,
                cwd=folder,
                preexec_fn=_limit_memory,
                env={**os.environ, "PYTHONWARNINGS": "error"},
            )
            running.append((index, process, stderr, time.monotonic()))
        time.sleep(0.05)
        for entry in list(running):
            index, process, stderr, started = entry
            if process.poll() is None and time.monotonic() - started < TIME_LIMIT_S:
                continue
            code = process.poll()
            if code is None:
                process.kill()
                process.wait()
            stderr.seek(0)
            text = stderr.read().decode("utf-8", "replace")
            stderr.close()
            endings[index] = Ending(runs[index][0], code, text)
            running.remove(entry)
    return [ending for ending in endings if ending is not None]


def _arguments(
    command: str,
    parser: argparse.ArgumentParser,
    hostile: tuple[argparse.Action | None, str],
    files: dict[str, Path],
    folder: Path,
) -> list[str]:
    action, value = hostile
    arguments = [*command.split(), *QUICK.get(command, [])]
    text = _value(value, files, folder)
    for positional in _value_options(parser):
        required = positional.nargs in (None, "+")  # one value each ("+": `show WORLD...`)
        if not positional.option_strings and positional is not action and required:
            arguments.append(_positionals(command, files)[positional.dest])
    if action is None:
        arguments.append(value)
    elif action.option_strings:
        arguments += [action.option_strings[0], text]
    else:
        arguments.append(text)
    return arguments


def _problem(ending: Ending) -> str | None:
    """What is wrong with a run's ending, or None."""
    if ending.returncode is None:
        return f"still running after {TIME_LIMIT_S} s"
    if "Traceback" in ending.stderr or "internal error" in ending.stderr:
        return f"a traceback or an internal error: {ending.stderr[-2000:]}"
    if ending.returncode not in (0, 2):
        return f"exit {ending.returncode}: {ending.stderr[-2000:]}"
    if ending.returncode == 2:
        # One line: ours, or argparse's usage line followed by its one-line error.
        lines = ending.stderr.strip().splitlines()
        if not lines or not lines[-1].startswith("mazesim") or "error: " not in lines[-1]:
            return f"no one-line error: {ending.stderr[-2000:]}"
        if len(lines) > 1 and not lines[0].startswith("usage: "):
            return f"more than one line: {ending.stderr[-2000:]}"
    return None


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_hostile_arguments_end_in_one_line_and_exit_2(
    command: str, files: dict[str, Path], tmp_path: Path
) -> None:
    parser = COMMANDS[command]
    runs = []
    for number, hostile in enumerate(HOSTILE_SETS[command]):
        if hostile[1] == "unreadable" and os.geteuid() == 0:
            continue  # root reads files without read permission
        folder = tmp_path / f"run-{number}"
        folder.mkdir()
        runs.append((_arguments(command, parser, hostile, files, folder), folder))
    problems = [
        f"mazesim {' '.join(ending.arguments)}: {problem}"
        for ending in run_limited(runs, tmp_path)
        if (problem := _problem(ending))
    ]
    assert not problems, "\n".join(problems)


def test_every_command_is_covered() -> None:
    commands = set(COMMANDS)
    assert {"demo", "train", "eval", "import-wbt", "sweep", "webots run"} <= commands


def _output_file_options(parser: argparse.ArgumentParser) -> list[argparse.Action]:
    return [
        action
        for action in _value_options(parser)
        if action.option_strings and _kind(action) == "output file"
    ]


#: The names of the option or positional argument naming a command's main input file.
INPUT_NAMES = ("--world", "world", "run_file", "file")


def _input_of(parser: argparse.ArgumentParser) -> argparse.Action:
    """The option or positional argument naming the command's main input file."""
    by_name = {a.option_strings[0] if a.option_strings else a.dest: a for a in parser._actions}
    for name in INPUT_NAMES:
        if name in by_name:
            return by_name[name]
    raise AssertionError(f"no input among {sorted(by_name)}")


#: Commands that write files named by options, each with an input the outputs must not replace
#: (``worlds --export`` reads none).
OUTPUT_FILE_COMMANDS = sorted(
    command
    for command, parser in COMMANDS.items()
    if _output_file_options(parser)
    and any((a.option_strings or [a.dest])[0] in INPUT_NAMES for a in parser._actions)
)


def _input_copy(action: argparse.Action, files: dict[str, Path], folder: Path) -> Path:
    """A fresh copy of a valid input for ``action`` in ``folder``."""
    source = {"run_file": files["run"], "file": WBT}.get(
        action.dest, REPO / "worlds" / "arena.toml"
    )
    copy = folder / f"input{''.join(source.suffixes)}"
    copy.write_bytes(source.read_bytes())
    return copy


def test_output_file_commands_are_found() -> None:
    assert {"demo", "eval", "webots run", "ros demo", "show", "replay"} <= set(OUTPUT_FILE_COMMANDS)


#: The suffix an output file option takes (a figure is a PNG, a video a GIF or an MP4...).
SUFFIXES = {"--video": ".gif", "--html": ".html", "--plot": ".png"}


@pytest.mark.parametrize(
    "command",
    [
        pytest.param(command, marks=needs_ros) if command.startswith("ros ") else command
        for command in OUTPUT_FILE_COMMANDS
    ],
)
def test_no_output_option_writes_over_an_input_or_another_output(
    command: str, files: dict[str, Path], tmp_path: Path
) -> None:
    """Each output file option given the command's input (under any name: a hard link with the
    suffix the option needs), or two output options given one path: refused in one line, exit 2,
    the input unchanged and nothing written."""
    parser = COMMANDS[command]
    source = _input_of(parser)
    outputs = _output_file_options(parser)
    runs: list[tuple[list[str], Path]] = []
    inputs: list[tuple[Path, bytes]] = []
    for number, option in enumerate(outputs):
        folder = tmp_path / f"run-{number}"
        folder.mkdir()
        original = _input_copy(source, files, folder)
        suffix = SUFFIXES.get(option.option_strings[-1])
        if command in ("show", "replay") or suffix is not None:
            suffix = suffix or (".html" if command == "replay" else ".png")
            alias = folder / f"same-input{suffix}"
            os.link(original, alias)
        else:
            alias = folder / ".." / folder.name / original.name
        arguments = _arguments(command, parser, (option, str(alias)), files, folder)
        if source.option_strings:
            arguments += [source.option_strings[0], str(original)]
        else:
            arguments[arguments.index(_positionals(command, files)[source.dest])] = str(original)
        runs.append((arguments, folder))
        inputs.append((original, original.read_bytes()))
    view = "view" + SUFFIXES.get(outputs[1].option_strings[-1] if len(outputs) > 1 else "", ".gif")
    if len(outputs) > 1:
        folder = tmp_path / "two-outputs"
        folder.mkdir()
        arguments = _arguments(command, parser, (outputs[1], f"./{view}"), files, folder)
        runs.append(([*arguments, outputs[0].option_strings[0], view], folder))
    endings = run_limited(runs, tmp_path)
    problems = [
        f"mazesim {' '.join(ending.arguments)}: {problem or 'ran'}"
        for ending in endings
        if (problem := _problem(ending))
        or ending.returncode != 2
        or "same file" not in ending.stderr
    ]
    assert not problems, "\n".join(problems)
    assert all(path.read_bytes() == data for path, data in inputs)
    assert not (tmp_path / "two-outputs" / view).exists()


@pytest.mark.parametrize("name", ["\u00fc.png", os.fsdecode(b"\xff.png")])
def test_an_output_name_the_terminal_cannot_show_is_printed_escaped(
    tmp_path: Path, name: str
) -> None:
    # A terminal of a strict ASCII encoding (or a non-UTF-8 byte in the name): the command
    # used to write its file, then fail with "internal error" printing the name.
    target = tmp_path / name
    result = subprocess.run(
        [sys.executable, "-m", "mazesim", "show", "seed-maze", "-o", os.fsencode(target)],
        capture_output=True,
        env={**os.environ, "PYTHONIOENCODING": "ascii:strict"},
        timeout=TIME_LIMIT_S,
        check=False,
    )
    assert result.returncode == 0, result.stderr
    assert target.exists()
    printed = result.stdout.decode("ascii")
    assert "wrote" in printed and ("\\x" in printed or "\\udc" in printed)


def _input_options(parser: argparse.ArgumentParser) -> list[argparse.Action]:
    return [action for action in _value_options(parser) if _kind(action) == "input"]


#: Commands with inputs (files or folders they read), ROS's aside (they need ROS 1).
INPUT_COMMANDS = sorted(
    command
    for command, parser in COMMANDS.items()
    if _input_options(parser) and not command.startswith("ros ")
)


def test_input_commands_are_found() -> None:
    assert {"show", "import-wbt", "replay", "sweep", "webots run"} <= set(INPUT_COMMANDS)


def _main_within(arguments: list[str], folder: Path, seconds: float) -> int | None:
    """``mazesim ARGUMENTS`` run in this process from ``folder``: its exit code, or None when it
    has not ended after ``seconds`` (it then stays blocked in a thread of its own)."""
    ended: list[int] = []

    def run() -> None:
        ended.append(main(arguments))

    saved = os.getcwd()
    os.chdir(folder)
    try:
        worker = threading.Thread(target=run, daemon=True)
        worker.start()
        worker.join(seconds)
    finally:
        os.chdir(saved)
    return ended[0] if ended else None


def test_a_fifo_without_a_writer_as_any_input_is_refused_at_once(
    files: dict[str, Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Each input of each command given a FIFO no process writes to: refused in one line, exit
    2, at once, instead of waiting for ever (6 of 9 commands hung, ``import-wbt`` deaf to
    Ctrl-C)."""
    problems = []
    for command in INPUT_COMMANDS:
        parser = COMMANDS[command]
        for number, action in enumerate(_input_options(parser)):
            folder = tmp_path / f"{command.replace(' ', '-')}-{number}"
            folder.mkdir()
            arguments = _arguments(command, parser, (action, "fifo"), files, folder)
            if command == "replay":
                arguments += ["-o", str(folder / "page.html")]
            code = _main_within(arguments, folder, 30.0)
            error = capsys.readouterr().err.strip()
            if code != 2 or not error.splitlines()[-1].startswith("mazesim: error: "):
                problems.append(f"mazesim {' '.join(arguments)}: exit {code}: {error[-500:]}")
    assert not problems, "\n".join(problems)


def test_special_outputs_are_written_into_never_replaced(
    tmp_path: Path, capfdbinary: pytest.CaptureFixture[bytes]
) -> None:
    """``show -o`` at a device node, a link to ``/dev/null`` and ``/dev/stdout``: written into
    (as root, ``-o /dev/null`` used to replace the system's /dev/null with a PNG)."""
    link = tmp_path / "null.png"
    link.symlink_to(os.devnull)
    targets = [str(link), "/dev/stdout"]
    if os.geteuid() == 0:
        node = tmp_path / "device.png"
        os.mknod(node, stat.S_IFCHR | 0o666, os.makedev(1, 3))  # a null device of its own
        targets.append(str(node))
    for target in targets:
        assert _main_within(["show", "arena", "-o", target], tmp_path, 60.0) == 0
        written = capfdbinary.readouterr().out
        if target == "/dev/stdout":
            assert written.startswith(b"\x89PNG"), written[:40]
    assert link.is_symlink() and stat.S_ISCHR(os.stat(os.devnull).st_mode)
    if os.geteuid() == 0:
        assert stat.S_ISCHR((tmp_path / "device.png").lstat().st_mode)
    assert sorted(os.listdir(tmp_path)) == sorted(
        ["null.png"] + (["device.png"] if os.geteuid() == 0 else [])
    )
    fifo = tmp_path / "picture.fifo"
    os.mkfifo(fifo)
    assert _main_within(["show", "arena", "-o", str(fifo)], tmp_path, 60.0) == 2
    assert b"FIFO that no process reads" in capfdbinary.readouterr().err
    assert stat.S_ISFIFO(fifo.lstat().st_mode)


def _options_of_kind(parser: argparse.ArgumentParser, kind: str) -> list[argparse.Action]:
    return [a for a in _value_options(parser) if a.option_strings and _kind(a) == kind]


#: Commands with an output folder option (``--out DIR``), ROS's aside (they need ROS).
OUTPUT_FOLDER_COMMANDS = sorted(
    command
    for command, parser in COMMANDS.items()
    if _options_of_kind(parser, "output") and command.split()[0] not in ("ros", "ros2")
)


def test_output_folder_commands_are_found() -> None:
    assert {"demo", "train", "webots run", "barcode-study"} <= set(OUTPUT_FOLDER_COMMANDS)


def test_an_output_folder_that_is_a_device_is_refused_saying_what_it_is(
    files: dict[str, Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """``--out /dev/full`` (a character device) to every command that writes a folder: exit 2
    and one line saying an output folder was expected and a character device found (``demo``
    and ``webots run`` said "/dev/full: File exists")."""
    problems = []
    for command in OUTPUT_FOLDER_COMMANDS:
        parser = COMMANDS[command]
        for action in _options_of_kind(parser, "output"):
            arguments = _arguments(command, parser, (action, "/dev/full"), files, tmp_path)
            code = _main_within(arguments, tmp_path, 60.0)
            error = capsys.readouterr().err.strip()
            expected = "/dev/full: expected an output folder, found a character device"
            if code != 2 or expected not in error.splitlines()[-1]:
                problems.append(f"mazesim {' '.join(arguments)}: exit {code}: {error[-500:]}")
    assert not problems, "\n".join(problems)


#: A name option's value of bytes the terminal's encoding cannot decode (Python keeps them as
#: lone surrogates).
NOT_UNICODE_NAME = os.fsdecode(b"\xff\xfe")


def test_a_name_that_is_not_unicode_text_is_refused_in_one_line(
    files: dict[str, Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Each name option (``--robot``, ``--address``...) of each command given undecodable bytes:
    refused in one line with exit 2 (or unused, ``sweep --sequential --address``), never an
    internal error (``demo --robot`` ended in "internal error ... UnicodeEncodeError")."""
    problems = []
    for command, parser in sorted(COMMANDS.items()):
        if command.startswith("ros"):
            continue
        for action in _options_of_kind(parser, "name"):
            arguments = _arguments(command, parser, (action, NOT_UNICODE_NAME), files, tmp_path)
            code = _main_within(arguments, tmp_path, 60.0)
            error = capsys.readouterr().err.strip()
            last = error.splitlines()[-1] if error else ""
            refused = code == 2 and last.startswith("mazesim")
            if not (refused or code == 0) or "internal error" in error:
                problems.append(f"mazesim {' '.join(arguments)}: exit {code}: {error[-500:]}")
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize(
    "argv",
    [
        ["show", "seed\x00maze"],
        ["eval", "--world", "seed\x00maze", "--episodes", "1"],
        ["import-wbt", "x\x00.wbt"],
    ],
)
def test_a_nul_character_in_any_argument_is_one_clear_line(
    argv: list[str], capsys: pytest.CaptureFixture[str]
) -> None:
    """No shell passes a NUL; from Python it reached a path as "embedded null byte", an
    internal error. The command line refuses it once, for every command."""
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "NUL character" in err
    assert "internal error" not in err
    assert len(err.strip().splitlines()) == 1


def test_a_standard_output_that_cannot_be_written_is_named_in_the_error() -> None:
    """``mazesim worlds > /dev/full``: exit 2 and one line naming the standard output (the
    system names no file for it, and the line read ": No space left on device")."""
    with open("/dev/full", "w") as full:
        done = subprocess.run(
            [sys.executable, "-m", "mazesim", "worlds"],
            stdout=full,
            stderr=subprocess.PIPE,
            text=True,
            timeout=120,
        )
    assert done.returncode == 2, done.stderr
    assert done.stderr.strip() == "mazesim: error: the standard output: No space left on device"


def test_an_io_error_that_names_no_file_is_its_reason_alone() -> None:
    from mazesim._error_tree import io_error

    assert str(io_error(OSError(28, "No space left on device"))) == "No space left on device"
    assert str(io_error(OSError(28, "No space left on device"), "w.toml")).startswith("w.toml: ")
