"""A transfer study's result, its JSON form and the schema that JSON is checked against.

The JSON object (``mazesim transfer-study --json``, and ``transfer.json`` in ``--out``)::

    {
      "format": "mazesim-transfer-study", "version": 1,
      "policy": "<the navigator's folder, or 'shipped'>", "world": "seed-maze",
      "seed": 0, "episodes": 100, "events": "robust", "odometry": "encoders",
      "max_steps": 2000,
      "axes": [{"name": "wheel_radius", "unit": "x", "rest": 1.0,
                "levels": [0.95, ...], "harshest": 0.95}, ...],
      "baseline": {CELL},
      "single": [{CELL}, ...],
      "pairs": [{CELL}, ...]
    }

where a CELL is ``{"setting": {"axis": level, ...}, "label": "...", "episodes": N,
"success_rate": s, "contacts_per_episode": c, "collision_free_rate": f, "path_ratio": p | null,
"mean_steps": m | null}``. ``single`` holds one cell per level of each axis; ``pairs`` one cell
per pair of axes, each at its harshest level (the level of lowest single-axis success). Shares
are in [0, 1]. The JSON holds no time or host, so the same study gives the same bytes.
:data:`STUDY_SCHEMA` is the schema, :func:`check_study_json` checks a document against it.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from mazesim.errors import InvalidArgumentError, PolicyFormatError
from mazesim.learn.schema import ListOf, Node, Number, Record, Text, Whole
from mazesim.learn.summary import Summary
from mazesim.transfer.axes import AXIS_NAMES, Axis, Level, Setting
from mazesim.transfer.odometry import ODOMETRY_SOURCES

__all__ = ["FORMAT", "STUDY_SCHEMA", "VERSION", "Cell", "StudyResult", "check_study_json"]

#: The ``format`` field of a study's JSON.
FORMAT = "mazesim-transfer-study"
#: The ``version`` field of a study's JSON.
VERSION = 1


@dataclass
class Cell:
    """A setting and what its episodes measured (the evaluator's :class:`Summary`)."""

    setting: Setting
    measure: Summary

    def as_json(self) -> dict[str, Any]:
        """The cell as the JSON's CELL object: the summary under the study's documented keys."""
        measure = self.measure
        return {
            "setting": self.setting.as_json(),
            "label": self.setting.label(),
            "episodes": measure.episodes,
            "success_rate": measure.success_rate,
            "contacts_per_episode": measure.mean_collisions,
            "collision_free_rate": measure.collision_free_rate,
            "path_ratio": measure.mean_path_ratio,
            "mean_steps": measure.mean_steps,
        }


@dataclass
class StudyResult:
    """What a transfer study measured.

    Attributes:
        policy: The navigator's folder, or ``"shipped"``.
        world: The world's name.
        seed: The study's seed.
        episodes: Episodes per cell.
        events: Where checkpoint events came from (``"truth"`` or ``"robust"``).
        odometry: What the navigator's odometry came from (``"encoders"`` or ``"truth"``).
        max_steps: Control steps after which an episode failed.
        axes: The axes studied.
        harshest: Each axis's level of lowest single-axis success.
        baseline: The unperturbed cell.
        single: One cell per level of each axis.
        pairs: One cell per pair of axes at their harshest levels.
    """

    policy: str
    world: str
    seed: int
    episodes: int
    events: str
    odometry: str
    max_steps: int
    axes: tuple[Axis, ...]
    harshest: dict[str, Level]
    baseline: Cell
    single: list[Cell] = field(default_factory=list)
    pairs: list[Cell] = field(default_factory=list)

    @property
    def episodes_label(self) -> str:
        """The episodes per cell in words: ``"1 episode a cell"``, ``"200 episodes a cell"``."""
        return f"{self.episodes} episode{'' if self.episodes == 1 else 's'} a cell"

    @property
    def odometry_label(self) -> str:
        """Where the odometry came from, in words: ``"odometry from the wheel encoders"``."""
        source = "the wheel encoders" if self.odometry == "encoders" else "the true pose"
        return f"odometry from {source}"

    def as_json(self) -> dict[str, Any]:
        """The result as the documented JSON object."""
        return {
            "format": FORMAT,
            "version": VERSION,
            "policy": self.policy,
            "world": self.world,
            "seed": self.seed,
            "episodes": self.episodes,
            "events": self.events,
            "odometry": self.odometry,
            "max_steps": self.max_steps,
            "axes": [
                {
                    "name": axis.name,
                    "description": axis.description,
                    "unit": axis.unit,
                    "rest": axis.rest,
                    "levels": list(axis.levels),
                    "harshest": self.harshest[axis.name],
                }
                for axis in self.axes
            ],
            "baseline": self.baseline.as_json(),
            "single": [cell.as_json() for cell in self.single],
            "pairs": [cell.as_json() for cell in self.pairs],
        }


@dataclass(frozen=True)
class _Nullable(Node):
    """``null`` or a value fitting ``item``."""

    item: Node

    def check(self, value: Any, where: str, path: str) -> None:
        if value is not None:
            self.item.check(value, where, path)


@dataclass(frozen=True)
class _LevelNode(Node):
    """A level: a finite number or a name."""

    def check(self, value: Any, where: str, path: str) -> None:
        if isinstance(value, str):
            Text(max_length=64).check(value, where, path)
        else:
            Number(-1e6, 1e6).check(value, where, path)


_SHARE = Number(0.0, 1.0)
_LEVEL = _LevelNode()
_CELL = Record(
    {
        "setting": Record({name: _LEVEL for name in AXIS_NAMES}, optional=frozenset(AXIS_NAMES)),
        "label": Text(max_length=512),
        "episodes": Whole(1, 10**9),
        "success_rate": _SHARE,
        "contacts_per_episode": Number(0.0, 1e9),
        "collision_free_rate": _SHARE,
        "path_ratio": _Nullable(Number(0.0, 1e6)),
        "mean_steps": _Nullable(Number(0.0, 1e9)),
    }
)
#: The schema of a study's JSON (:mod:`mazesim.learn.schema` nodes).
STUDY_SCHEMA = Record(
    {
        "format": Text(choices=(FORMAT,)),
        "version": Whole(VERSION, VERSION),
        "policy": Text(),
        "world": Text(max_length=256),
        "seed": Whole(0, 2**64 - 1),
        "episodes": Whole(1, 10**9),
        "events": Text(choices=("truth", "robust")),
        "odometry": Text(choices=ODOMETRY_SOURCES),
        "max_steps": Whole(1, 10**9),
        "axes": ListOf(
            Record(
                {
                    "name": Text(choices=AXIS_NAMES),
                    "description": Text(max_length=512),
                    "unit": Text(max_length=16),
                    "rest": _LEVEL,
                    "levels": ListOf(_LEVEL, 1, 64),
                    "harshest": _LEVEL,
                }
            ),
            1,
            len(AXIS_NAMES),
        ),
        "baseline": _CELL,
        "single": ListOf(_CELL, 0, 10_000),
        "pairs": ListOf(_CELL, 0, 10_000),
    },
    # Studies written before the odometry was a choice took the simulator's poses ("truth").
    optional=frozenset({"odometry"}),
)


def check_study_json(document: Any, where: str = "transfer study") -> None:
    """Checks a parsed study JSON document against :data:`STUDY_SCHEMA`.

    Raises:
        InvalidArgumentError: The first field that does not fit, named with what was expected
            and what was found.
    """
    try:
        STUDY_SCHEMA.check(document, where, "")
    except PolicyFormatError as error:
        raise InvalidArgumentError(str(error)) from None
