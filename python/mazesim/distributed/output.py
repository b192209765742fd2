"""A sweep's output folder: one folder per finished run, a summary table and a plot.

::

    OUT/
      sweep.toml          the sweep file as given
      settings.json       every setting of the grid (id, group, label, parameters)
      runs/<id>/          one folder per finished run: tables.npz, curves.csv, run.json
      results.json        every run's status and result (rewritten as each run finishes)
      results.csv         the same, one row per run
      sweep.png           success rate and training time per setting

A run's folder appears whole or not at all: its files are written into a hidden temporary folder
beside it, then renamed into place with :func:`os.replace`. Single files are replaced
atomically (:func:`mazesim._atomic.atomic_file`). So a sweep stopped at any point leaves only
complete runs, and running it again into the same folder skips them.
"""

from __future__ import annotations

import csv
import io
import json
import os
import shutil
import tempfile
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from mazesim._atomic import atomic_file
from mazesim._figures import save_figure
from mazesim._paths import make_output_folder, read_input
from mazesim.distributed.config import Setting
from mazesim.distributed.tasks import RUN_FILE
from mazesim.errors import InvalidArgumentError, MazesimIOError, _shown

__all__ = [
    "CSV_COLUMNS",
    "RESULTS_CSV",
    "RESULTS_JSON",
    "RUNS_DIR",
    "SWEEP_PLOT",
    "read_finished_run",
    "remove_leftovers",
    "save_plot",
    "write_json",
    "write_results_csv",
    "write_run_folder",
]

RUNS_DIR = "runs"
RESULTS_JSON = "results.json"
RESULTS_CSV = "results.csv"
SWEEP_PLOT = "sweep.png"
#: Columns of ``results.csv``.
CSV_COLUMNS: tuple[str, ...] = (
    "id",
    "group",
    "label",
    "seed",
    "status",
    "success_rate",
    "mean_collisions",
    "mean_steps",
    "training_seconds",
    "evaluation_seconds",
    "env_steps",
    "eval_env_steps",
    "trainer",
    "host",
    "folder",
    "error",
)
_TEMPORARY_SUFFIX = ".partial"
#: The largest ``run.json`` read back (a finished run's is a few kB).
MAX_RUN_FILE_BYTES = 16 * 1024 * 1024


def write_json(path: str, value: Any) -> None:
    """Writes a JSON file atomically."""
    with atomic_file(path) as handle:
        handle.write((json.dumps(value, indent=2) + "\n").encode("utf-8"))


def write_run_folder(out_dir: str, run_id: str, files: Mapping[str, bytes]) -> str:
    """Writes a run's files into ``OUT/runs/<run_id>/`` as one atomic step.

    The files go into a hidden temporary folder in ``OUT/runs``, which is then renamed to the
    run's folder; a folder already there (an earlier run of the same setting) is replaced.

    Args:
        out_dir: The sweep's output folder.
        run_id: The setting's id.
        files: File names (no folders) and their contents.

    Returns:
        The run's folder.

    Raises:
        InvalidArgumentError: A file name has a folder in it.
    """
    for name in files:
        if not name or os.path.basename(name) != name or name in (".", ".."):
            raise InvalidArgumentError(
                f"expected a plain file name for a run file, found {_shown(name)}"
            )
    runs = os.path.join(out_dir, RUNS_DIR)
    make_output_folder(runs, "out_dir")
    target = os.path.join(runs, run_id)
    temporary = tempfile.mkdtemp(prefix=f".{run_id}.", suffix=_TEMPORARY_SUFFIX, dir=runs)
    try:
        for name, data in files.items():
            with open(os.path.join(temporary, name), "wb") as handle:
                handle.write(data)
                handle.flush()
                os.fsync(handle.fileno())
        os.chmod(temporary, 0o777 & ~_umask())
        if os.path.isdir(target):
            # A folder cannot be renamed over a non-empty one: move the old one aside first.
            stale = tempfile.mkdtemp(prefix=f".{run_id}.", suffix=_TEMPORARY_SUFFIX, dir=runs)
            os.replace(target, os.path.join(stale, "old"))
            os.replace(temporary, target)
            shutil.rmtree(stale, ignore_errors=True)
        else:
            os.replace(temporary, target)
    except BaseException:
        shutil.rmtree(temporary, ignore_errors=True)
        raise
    return target


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def remove_leftovers(out_dir: str) -> None:
    """Removes temporary folders that an interrupted run left in ``OUT/runs``."""
    runs = os.path.join(out_dir, RUNS_DIR)
    if not os.path.isdir(runs):
        return
    for name in os.listdir(runs):
        if name.startswith(".") and name.endswith(_TEMPORARY_SUFFIX):
            shutil.rmtree(os.path.join(runs, name), ignore_errors=True)


