"""The figures a Markdown page shows that a run produced, and whether each is accounted for.

A run figure is a number with a unit a run measures: a time (``µs``, ``ms``, ``s``, ``min``,
``h``), a share (``%``), a size in decimal units (``kB``, ``MB``, ``GB``, ``bytes``), a rate
(``steps/s``, ``env-steps/s``, ``M/s``) or a ratio (``3.7x``). Limits are written in binary
units (``64 MiB``) and are no run figures. Inline code, link addresses and HTML comments are not
read.

A page is read in units: a paragraph, a list item, a heading, a table (with the paragraph right
before it, its caption) and a ``text`` or ``console`` block (with the paragraph right before it;
a console block's ``$`` lines are commands, not read). Other code blocks run in the tests, and a
``text`` block marked ``<!-- output -->`` is compared with what its run printed; neither is read.

A figure is accounted for when its unit

- carries a measurement mark: a date (``2026-11-29``) and the machine (``2-core``, ``machine``,
  ``EPYC``), as in "(measured 2026-11-29, 2-core machine)";
- or is checked by a test: the line right above the unit (for a table: above it or above its
  caption) is ``<!-- checked: tests/PATH.py -->``, naming the test files (comma-separated) that
  compare the unit's figures with a run; each must exist and name the page;
- or the figure is a constant of :data:`CONSTANTS` or of the page's :data:`PAGE_CONSTANTS`.

A page a run writes whole (:data:`GENERATED_PAGES`) is accounted for by the date at its top.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

_NUMBER = r"\d(?:[\d,]*\d)?(?:\.\d+)?"
_UNIT = r"(?:µs|ms|s|min|h|%|kB|MB|GB|bytes|(?:env-|robot-|control )?steps/s|M/s)"
#: A run figure: a number or a range or list of numbers ("16-18 s", "93 / 83 / 94 %", "2 to 5
#: minutes" is words), then a unit; or a ratio ("3.7x").
RUN_FIGURE = re.compile(
    rf"(?<![\w.]){_NUMBER}(?:\s?(?:-|to|/)\s?{_NUMBER})*\s?{_UNIT}(?![\w/])"
    rf"|(?<![\w.]){_NUMBER}x(?![\w])"
)
_DATE = re.compile(r"\b20\d\d-\d\d-\d\d\b")
_MACHINE = re.compile(r"\d-core\b|\bmachine\b|\bEPYC\b", re.IGNORECASE)
_CHECKED = re.compile(r"^\s*<!--\s*checked:\s*(?P<tests>[^>]+?)\s*-->\s*$")
_OUTPUT = re.compile(r"^\s*<!--\s*output\s*-->\s*$")
_FENCE = re.compile(r"^(?P<indent>[ \t]*)(?P<fence>`{3,}|~{3,})[ \t]*(?P<info>[^`]*)$")
_COMMENT = re.compile(r"<!--.*?-->", re.DOTALL)
_CODE_SPAN = re.compile(r"`[^`]*`")
_LINK_ADDRESS = re.compile(r"\]\([^)]*\)")
_LIST_ITEM = re.compile(r"^\s*(?:[-*+]|\d+\.)\s")

#: Figures that are constants, not measurements: (pattern, why). Each pattern matches the whole
#: figure as :data:`RUN_FIGURE` finds it.
CONSTANTS: tuple[tuple[str, str], ...] = (
    (r"(?:32|64) ms", "the basic and control time steps of worlds and of the navigator"),
    (r"(?:60|256) s", "mazesim demo's time limits: 60 s, and 4,000 steps of 64 ms with hrl"),
    (r"0\.25x|16x", "the replay's slowest and fastest playback speeds"),
)
#: Constants of one page only: page name -> {figure: why}.
PAGE_CONSTANTS: dict[str, dict[str, str]] = {
    "README.md": {"0.1-1,000 ms": "the limits of a world's time steps"},
    "cli.md": {
        "42%": "an illustration of the progress bar's form",
        "716.42steps/s": "an illustration of the progress bar's form",
        "24%": "an illustration of the progress lines' form",
        "100%": "an illustration of the progress lines' form",
        "30 s": "the progress lines' interval",
    },
    "design.md": {"30 s": "the documentation blocks' time budget, a rule"},
    "multi-robot.md": {
        "128 ms": "the multi-robot tasks' control step",
        "38 s": "the multi-robot tasks' time limit, 300 steps of 128 ms",
    },
    "perturbations.md": {"5 %": "an example of a scale (1.05), not a result"},
    "transfer.md": {
        "5 %": "a level of the motor-mismatch axis",
        "10 %": "a level of the motor-mismatch axis",
        "50 %": "the motor-mismatch axis' documented range",
    },
    "rl.md": {"128 ms": "the goal-conditioned tasks' control step"},
    "ray.md": {
        "2.5x": "Ray's version (2.5 and later)",
        "20 s": "how long Ray retries without its token (Ray's behaviour)",
        "5 s": "how long a cluster's address is given to answer, a rule (ANSWER_SECONDS)",
    },
    "reliability.md": {
        "0.1 to 1000 ms": "the limits of a world's time steps",
        "67108864 bytes": "the input files' limit, 64 MiB",
        "50 ms": "how often a long call checks for Ctrl-C",
        "2 s": "the fuzzer's watchdog",
        "1.5 %": "arithmetic: one step's travel against the largest coordinate's resolution",
    },
    "robots.md": {"0.7-12.6 %": "the e-puck2 PROTO's noise column (Webots' source)"},
    "ros.md": {
        "5 s": "the lockstep bridge's wait before it sends the reset state again",
        "1 s": "the lockstep bridge's wait after that before its clock runs on its own",
        "0.5 s": "the simulated sleep of the test of a controller that sleeps before commanding",
        "0.8 s": "the eighth tick of a 0.1 s rospy.Rate, where --command-period's hold is 4 steps",
        "2 s": "the lockstep bridge's wait before it holds a command on over a tick let go",
        "600 s": "the bridges' default idle timeout (mazesim.ros.lockstep.IDLE_TIMEOUT_S)",
        "3 s": "how long the idle test's node holds cmd_vel open, sending nothing",
    },
    "ros2.md": {
        "600 s": "the bridges' default idle timeout (mazesim.ros.lockstep.IDLE_TIMEOUT_S)",
        "0.3 %": "the noise column of the E-puck PROTO's gyro and accelerometer tables",
        "0.5 s": "the bridge's wait for its readers to match",
        "5 s": "the lockstep bridge's wait before it sends the reset state again",
        "1 s": "the lockstep bridge's wait after that before its clock runs on its own",
        "6.4 s": "the argument of the page's run_until example",
        "0.1 s": "the period of the tests' and stand-ins' nodes on a timer of simulated time",
        "0.25 s": "the lockstep bridge's wait between the first state's motion and its sensors",
        "2 s": "the lockstep bridge's wait before it holds a command on over a tick let go",
    },
    "webots.md": {
        "1 %": "the LightSensor PROTO table's noise (Webots' source)",
        "0.3 %": "the Accelerometer and Gyro PROTO tables' noise (Webots' source)",
        "80 %": "the reflection factor of Webots' wall for infra-red rays",
    },
}
#: Pages a run writes whole, dated at their top: page name -> the run.
GENERATED_PAGES: dict[str, str] = {
    "webots-compat.md": "make webots-compat (tests/webots_corpus/run_corpus.py) writes it",
}


@dataclass(frozen=True)
class Unit:
    """A paragraph, list item, heading, table or text block of a page.

    Attributes:
        line: The 1-based line of its first line.
        lines: Its lines, as on the page.
        context: Its text with its caption, where marks are looked for.
        checked_by: The test files a ``checked`` marker names (empty when none).
    """

    line: int
    lines: tuple[str, ...]
    context: str
    checked_by: tuple[str, ...]


@dataclass(frozen=True)
class Figure:
    """A run figure a page shows that nothing accounts for."""

    page: str
    line: int
    figure: str
    text: str

    def __str__(self) -> str:
        return f"{self.page}:{self.line}: {self.figure!r} in: {self.text.strip()[:120]}"


def _checked_by(lines: list[str], index: int) -> tuple[str, ...]:
    """The test files a ``checked`` marker on the line above ``index`` names."""
    if index > 0:
        marker = _CHECKED.match(lines[index - 1])
        if marker:
            return tuple(name.strip() for name in marker["tests"].split(","))
    return ()


def _paragraphs(lines: list[str]) -> list[tuple[int, int]]:
    """(first, end) line indices of the blank-line separated runs of lines outside code fences,
    and of each code block as a run of its own (its fence lines included)."""
    runs: list[tuple[int, int]] = []
    index, start = 0, None
    while index < len(lines):
        opening = _FENCE.match(lines[index])
        if opening:
            if start is not None:
                runs.append((start, index))
                start = None
            fence = opening["fence"]
            end = index + 1
            while end < len(lines):
                closing = _FENCE.match(lines[end])
                if closing and closing["fence"][0] == fence[0] and not closing["info"].strip():
                    break
                end += 1
            runs.append((index, min(end + 1, len(lines))))
            index = end + 1
            continue
        if lines[index].strip() and not _COMMENT.fullmatch(lines[index].strip()):
            start = index if start is None else start
        elif start is not None:
            runs.append((start, index))
            start = None
        index += 1
    if start is not None:
        runs.append((start, len(lines)))
    return runs


def units(text: str) -> list[Unit]:
    """The units of a page's text whose figures are read (see the module)."""
    lines = text.splitlines()
    found: list[Unit] = []
    previous: tuple[int, int] | None = None
    for first, end in _paragraphs(lines):
        block = lines[first:end]
        caption = "\n".join(lines[previous[0] : previous[1]]) if previous else ""
        caption_checked = _checked_by(lines, previous[0]) if previous else ()
        opening = _FENCE.match(block[0])
        if opening:
            info = opening["info"].strip().split()
            language = info[0].lower() if info else ""
            output = first > 0 and _OUTPUT.match(lines[first - 1])
            if language in ("text", "console") and not output:
                body = [
                    "" if language == "console" and line.lstrip().startswith("$ ") else line
                    for line in block[1:-1]
                ]
                found.append(
                    Unit(
                        first + 2,
                        tuple(body),
                        caption + "\n" + "\n".join(body),
                        _checked_by(lines, first),
                    )
                )
            previous = None
            continue
        if all(line.lstrip().startswith("|") for line in block):
            found.append(
                Unit(
                    first + 1,
                    tuple(block),
                    caption + "\n" + "\n".join(block),
                    _checked_by(lines, first) or caption_checked,
                )
            )
            previous = (first, end)
            continue
        items = [
            i for i, line in enumerate(block) if _LIST_ITEM.match(line) or line.startswith("#")
        ]
        starts = sorted({0, *items})
        for k, item_start in enumerate(starts):
            item_end = starts[k + 1] if k + 1 < len(starts) else len(block)
            item = block[item_start:item_end]
            found.append(
                Unit(
                    first + item_start + 1,
                    tuple(item),
                    "\n".join(item),
                    _checked_by(lines, first + item_start),
                )
            )
        previous = (first, end)
    return found


