"""PNG files of matplotlib figures: the one place a figure of mazesim is laid out and saved.

A title or label may hold characters the installed fonts lack (a world named in Chinese or with
an emoji): matplotlib draws each as an empty box and warns once per character, and under
``PYTHONWARNINGS=error`` (or ``-W error``) that warning became an error that stopped the command
after its run. :func:`save_png` draws them as boxes without the warning, and writes the file
atomically (:func:`mazesim._atomic.atomic_file`).
"""

from __future__ import annotations

import contextlib
import os
import warnings
from collections.abc import Iterator
from typing import TYPE_CHECKING

from mazesim._atomic import atomic_file

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["missing_glyphs_as_boxes", "save_png"]

#: matplotlib's warning of a character no font it tried has ("Glyph 36855 (...) missing from
#: font(s) DejaVu Sans.").
_MISSING_GLYPH = r"Glyph \d+ .*missing from font"


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
    as a PNG, atomically, at ``dpi`` (the figure's own when None)."""
    with missing_glyphs_as_boxes():
        if tight:
            figure.tight_layout()
        with atomic_file(path) as handle:
            if dpi is None:
                figure.savefig(handle, format="png")
            else:
                figure.savefig(handle, format="png", dpi=dpi)
