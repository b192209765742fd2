"""Heat maps of a transfer study, and the files a study writes.

``transfer_single.png`` has one row per axis: the baseline first, then each level, coloured by the
success rate (red 0 % to green 100 %) and labelled with the level and the rate.
``transfer_pairs.png`` is the pairwise matrix: the cell of axes (a, b) is the success with both at
their harshest levels; the diagonal is each axis alone at its harshest level. Figures are drawn
with the Agg backend, away from pyplot's global state, and written atomically.
"""

from __future__ import annotations

import json
import os

import numpy as np
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.image import AxesImage

from mazesim._atomic import atomic_file
from mazesim._figures import save_figure
from mazesim._paths import make_output_folder
from mazesim.transfer.result import StudyResult

__all__ = ["save_pairs_map", "save_single_map", "write_study_files"]

#: The colour map of success rates.
COLOURS = "RdYlGn"


def _save(figure: Figure, plot: Axes, image: AxesImage, title: str, path: str) -> None:
    """Adds the colour bar of success rates and the title, then writes the PNG."""
    figure.colorbar(image, ax=plot, label="success rate")
    plot.set_title(title, fontsize=9)
    FigureCanvasAgg(figure)
    save_figure(figure, path, dpi=110)


def _percent(share: float) -> str:
    return f"{100.0 * share:.0f}%"


def save_single_map(result: StudyResult, path: str) -> None:
    """Draws the single-axis heat map (axes x levels) into a PNG."""
    axes = result.axes
    columns = 1 + max(len(axis.levels) for axis in axes)
    rates = np.full((len(axes), columns), np.nan)
    figure = Figure(figsize=(2.0 + 1.5 * columns, 1.2 + 0.55 * len(axes)))
    plot = figure.add_subplot()
    for row, axis in enumerate(axes):
        rates[row, 0] = result.baseline.measure.success_rate
        plot.text(0, row, f"rest\n{_percent(rates[row, 0])}", ha="center", va="center",
                  fontsize=7)  # fmt: skip
        own = [cell for cell in result.single if cell.setting.axes == (axis.name,)]
        for column, cell in enumerate(own, start=1):
            rate = cell.measure.success_rate
            rates[row, column] = rate
            text = f"{axis.label(cell.setting.get(axis.name))}\n{_percent(rate)}"
            plot.text(column, row, text, ha="center", va="center", fontsize=7)
    image = plot.imshow(np.ma.masked_invalid(rates), cmap=COLOURS, vmin=0.0, vmax=1.0,
                        aspect="auto")  # fmt: skip
    plot.set_yticks(range(len(axes)), [axis.name for axis in axes], fontsize=8)
    plot.set_xticks(range(columns), ["baseline", *(f"level {i}" for i in range(1, columns))],
                    fontsize=8)  # fmt: skip
    title = (
        f"{result.world}: {result.policy} navigator, success by perturbation "
        f"({result.episodes_label}, seed {result.seed}, {result.odometry_label})"
    )
    _save(figure, plot, image, title, path)


def save_pairs_map(result: StudyResult, path: str) -> None:
    """Draws the pairwise matrix (axes x axes at their harshest levels) into a PNG."""
    axes = result.axes
    names = [axis.name for axis in axes]
    rates = np.full((len(axes), len(axes)), np.nan)
    for cell in result.single:
        (name,) = cell.setting.axes
        if cell.setting.get(name) == result.harshest[name]:
            place = names.index(name)
            rates[place, place] = cell.measure.success_rate
    for cell in result.pairs:
        a, b = (names.index(name) for name in cell.setting.axes)
        rates[a, b] = rates[b, a] = cell.measure.success_rate
    figure = Figure(figsize=(max(6.5, 2.5 + 0.75 * len(axes)), 2.0 + 0.65 * len(axes)))
    plot = figure.add_subplot()
    image = plot.imshow(np.ma.masked_invalid(rates), cmap=COLOURS, vmin=0.0, vmax=1.0)
    for a in range(len(axes)):
        for b in range(len(axes)):
            if not np.isnan(rates[a, b]):
                plot.text(b, a, _percent(rates[a, b]), ha="center", va="center", fontsize=7)
    labels = [f"{axis.name}\n{axis.label(result.harshest[axis.name])}" for axis in axes]
    plot.set_xticks(range(len(axes)), labels, fontsize=7, rotation=60, ha="right")
    plot.set_yticks(range(len(axes)), labels, fontsize=7)
    title = (
        f"{result.world}: {result.policy} navigator, pairs of perturbations at their harshest "
        f"levels\n({result.episodes_label}; {result.odometry_label}; diagonal: one axis alone)"
    )
    _save(figure, plot, image, title, path)


def write_study_files(result: StudyResult, folder: str | os.PathLike[str]) -> list[str]:
    """Writes ``transfer.json``, ``transfer_single.png`` and (with pairs)
    ``transfer_pairs.png`` into ``folder`` (created if missing); returns their paths."""
    make_output_folder(folder)
    document = os.path.join(folder, "transfer.json")
    with atomic_file(document) as handle:
        handle.write((json.dumps(result.as_json(), indent=2) + "\n").encode("utf-8"))
    single = os.path.join(folder, "transfer_single.png")
    save_single_map(result, single)
    written = [document, single]
    if result.pairs:
        pairs = os.path.join(folder, "transfer_pairs.png")
        save_pairs_map(result, pairs)
        written.append(pairs)
    return written
