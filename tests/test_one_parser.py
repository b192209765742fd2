"""One command-line parser class: every parser the package makes is a ``BoundedParser``.

A fuzzed call found ``python -m mazesim.replay.screenshot`` printing a word of 200,000 characters
back whole: it was the one parser not made by the commands' class. Every parser is now made from
:class:`mazesim._arguments.BoundedParser` (or the commands' subclass of it); this test refuses a
plain ``argparse.ArgumentParser`` made or subclassed anywhere else, so the next entry point is
bounded by construction.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import mazesim
from mazesim._arguments import BoundedParser
from mazesim.cli._help import CommandParser

ROOT = Path(mazesim.__file__).parent
#: The one file that may subclass argparse's parser itself.
HOME = Path("_arguments.py")


def _is_argparse_parser(node: ast.expr) -> bool:
    """Whether an expression names argparse's own parser (``argparse.ArgumentParser`` or the
    name imported from argparse)."""
    if isinstance(node, ast.Attribute):
        return node.attr == "ArgumentParser"
    return isinstance(node, ast.Name) and node.id == "ArgumentParser"


def plain_parsers(path: Path, root: Path = ROOT) -> list[str]:
    """Where a file makes or subclasses argparse's parser directly."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and _is_argparse_parser(node.func):
            found.append(f"{path.relative_to(root)}:{node.lineno} makes an ArgumentParser")
        elif isinstance(node, ast.ClassDef):
            if any(_is_argparse_parser(base) for base in node.bases):
                found.append(f"{path.relative_to(root)}:{node.lineno} subclasses ArgumentParser")
    return found


def test_no_module_but_the_home_makes_or_subclasses_argparses_parser() -> None:
    found = [
        place
        for path in sorted(ROOT.rglob("*.py"))
        if path.relative_to(ROOT) != HOME
        for place in plain_parsers(path)
    ]
    assert found == []


@pytest.mark.parametrize(
    ("source", "expected"),
    [
        ("import argparse\nparser = argparse.ArgumentParser(prog='x')\n", 1),
        ("from argparse import ArgumentParser\nclass P(ArgumentParser):\n    pass\n", 1),
        ("from mazesim._arguments import BoundedParser\nparser = BoundedParser(prog='x')\n", 0),
    ],
)
def test_the_check_sees_a_plain_parser_made_or_subclassed(
    tmp_path: Path, source: str, expected: int
) -> None:
    probe = tmp_path / "probe.py"
    probe.write_text(source, encoding="utf-8")
    assert len(plain_parsers(probe, tmp_path)) == expected


def test_the_commands_parser_and_the_screenshot_parser_are_bounded() -> None:
    from mazesim.cli import build_parser

    assert issubclass(CommandParser, BoundedParser)
    parser = build_parser()
    assert isinstance(parser, BoundedParser)
    assert parser.allow_abbrev is False


def test_a_bounded_parser_takes_options_by_their_whole_name_and_bounds_its_error(
    capsys: pytest.CaptureFixture[str],
) -> None:
    parser = BoundedParser(prog="probe")
    parser.add_argument("--step", type=int)
    with pytest.raises(SystemExit) as stopped:
        parser.parse_args(["--st", "3"])
    assert stopped.value.code == 2
    assert "unrecognized arguments: --st" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        parser.parse_args(["x" * 200_000])
    assert len(capsys.readouterr().err) < 5_000