def is_marked(context: str) -> bool:
    """Whether a unit's text carries a measurement mark: a date and the machine."""
    plain = _COMMENT.sub("", context)
    return bool(_DATE.search(plain) and _MACHINE.search(plain))


def is_constant(page: str, figure: str) -> bool:
    """Whether ``figure`` is a constant of :data:`CONSTANTS` or of the page's own list."""
    if figure in PAGE_CONSTANTS.get(page, {}):
        return True
    return any(re.fullmatch(pattern, figure) for pattern, _ in CONSTANTS)


def figures_of(line: str) -> list[str]:
    """The run figures of one line of prose (inline code, link addresses, comments left out)."""
    plain = _LINK_ADDRESS.sub("]", _CODE_SPAN.sub("", _COMMENT.sub("", line)))
    return [match.group(0) for match in RUN_FIGURE.finditer(plain)]


def unaccounted_figures(page: Path, root: Path) -> tuple[list[Figure], list[str]]:
    """The run figures of ``page`` that nothing accounts for, and what is wrong with its
    ``checked`` markers (a test file that does not exist or does not name the page)."""
    text = page.read_text(encoding="utf-8")
    figures: list[Figure] = []
    problems: list[str] = []
    if page.name in GENERATED_PAGES:
        if not re.search(r"^Measured on 20\d\d-\d\d-\d\d\b", text, re.MULTILINE):
            problems.append(f"{page.name}: a page a run writes must say when it was measured")
        return figures, problems
    for unit in units(text):
        for test in unit.checked_by:
            path = root / test
            if not path.is_file():
                problems.append(f"{page.name}:{unit.line}: checked by {test}, which does not exist")
            elif page.name not in path.read_text(encoding="utf-8"):
                problems.append(f"{page.name}:{unit.line}: {test} does not name {page.name}")
        if unit.checked_by or is_marked(unit.context):
            continue
        for offset, line in enumerate(unit.lines):
            for figure in figures_of(line):
                if not is_constant(page.name, figure):
                    figures.append(Figure(page.name, unit.line + offset, figure, line))
    return figures, problems
