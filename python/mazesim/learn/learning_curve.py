"""The learning curve of a training: its points, built in one place, and its files.

The training reports the curve point by point through a :data:`CurveFn`: a point per lower-level
round (:func:`lower_point`, from the round's summary) and a point each time higher-level (or flat)
episodes end (:func:`episode_progress`: the share of the last 200 episodes that reached the
goal). :class:`CurvePoints` keeps them as columns (a sweep's ``curves.csv``);
:class:`LearningCurve` writes them as they come for ``mazesim train``.

``OUT/learning_curve.csv`` has one row per point and the columns :data:`CSV_COLUMNS`: ``stage``
(``lower``, ``higher``, or ``flat`` for ``--flat``), then the values that :data:`CURVE_VALUES`
describes, empty where a stage does not measure one. A resumed run writes the file afresh, its
checkpoint's rounds first. With ``--tensorboard``
the same values also go to TensorBoard event files in ``OUT/tensorboard/`` (as
``lower/door_success_right``, ``higher/goal_rate``..., stepped by ``index``); that needs the
optional ``tensorboardX`` package (``pip install 'mazesim[tensorboard]'``).
"""

from __future__ import annotations

import csv
import io
import math
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from mazesim._atomic import atomic_file
from mazesim._closing import Closing
from mazesim._paths import make_output_folder
from mazesim.errors import MissingDependencyError

if TYPE_CHECKING:
    from mazesim.learn.lower import LowerSettings

__all__ = [
    "CSV_COLUMNS",
    "CURVE_FILE",
    "CURVE_VALUES",
    "TENSORBOARD_FOLDER",
    "CurveFn",
    "CurvePoints",
    "LearningCurve",
    "episode_progress",
    "lower_point",
]

#: The learning curve's values, in order: what :data:`CurveFn` reports for each point.
#: ``index`` is the lower level's round (1-based) or the higher level's episodes finished (the
#: flat learner's env-steps done); ``env_steps`` the lower level's env-steps so far; ``epsilon``
#: its exploration rate; ``door_success_right``/``_left``/``_forward`` the share of each door
#: sub-task's episodes of the round that ended in their opening; ``corridor_speed`` "Corridors
#: and Corners"' mean forward speed over the round as a share of the cruise speed;
#: ``contact_share`` the share of the round's steps in contact with a wall; ``goal_rate`` the
#: share of the last 200 episodes that reached the goal. A value a stage does not measure is
#: absent.
CURVE_VALUES = (
    "index",
    "env_steps",
    "epsilon",
    "door_success_right",
    "door_success_left",
    "door_success_forward",
    "corridor_speed",
    "contact_share",
    "goal_rate",
)
#: Receives the learning curve point by point as ``curve(stage, values)``: stage ``"lower"``
#: after each round (the rounds of a resumed run's checkpoint first), ``"higher"`` (or
#: ``"flat"``) each time episodes end; ``values`` maps names of :data:`CURVE_VALUES` to numbers.
CurveFn = Callable[[str, dict[str, float]], None]
#: How training stages report progress: ``progress(stage, done, total)``.
_ProgressFn = Callable[[str, int, int], None]

#: The CSV file's name in the output folder.
CURVE_FILE = "learning_curve.csv"
#: The folder of the TensorBoard event files in the output folder.
TENSORBOARD_FOLDER = "tensorboard"
#: The CSV file's columns.
CSV_COLUMNS = ("stage", *CURVE_VALUES)


def lower_point(summary: dict[str, Any], lower: LowerSettings) -> dict[str, float]:
    """The learning curve's point of a lower-level round from its summary."""
    done = int(summary["round"]) + 1
    right, left, forward = summary["door_success"]
    return {
        "index": done,
        "env_steps": done * lower.num_envs * lower.round_steps,
        "epsilon": summary["epsilon"],
        "door_success_right": right,
        "door_success_left": left,
        "door_success_forward": forward,
        "corridor_speed": summary["corridor_speed"],
        "contact_share": summary["contact_share"],
    }


def episode_progress(
    stage: str, progress: _ProgressFn | None, curve: CurveFn | None
) -> Callable[[int, int, float], None]:
    """The ``progress(done, total, recent_goal_rate)`` callback of the higher level's or the flat
    learner's training: it reports ``progress(stage, done, total)`` and the curve's point
    ``{"index": done, "goal_rate": recent_goal_rate}``."""

    def report(done: int, total: int, recent: float) -> None:
        if progress is not None:
            progress(stage, done, total)
        if curve is not None:
            curve(stage, {"index": done, "goal_rate": recent})

    return report


class CurvePoints:
    """A :data:`CurveFn` that keeps the points, to hand them back as columns."""

    def __init__(self) -> None:
        self.points: list[tuple[str, dict[str, float]]] = []

    def __call__(self, stage: str, values: dict[str, float]) -> None:
        self.points.append((stage, dict(values)))

    def columns(self) -> dict[str, list[Any]]:
        """``stage`` and each of :data:`CURVE_VALUES`, one item per point (NaN where a stage
        does not measure a value)."""
        found: dict[str, list[Any]] = {"stage": [stage for stage, _ in self.points]}
        for name in CURVE_VALUES:
            found[name] = [values.get(name, math.nan) for _, values in self.points]
        return found


def _tensorboard_writer_class() -> Any:
    """``tensorboardX.SummaryWriter``."""
    try:
        from tensorboardX import SummaryWriter
    except ImportError:
        raise MissingDependencyError(
            "--tensorboard needs the tensorboardX package: pip install 'mazesim[tensorboard]'"
        ) from None
    return SummaryWriter


class LearningCurve(Closing):
    """Writes a training's learning curve into ``folder`` as it comes (a context manager and a
    :data:`CurveFn`); the files are opened at the first point, the folder
    made then if the training has not made it yet.

    Args:
        folder: The output folder.
        tensorboard: Also log to TensorBoard event files.

    Raises:
        MissingDependencyError: ``tensorboard`` without the tensorboardX package (raised before
            any file is written).
    """

    def __init__(self, folder: Path, tensorboard: bool = False) -> None:
        self.folder = folder
        self._writer_class = _tensorboard_writer_class() if tensorboard else None
        self.writer: Any = None
        self.path = folder / CURVE_FILE
        self._rows = io.StringIO()
        self._csv: Any = None

    def __call__(self, stage: str, values: dict[str, float]) -> None:
        if self._csv is None:
            # The hierarchical training has made the folder by now; the flat one makes it last.
            make_output_folder(self.folder)
            self._csv = csv.DictWriter(self._rows, fieldnames=CSV_COLUMNS, restval="")
            self._csv.writeheader()
            if self._writer_class is not None:
                self.writer = self._writer_class(logdir=str(self.folder / TENSORBOARD_FOLDER))
        self._csv.writerow({"stage": stage, **values})
        # Written whole at each point (a few hundred short rows at most), as every output is.
        with atomic_file(self.path) as handle:
            handle.write(self._rows.getvalue().encode("utf-8"))
        if self.writer is not None:
            step = int(values["index"])
            for name, value in values.items():
                if name != "index":
                    self.writer.add_scalar(f"{stage}/{name}", value, step)

    def close(self) -> None:
        """Closes the TensorBoard files (the CSV file is complete after each point)."""
        if self.writer is not None:
            self.writer.close()
