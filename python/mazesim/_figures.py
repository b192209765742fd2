"""PNG files of matplotlib figures: the one place a figure of mazesim is laid out and saved.

A title or label may hold characters the installed fonts lack (a world named in Chinese or with
an emoji): matplotlib draws each as an empty box and warns once per character, and under
``PYTHONWARNINGS=error`` (or ``-W error``) that warning became an error that stopped the command
after its run. :func:`save_png` draws them as boxes without the warning, and writes the file
atomically (:func:`mazesim._atomic.atomic_file`).

A figure is written as PNG whatever its file is named: a name with another suffix (``x.txt``,
``plot.pdf``) is refused, by :func:`save_png` before anything is written and by the command-line
options that name a figure (:func:`figure_file`) before the command runs.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import stat
import warnings
from collections.abc import Iterator
from typing import TYPE_CHECKING

from mazesim._atomic import atomic_file
from mazesim._paths import output_path
from mazesim.errors import InvalidArgumentError

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = [
    "FIGURE_SUFFIXES",
    "figure_file",
    "figure_suffix_refusal",
    "missing_glyphs_as_boxes",
    "save_png",
]

#: matplotlib's warning of a character no font it tried has ("Glyph 36855 (...) missing from
#: font(s) DejaVu Sans.").
_MISSING_GLYPH = r"Glyph \d+ .*missing from font"


#: The suffixes a figure's file may have (any case): the one format :func:`save_png` writes. A
#: name without a suffix (``plot``) takes it too, and so does something that is not a file
#: (``/dev/stdout``, a FIFO, a device), whose name says nothing of what goes through it.
FIGURE_SUFFIXES = (".png",)


def figure_suffix_refusal(path: str | os.PathLike[str]) -> str | None:
    """Why a PNG cannot honestly be written to ``path`` (its name ends in another suffix), or
    None."""
    name = os.fsdecode(os.fspath(path))
    suffix = os.path.splitext(name)[1]
    if not suffix or suffix.lower() in FIGURE_SUFFIXES or _special(name):
        return None
    return (
        f"expected a figure file ending in {' or '.join(FIGURE_SUFFIXES)} (figures are written as "
        f"PNG), found {name!r}, ending in {suffix!r}"
    )


def _special(name: str) -> bool:
    """Whether ``name`` is something other than a file or folder (a device, a FIFO, a socket)."""
    try:
        mode = os.stat(name).st_mode
    except (OSError, ValueError):
        return False
    return not (stat.S_ISREG(mode) or stat.S_ISDIR(mode))


def figure_file(text: str) -> str:
    """The path of a figure to write, as a command-line argument type: a path to write to
    (:func:`mazesim._paths.output_path`) whose suffix, if any, is one of
    :data:`FIGURE_SUFFIXES`."""
    output_path(text)
    refusal = figure_suffix_refusal(text)
    if refusal is not None:
        raise argparse.ArgumentTypeError(refusal)
    return text


@contextlib.contextmanager
def missing_glyphs_as_boxes() -> Iterator[None]:
    """Within it, a character the fonts lack is drawn as a box without a warning."""
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=_MISSING_GLYPH, category=UserWarning)
        yield


def save_png(
    figure: Figure, path: str | os.PathLike[str], *, tight: bool = True, dpi: float | None = None
) -> None:
    """Lays ``figure`` out (``tight_layout`` unless ``tight`` is False) and writes it to ``path``
    as a PNG, atomically, at ``dpi`` (the figure's own when None).

    Raises:
        InvalidArgumentError: ``path`` ends in a suffix other than those of
            :data:`FIGURE_SUFFIXES`; nothing is written.
    """
    refusal = figure_suffix_refusal(path)
    if refusal is not None:
        raise InvalidArgumentError(refusal)
    with missing_glyphs_as_boxes():
        if tight:
            figure.tight_layout()
        with atomic_file(path) as handle:
            if dpi is None:
                figure.savefig(handle, format="png")
            else:
                figure.savefig(handle, format="png", dpi=dpi)
