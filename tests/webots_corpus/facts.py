"""The facts a corpus project's run is checked against, and their measurement.

A fact is one line, ``kind [argument]``, written in the manifest as Webots shows the project:

- ``exit N``: the run's exit status is N (0: the run ended normally);
- ``no_error``: the controller raised no exception;
- ``leaves_start D``: the robot gets farther than D metres from its start;
- ``stays_near D``: the robot never gets farther than D metres from its start;
- ``travels D``: the robot's path is longer than D metres;
- ``clearance D``: the robot's body stays more than D metres from every wall (0: never touches);
- ``on_dark F``: at least a fraction F of the steps the floor under the robot is dark
  (reflectance below 0.5 within 1 cm of its centre): it follows a line;
- ``walls N``: the world imports with at least N wall obstacles;
- ``robots N``: at least N robots move (travel more than 5 cm, or are put more than 5 cm from
  their start by a supervisor);
- ``prints TEXT``: the controller prints TEXT (the rest of the line) on its standard output.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
import numpy.typing as npt

#: kind -> whether it takes a number (False: none, or free text for ``prints``).
KINDS: dict[str, bool] = {
    "exit": True,
    "no_error": False,
    "leaves_start": True,
    "stays_near": True,
    "travels": True,
    "clearance": True,
    "on_dark": True,
    "walls": True,
    "robots": True,
    "prints": False,
}
DARK = 0.5
MOVED = 0.05


@dataclass(frozen=True)
class Fact:
    """One parsed fact: its kind and its number or text."""

    kind: str
    number: float = 0.0
    text: str = ""


def parse_fact(line: str) -> Fact:
    """Parses ``kind [argument]``.

    Raises:
        ValueError: An unknown kind, or an argument missing or not a number.
    """
    kind, _, rest = line.strip().partition(" ")
    rest = rest.strip()
    if kind not in KINDS:
        raise ValueError(f"fact {line!r}: expected a kind among {sorted(KINDS)}, found {kind!r}")
    if kind == "prints":
        if not rest:
            raise ValueError(f"fact {line!r}: expected the text the controller prints")
        return Fact(kind, text=rest)
    if not KINDS[kind]:
        if rest:
            raise ValueError(f"fact {line!r}: {kind} takes no argument, found {rest!r}")
        return Fact(kind)
    try:
        number = float(rest)
    except ValueError:
        raise ValueError(f"fact {line!r}: expected a number after {kind}, found {rest!r}") from None
    if not math.isfinite(number) or number < 0:
        raise ValueError(f"fact {line!r}: expected a finite number >= 0, found {rest!r}")
    return Fact(kind, number=number)


@dataclass
class Outcome:
    """What one run left behind, as the facts read it.

    ``path`` is the robot's (N, 2) positions after each step, the first its start; ``walls`` the
    (M, 5) wall boxes (cx, cy, sx, sy, yaw) of the imported world; ``floor`` the floor's
    reflectance at a point; ``robots_moving`` how many robots moved more than 5 cm (None:
    count the one robot of ``path``).
    """

    exit_status: int | None
    error: str
    stdout: str
    path: npt.NDArray[np.float64]
    walls: npt.NDArray[np.float64]
    floor: Callable[[float, float], float]
    robot_radius: float = 0.037
    robots_moving: int | None = None
    wall_count: int = 0
    notes: list[str] = field(default_factory=list)


def path_length(path: npt.NDArray[np.float64]) -> float:
    """The length of a polyline of (N, 2) points."""
    if len(path) < 2:
        return 0.0
    return float(np.hypot(*np.diff(path, axis=0).T).sum())


def farthest_from_start(path: npt.NDArray[np.float64]) -> float:
    """The largest distance of a point from the first."""
    if len(path) == 0:
        return 0.0
    return float(np.hypot(*(path - path[0]).T).max())


def min_gap(path: npt.NDArray[np.float64], walls: npt.NDArray[np.float64], radius: float) -> float:
    """The smallest distance between a disc of ``radius`` along ``path`` and any wall box."""
    if len(path) == 0 or len(walls) == 0:
        return math.inf
    px = path[:, 0][:, None] - walls[:, 0][None, :]
    py = path[:, 1][:, None] - walls[:, 1][None, :]
    cos, sin = np.cos(walls[:, 4])[None, :], np.sin(walls[:, 4])[None, :]
    local_x = np.abs(cos * px + sin * py) - walls[:, 2][None, :] / 2
    local_y = np.abs(-sin * px + cos * py) - walls[:, 3][None, :] / 2
    outside = np.hypot(np.maximum(local_x, 0), np.maximum(local_y, 0))
    inside = np.minimum(np.maximum(local_x, local_y), 0)
    return float((outside + inside).min() - radius)


def dark_fraction(path: npt.NDArray[np.float64], floor: Callable[[float, float], float]) -> float:
    """The fraction of points where the floor within 1 cm (the centre and four points around it)
    is darker than 0.5."""
    if len(path) == 0:
        return 0.0
    offsets = ((0.0, 0.0), (0.01, 0.0), (-0.01, 0.0), (0.0, 0.01), (0.0, -0.01))
    dark = sum(1 for x, y in path if min(floor(x + dx, y + dy) for dx, dy in offsets) < DARK)
    return dark / len(path)


def check(fact: Fact, outcome: Outcome) -> tuple[bool, str]:
    """Whether the outcome shows the fact, and what was measured."""
    if fact.kind == "exit":
        return outcome.exit_status == int(fact.number), f"exit {outcome.exit_status}"
    if fact.kind == "no_error":
        last = outcome.error.strip().splitlines()[-1] if outcome.error.strip() else ""
        return not last, f"error: {last}" if last else "no error"
    if fact.kind == "leaves_start":
        far = farthest_from_start(outcome.path)
        return far > fact.number, f"farthest {far:.2f} m from start"
    if fact.kind == "stays_near":
        far = farthest_from_start(outcome.path)
        return far <= fact.number, f"farthest {far:.2f} m from start"
    if fact.kind == "travels":
        length = path_length(outcome.path)
        return length > fact.number, f"travelled {length:.2f} m"
    if fact.kind == "clearance":
        gap = min_gap(outcome.path, outcome.walls, outcome.robot_radius)
        return gap > fact.number - 1e-9, f"closest to a wall {gap * 100:.1f} cm"
    if fact.kind == "on_dark":
        share = dark_fraction(outcome.path, outcome.floor)
        return share >= fact.number, f"on dark floor {share:.0%} of steps"
    if fact.kind == "walls":
        return outcome.wall_count >= fact.number, f"{outcome.wall_count} walls imported"
    if fact.kind == "robots":
        moving = outcome.robots_moving
        if moving is None:
            moving = int(path_length(outcome.path) > MOVED)
        return moving >= fact.number, f"{moving} robot(s) moved"
    if fact.kind == "prints":
        return (
            fact.text in outcome.stdout,
            "printed" if fact.text in outcome.stdout else "not printed",
        )
    raise ValueError(f"unknown fact kind {fact.kind!r}")
