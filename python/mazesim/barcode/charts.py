"""CSV tables and bar charts of the barcode reading study (cf. the report's Fig. 4.3 and 4.5).

Each chart has one panel per decoder with, for every setting, three bars: the percentage of
right, wrong and missed readings out of N. Files are written atomically and figures are drawn
with the Agg backend, away from pyplot's global state.
"""

from __future__ import annotations

import csv
import io
import os
from collections.abc import Sequence

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from mazesim._atomic import atomic_file
from mazesim._figures import save_figure
from mazesim._paths import make_output_folder
from mazesim.barcode.study import StudyResult, Tally

__all__ = ["CSV_COLUMNS", "save_study_chart", "study_csv", "write_study_files"]

#: Columns of the CSV tables; shares are in [0, 1], counts out of ``readings``.
CSV_COLUMNS = (
    "decoder",
    "threshold_v",
    "speed",
    "readings",
    "right",
    "wrong",
    "missed",
    "spurious",
    "right_count",
    "wrong_count",
    "missed_count",
    "spurious_count",
)

OUTCOME_COLORS = {"right": "#2ca02c", "wrong": "#d62728", "missed": "#7f7f7f"}


def study_csv(tallies: Sequence[Tally]) -> str:
    """The tallies as CSV text, one row per decoder and setting."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(CSV_COLUMNS)
    for tally in tallies:
        writer.writerow(
            [
                tally.decoder,
                f"{tally.threshold_v:g}",
                f"{tally.speed:g}",
                tally.readings,
                f"{tally.share(tally.right):.4f}",
                f"{tally.share(tally.wrong):.4f}",
                f"{tally.share(tally.missed):.4f}",
                f"{tally.share(tally.spurious):.4f}",
                tally.right,
                tally.wrong,
                tally.missed,
                tally.spurious,
            ]
        )
    return buffer.getvalue()


def save_study_chart(
    tallies: Sequence[Tally],
    key: str,
    path: str | os.PathLike[str],
    title: str,
) -> None:
    """Draws grouped bars of right / wrong / missed percentages per setting, one panel per
    decoder, and writes them as a PNG file.

    Args:
        tallies: The tallies of one study (all decoders, all settings).
        key: ``"threshold_v"`` or ``"speed"``: the setting on the x axis.
        path: The PNG file to write; its folder must exist.
        title: The figure's title.
    """
    decoders = list(dict.fromkeys(t.decoder for t in tallies))
    figure = Figure(figsize=(4.2 * max(len(decoders), 1) + 0.6, 3.8), dpi=120)
    FigureCanvasAgg(figure)
    axes = figure.subplots(1, max(len(decoders), 1), sharey=True, squeeze=False)[0]
    label = "obstacle threshold (V)" if key == "threshold_v" else "wheel speed (rad/s)"
    width = 0.26
    for ax, decoder in zip(axes, decoders):
        rows = [t for t in tallies if t.decoder == decoder]
        settings = [t.threshold_v if key == "threshold_v" else t.speed for t in rows]
        positions = np.arange(len(rows))
        for offset, outcome in zip((-width, 0.0, width), OUTCOME_COLORS):
            shares = [100.0 * t.share(getattr(t, outcome)) for t in rows]
            bars = ax.bar(
                positions + offset,
                shares,
                width,
                color=OUTCOME_COLORS[outcome],
                label=outcome,
            )
            if outcome == "right":
                ax.bar_label(bars, fmt="%.0f", fontsize=7, padding=1)
        ax.set_xticks(positions, [f"{value:g}" for value in settings])
        ax.set_xlabel(label)
        ax.set_title(f"decoder {decoder}", fontsize=10)
        ax.set_ylim(0.0, 109.0)
        ax.grid(axis="y", alpha=0.3)
    axes[0].set_ylabel("readings (%)")
    axes[-1].legend(loc="center right", fontsize=8)
    figure.suptitle(title, fontsize=10)
    save_figure(figure, path)


def write_study_files(result: StudyResult, folder: str | os.PathLike[str]) -> list[str]:
    """Writes ``by_threshold.csv``, ``by_speed.csv``, ``by_threshold.png`` and
    ``by_speed.png`` into ``folder`` (created if missing) and returns their paths.

    A study part with no settings writes no files.
    """
    make_output_folder(folder)
    written = []
    parts = (
        (
            "by_threshold",
            result.by_threshold,
            "threshold_v",
            f"Barcode readings by obstacle threshold ({result.readings} readings each, "
            f"speed {result.default_speed:g} rad/s, {result.link} link)",
        ),
        (
            "by_speed",
            result.by_speed,
            "speed",
            f"Barcode readings by wheel speed ({result.readings} readings each, "
            f"threshold {result.default_threshold_v:g} V, {result.link} link)",
        ),
    )
    for stem, tallies, key, title in parts:
        if not tallies:
            continue
        table = os.path.join(folder, f"{stem}.csv")
        with atomic_file(table) as handle:
            handle.write(study_csv(tallies).encode("utf-8"))
        chart = os.path.join(folder, f"{stem}.png")
        save_study_chart(tallies, key, chart, title)
        written += [table, chart]
    return written