def read_finished_run(out_dir: str, setting: Setting) -> dict[str, Any] | None:
    """The result of a run of ``setting`` already in the output folder, or ``None``.

    A run counts when its folder holds a readable ``run.json`` for the same parameters; any other
    file there (damaged, of another layout, too large or nested too deeply) means the run is done
    again.
    """
    path = os.path.join(out_dir, RUNS_DIR, setting.id, RUN_FILE)
    try:
        text = read_input(path, MAX_RUN_FILE_BYTES, "a finished run")
        metadata = json.loads(text.decode("utf-8")) if len(text) <= MAX_RUN_FILE_BYTES else None
    except (OSError, ValueError, RecursionError):
        return None
    if not isinstance(metadata, dict) or not isinstance(metadata.get("result"), dict):
        return None
    recorded = metadata.get("setting")
    if not isinstance(recorded, dict) or recorded.get("params") != dict(setting.params):
        return None
    return dict(metadata["result"])


def write_results_csv(path: str, runs: Sequence[Mapping[str, Any]]) -> None:
    """Writes ``results.csv``: one row per run, the columns of :data:`CSV_COLUMNS`."""
    text = io.StringIO()
    writer = csv.writer(text, lineterminator="\n")
    writer.writerow(CSV_COLUMNS)
    for run in runs:
        writer.writerow(["" if run.get(key) is None else run[key] for key in CSV_COLUMNS])
    with atomic_file(path) as handle:
        handle.write(text.getvalue().encode("utf-8"))


def _groups(runs: Sequence[Mapping[str, Any]]) -> list[tuple[str, list[Mapping[str, Any]]]]:
    """The runs by setting group, in the order the groups first appear."""
    grouped: dict[str, list[Mapping[str, Any]]] = {}
    labels: dict[str, str] = {}
    for run in runs:
        grouped.setdefault(run["group"], []).append(run)
        labels.setdefault(run["group"], run["label"])
    return [(labels[group], members) for group, members in grouped.items()]


def save_plot(path: str, title: str, runs: Sequence[Mapping[str, Any]]) -> None:
    """Draws success rate and training time per setting (bars: the mean over seeds; dots: each
    seed; red crosses: failed runs) and writes a PNG file atomically."""
    groups = _groups(runs)
    width = min(16.0, max(6.0, 1.1 * len(groups) + 3.0))
    figure = Figure(figsize=(width, 6.5), dpi=110)
    FigureCanvasAgg(figure)
    axes = figure.subplots(2, 1, sharex=True)
    panels = (
        (axes[0], "success_rate", 100.0, "success rate (%)"),
        (axes[1], "training_seconds", 1.0, "training time (s)"),
    )
    positions = np.arange(len(groups))
    for ax, key, scale, ylabel in panels:
        for position, (_, members) in zip(positions, groups):
            values = [
                scale * run[key]
                for run in members
                if run.get("status") == "ok" and run.get(key) is not None
            ]
            failed = sum(1 for run in members if run.get("status") != "ok")
            if values:
                ax.bar(position, float(np.mean(values)), width=0.6, color="#9ecae1", zorder=2)
                spread = np.linspace(-0.15, 0.15, len(values)) if len(values) > 1 else [0.0]
                ax.plot(position + np.asarray(spread), values, "o", color="#08519c", zorder=3)
            if failed:
                ax.plot([position] * failed, [0.0] * failed, "x", color="#d62728", ms=9, zorder=4)
        ax.set_ylabel(ylabel)
        ax.grid(axis="y", alpha=0.3, zorder=0)
    axes[0].set_ylim(0.0, 105.0)
    axes[0].set_title(title)
    axes[1].set_xticks(positions)
    axes[1].set_xticklabels([label for label, _ in groups], rotation=30, ha="right", fontsize=8)
    try:
        save_figure(figure, path)
    except OSError as error:
        raise MazesimIOError(f"cannot write the sweep plot {_shown(path)}: {error}") from error
