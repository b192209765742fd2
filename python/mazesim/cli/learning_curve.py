"""The learning curve of ``mazesim train``: a CSV file always, TensorBoard on request.

``OUT/learning_curve.csv`` has one row per point the training reports
(:data:`mazesim.learn.train.CurveFn`) and the columns :data:`CSV_COLUMNS`: ``stage``
(``lower``, ``higher``, or ``flat`` for ``--flat``), then the values that
:data:`mazesim.learn.train.CURVE_VALUES` describes, empty where a stage does not measure one.
A resumed run writes the file afresh, its checkpoint's rounds first. With ``--tensorboard``
the same values also go to TensorBoard event files in ``OUT/tensorboard/`` (as
``lower/door_success_right``, ``higher/goal_rate``..., stepped by ``index``); that needs the
optional ``tensorboardX`` package (``pip install 'mazesim[tensorboard]'``).
"""

from __future__ import annotations

import csv
import io
from pathlib import Path
from types import TracebackType
from typing import Any

from mazesim._atomic import atomic_file
from mazesim.errors import MissingDependencyError
from mazesim.learn.train import CURVE_VALUES

__all__ = ["CSV_COLUMNS", "CURVE_FILE", "TENSORBOARD_FOLDER", "LearningCurve"]

#: The CSV file's name in the output folder.
CURVE_FILE = "learning_curve.csv"
#: The folder of the TensorBoard event files in the output folder.
TENSORBOARD_FOLDER = "tensorboard"
#: The CSV file's columns.
CSV_COLUMNS = ("stage", *CURVE_VALUES)


def _tensorboard_writer_class() -> Any:
    """``tensorboardX.SummaryWriter``."""
    try:
        from tensorboardX import SummaryWriter
    except ImportError:
        raise MissingDependencyError(
            "--tensorboard needs the tensorboardX package: pip install 'mazesim[tensorboard]'"
        ) from None
    return SummaryWriter


class LearningCurve:
    """Writes a training's learning curve into ``folder`` as it comes (a context manager and a
    :data:`mazesim.learn.train.CurveFn`); the files are opened at the first point, the folder
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
            self.folder.mkdir(parents=True, exist_ok=True)
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

    def __enter__(self) -> LearningCurve:
        return self

    def __exit__(
        self,
        kind: type[BaseException] | None,
        error: BaseException | None,
        trace: TracebackType | None,
    ) -> None:
        self.close()
