"""The fenced code blocks of the Markdown pages, as the documentation tests run them.

A block is a fenced code block (```` ``` ```` or ``~~~``, possibly indented inside a list) with
its language. The line directly above its opening fence may carry a marker:

- ``<!-- no-test: REASON -->``: the block is not run; the tests show it as skipped with REASON.
- ``<!-- world -->``: a ``toml`` block that is a whole world file, loaded with
  ``mazesim.World.from_toml`` (other ``toml`` blocks are only parsed).
- ``<!-- output -->``: a ``text`` block that shows what the page's previous runnable block
  prints: each of its lines, but those that are ``...``, must be a line of that output (spaces
  between words do not count).

In a ``console`` block only the lines that start with the prompt ``$ `` are commands; the other
lines are their output.

A line ``--8<-- "PATH"`` inside a block (the mkdocs snippet syntax) stands for the text of the
file PATH, relative to the repository's root.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

#: The languages whose blocks run: Python, shell, and TOML (parsed or loaded as a world).
PYTHON_LANGUAGES = frozenset({"python", "py"})
SHELL_LANGUAGES = frozenset({"bash", "sh", "console", "shell"})
TOML_LANGUAGES = frozenset({"toml"})

_FENCE = re.compile(r"^(?P<indent>[ \t]*)(?P<fence>`{3,}|~{3,})[ \t]*(?P<info>[^`]*)$")
_NO_TEST = re.compile(r"^\s*<!--\s*no-test:\s*(?P<reason>.+?)\s*-->\s*$")
_WORLD = re.compile(r"^\s*<!--\s*world\s*-->\s*$")
_OUTPUT = re.compile(r"^\s*<!--\s*output\s*-->\s*$")
_SNIPPET = re.compile(r"^\s*--8<--\s+\"(?P<path>[^\"]+)\"\s*$")


def example_environment() -> dict[str, str]:
    """The environment of a docs block or an example.

    This interpreter's folder comes first on ``PATH`` (so ``mazesim`` and ``python`` are this
    installation's); ``MAZESIM_EXAMPLES_FAST=1`` asks the examples for their fast mode, and
    matplotlib draws without a display.
    """
    bin_dir = str(Path(sys.executable).parent)
    return {
        **os.environ,
        "PATH": f"{bin_dir}{os.pathsep}{os.environ.get('PATH', '')}",
        "MAZESIM_EXAMPLES_FAST": "1",
        "MPLBACKEND": "Agg",
    }


def run_command(argv: list[str], cwd: Path, timeout_s: float) -> subprocess.CompletedProcess[str]:
    """Runs a command in ``cwd`` in :func:`example_environment`; returns the finished process.

    Args:
        argv: The command and its arguments.
        cwd: The working folder.
        timeout_s: A guard against a command that hangs (not a speed requirement).
    """
    return subprocess.run(
        argv,
        cwd=cwd,
        env=example_environment(),
        capture_output=True,
        text=True,
        timeout=timeout_s,
        check=False,
    )


@dataclass(frozen=True)
class Block:
    """One fenced code block of a page.

    Attributes:
        page: The page's path.
        line: The 1-based line of the opening fence.
        language: The fence's language, lower case ("" when none is given).
        text: The block's text, its indentation removed and snippets expanded.
        skip_reason: The reason of a ``no-test`` marker, or ``None``.
        is_world: Whether a ``world`` marker says the block is a whole world file.
        is_output: Whether an ``output`` marker says the block shows the previous block's output.
    """

    page: Path
    line: int
    language: str
    text: str
    skip_reason: str | None
    is_world: bool
    is_output: bool = False

    @property
    def where(self) -> str:
        """``page:line`` of the opening fence."""
        return f"{self.page.name}:{self.line}"


def console_commands(text: str) -> str:
    """The commands of a ``console`` block: its ``$ `` lines without the prompt."""
    commands = [line[2:] for line in text.splitlines() if line.startswith("$ ")]
    return "\n".join(commands) + "\n"


def expand_snippets(text: str, root: Path) -> str:
    """Replaces each ``--8<-- "PATH"`` line by the text of ``root / PATH``."""
    lines = []
    for line in text.splitlines():
        match = _SNIPPET.match(line)
        if match:
            lines.append((root / match["path"]).read_text(encoding="utf-8").rstrip("\n"))
        else:
            lines.append(line)
    return "\n".join(lines) + ("\n" if text.endswith("\n") else "")


def parse_blocks(page: Path, text: str, root: Path) -> list[Block]:
    """The fenced code blocks of a page's text, in order.

    Args:
        page: The page's path (for messages).
        text: The page's Markdown text.
        root: The folder snippet paths are relative to.

    Returns:
        The blocks, each with its marker read from the line directly above its fence.

    Raises:
        ValueError: A fence is never closed.
    """
    lines = text.splitlines()
    blocks = []
    index = 0
    while index < len(lines):
        opening = _FENCE.match(lines[index])
        if not opening:
            index += 1
            continue
        indent, fence = opening["indent"], opening["fence"]
        info = opening["info"].strip().split()
        language = info[0].lower().lstrip("{.").rstrip("}") if info else ""
        previous = lines[index - 1] if index > 0 else ""
        no_test = _NO_TEST.match(previous)
        body = []
        end = index + 1
        while end < len(lines):
            closing = _FENCE.match(lines[end])
            if (
                closing
                and closing["fence"][0] == fence[0]
                and len(closing["fence"]) >= len(fence)
                and not closing["info"].strip()
            ):
                break
            body.append(lines[end][len(indent) :] if lines[end].startswith(indent) else lines[end])
            end += 1
        else:
            raise ValueError(f"{page.name}:{index + 1}: a code fence {fence!r} is never closed")
        blocks.append(
            Block(
                page=page,
                line=index + 1,
                language=language,
                text=expand_snippets("\n".join(body) + "\n", root),
                skip_reason=no_test["reason"] if no_test else None,
                is_world=bool(_WORLD.match(previous)),
                is_output=bool(_OUTPUT.match(previous)),
            )
        )
        index = end + 1
    return blocks


def missing_output_lines(shown: str, printed: str) -> list[str]:
    """The lines of an ``output`` block that are not lines of what was printed (``...`` lines
    stand for any lines; runs of spaces count as one)."""
    printed_lines = {" ".join(line.split()) for line in printed.splitlines()}
    return [
        line
        for line in shown.splitlines()
        if line.strip() not in ("", "...") and " ".join(line.split()) not in printed_lines
    ]


#: A guard against a site build that hangs, not a speed requirement.
SITE_BUILD_TIMEOUT_S = 600


def build_site(
    root: Path, site: Path, hidden: tuple[str, ...] = ()
) -> subprocess.CompletedProcess[str]:
    """Builds the documentation site of ``root`` into ``site`` as ``make docs`` does (``mkdocs
    build --strict``), in a fresh interpreter to which the top-level packages ``hidden`` look
    absent (as if not installed)."""
    script = (
        "import sys\n"
        "class Absent:\n"
        "    def find_spec(self, name, path=None, target=None):\n"
        f"        if name.split('.')[0] in {tuple(hidden)!r}:\n"
        "            raise ModuleNotFoundError(f'No module named {name!r}', name=name)\n"
        "sys.meta_path.insert(0, Absent())\n"
        "from mkdocs.__main__ import cli\n"
        "cli(['build', '--strict', '--quiet', '--site-dir', sys.argv[1]])\n"
    )
    return subprocess.run(
        [sys.executable, "-c", script, str(site)],
        cwd=root,
        env={**os.environ, "NO_MKDOCS_2_WARNING": "1"},
        capture_output=True,
        text=True,
        timeout=SITE_BUILD_TIMEOUT_S,
        check=False,
    )
