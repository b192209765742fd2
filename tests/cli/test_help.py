"""``mazesim --help`` and each command's help: summaries, defaults, examples that parse, and a
parser that imports only the command it runs."""

from __future__ import annotations

import argparse
import json
import shlex
import subprocess
import sys
from collections.abc import Iterator

import pytest

from mazesim.cli import COMMANDS, build_parser
from mazesim.cli._args import output_path, seed_argument
from mazesim.cli._help import HelpFormatter, examples

#: Commands whose parsers read their defaults from the learning modules (not yet import-light).
LEARNING_PARSERS = {"sweep", "train", "eval"}
#: Modules no parser may import: plotting, learning, Ray, images, ROS.
HEAVY = ("matplotlib", "PIL", "ray", "rospy", "imageio", "mazesim.hrl", "mazesim.distributed")


def _leaf_commands(
    parser: argparse.ArgumentParser, words: tuple[str, ...] = ()
) -> Iterator[tuple[str, argparse.ArgumentParser]]:
    subparsers = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    if not subparsers:
        yield " ".join(words), parser
    for action in subparsers:
        for name, sub in action.choices.items():
            yield from _leaf_commands(sub, (*words, name))


LEAVES = dict(_leaf_commands(build_parser()))


def _imported_by(code: str) -> list[str]:
    """The modules a fresh interpreter has imported after ``code``."""
    script = f"import sys, json\n{code}\nprint(json.dumps(sorted(sys.modules)))\n"
    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=True
    )
    modules: list[str] = json.loads(done.stdout.splitlines()[-1])
    return modules


def test_the_summaries_of_mazesim_help_are_the_commands_own() -> None:
    (commands,) = [a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction)]
    registered = [(choice.dest, choice.help) for choice in commands._choices_actions]
    assert registered == [(name, summary) for name, (_, summary) in COMMANDS.items()]


def test_mazesim_help_imports_no_command_module() -> None:
    code = "from mazesim.cli import main\nassert main(['--help']) == 0"
    modules = _imported_by(code)
    commands = {module for module, _ in COMMANDS.values()}
    assert commands.isdisjoint(modules)
    assert [m for m in modules if m.startswith(HEAVY)] == []


@pytest.mark.parametrize("command", sorted(set(COMMANDS) - LEARNING_PARSERS))
def test_a_command_imports_its_own_module_only(command: str) -> None:
    modules = _imported_by(f"from mazesim.cli import build_parser\nbuild_parser({command!r})")
    others = {module for module, _ in COMMANDS.values()} - {COMMANDS[command][0]}
    assert others.isdisjoint(modules)
    assert [m for m in modules if m.startswith(HEAVY)] == []


@pytest.mark.parametrize("command", sorted(LEAVES))
def test_every_default_is_shown(command: str) -> None:
    unshown = [
        action.option_strings
        for action in LEAVES[command]._actions
        if action.option_strings
        and action.default not in (None, False, argparse.SUPPRESS)
        and "default" not in (action.help or "")
    ]
    assert unshown == []


@pytest.mark.parametrize("command", sorted(LEAVES))
def test_an_output_folder_is_said_to_be_made_and_a_seed_is_checked(command: str) -> None:
    for action in LEAVES[command]._actions:
        if "--out" in action.option_strings and action.metavar == "DIR":
            assert action.type is output_path
            assert ", created if missing (default: %(default)s)" in (action.help or "")
        if "--seed" in action.option_strings:
            assert action.type is seed_argument


@pytest.mark.parametrize("command", sorted(LEAVES))
def test_the_examples_of_a_command_parse(command: str) -> None:
    parser = LEAVES[command]
    help_text = parser.format_help()
    assert "\nexamples:\n" in help_text
    lines = help_text.split("\nexamples:\n", 1)[1].splitlines()
    assert lines and all(line.startswith(f"  mazesim {command}") for line in lines), lines
    for line in lines:
        args = build_parser().parse_args(shlex.split(line)[1:])
        assert args.command == command.split()[0]


def _every_command(
    parser: argparse.ArgumentParser, words: tuple[str, ...] = ()
) -> Iterator[tuple[str, argparse.ArgumentParser]]:
    """Every command and subcommand, groups included (``ros2`` and ``ros2 bridge``)."""
    if words:
        yield " ".join(words), parser
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                yield from _every_command(sub, (*words, name))


@pytest.mark.parametrize("command", sorted(dict(_every_command(build_parser()))))
def test_every_command_says_what_it_does_in_plain_words(command: str) -> None:
    parser = dict(_every_command(build_parser()))[command]
    # The paragraph under the usage lines: what the command does, before its options.
    description = parser.description or ""
    assert len(description.split()) >= 5, f"mazesim {command} --help has no description"
    assert "``" not in description and ":class:" not in description, description


def test_examples_keep_their_lines_and_wrap_the_notes() -> None:
    parser = argparse.ArgumentParser(
        prog="mazesim x",
        formatter_class=HelpFormatter,
        epilog=examples("mazesim x " + "--long-option " * 8, notes="word " * 40),
    )
    text = parser.format_help()
    notes, listed = text.split("\nexamples:\n")
    assert max(len(line) for line in notes.splitlines()) <= 80
    assert listed.splitlines() == ["  mazesim x " + "--long-option " * 8]


@pytest.mark.parametrize("option", ["--world", "--robot", "--controller", "--out"])
def test_the_ros_demos_describe_their_shared_options_alike(option: str) -> None:
    """``mazesim ros demo`` and ``mazesim ros2 demo`` take the world, the robot profile, the
    controller and the output folder the same way: the same choices, metavar and check, and but
    for the controller's the same help."""
    found = []
    for command in ("ros demo", "ros2 demo"):
        (action,) = [a for a in LEAVES[command]._actions if option in a.option_strings]
        help_text = None if option == "--controller" else action.help
        found.append((action.choices, action.metavar, action.type, help_text))
    assert found[0] == found[1]
