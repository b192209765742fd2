"""Files of matplotlib figures: the one place a figure of mazesim is laid out and saved.

A title or label may hold characters the installed fonts lack (a world named in Chinese or with
an emoji): matplotlib draws each as an empty box and warns once per character, and under
``PYTHONWARNINGS=error`` (or ``-W error``) that warning became an error that stopped the command
after its run. :func:`save_figure` draws them as boxes without the warning, and writes the file
atomically (:func:`mazesim._atomic.atomic_file`).

A text may also hold a lone surrogate, which FreeType cannot lay out (matplotlib raised a
TypeError): a file name's undecodable byte, which Python decodes as one (``\\xff`` as ``\\udcff``),
reaches a title through a world's or a controller's name, a tick label through a sweep's group.
While :func:`save_figure` lays a figure out and writes it, every text matplotlib draws (titles,
labels, legends, annotations, and the tick labels it formats only then) is read with each such
character escaped, as ``\\xff`` for a byte a name could not decode and ``\\ud800`` for another;
the figure's own texts are left as they were, and so are figures drawn elsewhere.

A figure is written in the format its file's suffix names: PNG, or PDF and SVG for a paper's
vector figures (written without a creation date, and SVG with fixed ids, so the same figure gives
the same bytes); a name without a suffix, or a device or FIFO, gets PNG. A name with another suffix
(``x.txt``, ``plot.jpg``) is refused, by :func:`save_figure` before anything is written and by the
command-line options that name a figure (:func:`figure_file`) before the command runs.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import re
import stat
import threading
import warnings
from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

from mazesim._atomic import atomic_file
from mazesim._callers import thread_flag
from mazesim._paths import output_path
from mazesim.errors import InvalidArgumentError, _shown

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = [
    "FIGURE_SUFFIXES",
    "drawable_text",
    "figure_file",
    "figure_format",
    "figure_suffix_refusal",
    "missing_glyphs_as_boxes",
    "save_figure",
]

#: matplotlib's warning of a character no font it tried has ("Glyph 36855 (...) missing from
#: font(s) DejaVu Sans.").
_MISSING_GLYPH = r"Glyph \d+ .*missing from font"

#: A lone surrogate (U+D800 to U+DFFF), which no font draws and FreeType refuses to lay out.
_LONE_SURROGATE = re.compile("[\ud800-\udfff]")

#: The suffixes a figure's file may have (any case), each the format :func:`save_figure` writes.
#: A name without a suffix (``plot``) gets PNG, and so does something that is not a file
#: (``/dev/stdout``, a FIFO, a device), whose name says nothing of what goes through it.
FIGURE_SUFFIXES = (".png", ".pdf", ".svg")
#: What each vector format would otherwise vary from one run to the next (the time it was
#: written), left out.
_UNDATED = {"pdf": {"CreationDate": None}, "svg": {"Date": None}}


def figure_suffix_refusal(path: str | os.PathLike[str]) -> str | None:
    """Why a figure cannot honestly be written to ``path`` (its name ends in a suffix of no
    format :func:`save_figure` writes), or None."""
    name = os.fsdecode(os.fspath(path))
    suffix = os.path.splitext(name)[1]
    if not suffix or suffix.lower() in FIGURE_SUFFIXES or _special(name):
        return None
    return (
        f"expected a figure file ending in {', '.join(FIGURE_SUFFIXES[:-1])} or "
        f"{FIGURE_SUFFIXES[-1]} (figures are written as PNG, PDF or SVG), found {_shown(name)}, "
        f"ending in {_shown(suffix)}"
    )


def figure_format(path: str | os.PathLike[str]) -> str:
    """The format :func:`save_figure` writes to ``path``: its suffix's (``"pdf"``, ``"svg"``),
    else ``"png"``."""
    name = os.fsdecode(os.fspath(path))
    suffix = os.path.splitext(name)[1].lower()
    return suffix[1:] if suffix in FIGURE_SUFFIXES and not _special(name) else "png"


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


def drawable_text(text: str) -> str:
    """``text`` with each lone surrogate escaped: ``\\xff`` for one that stands for a byte a file
    name could not decode (U+DC80 to U+DCFF, as :func:`os.fsdecode` makes them), else
    ``\\ud800``."""
    return _LONE_SURROGATE.sub(_escaped_surrogate, text)


def _escaped_surrogate(found: re.Match[str]) -> str:
    code = ord(found.group())
    return f"\\x{code - 0xDC00:02x}" if 0xDC80 <= code <= 0xDCFF else f"\\u{code:04x}"


#: Whether this thread is inside :func:`_texts_drawable` (a figure being laid out and saved).
_DRAWING = threading.local()


def _install_drawable_texts() -> None:
    """Makes matplotlib's ``Text.get_text`` give :func:`drawable_text` of the text while this
    thread saves a figure (:data:`_DRAWING`), its own text otherwise; once per process. Every
    text matplotlib lays out and draws is read through ``get_text``, tick labels included, which
    are formatted only while the figure is drawn."""
    from matplotlib.text import Text

    original = Text.get_text
    if getattr(original, "_drawable", False):
        return

    def get_text(self: Text) -> str:
        text = original(self)
        if getattr(_DRAWING, "active", False) and isinstance(text, str):
            return drawable_text(text)
        return text

    get_text._drawable = True  # type: ignore[attr-defined]
    Text.get_text = get_text  # type: ignore[method-assign]


def _texts_drawable() -> contextlib.AbstractContextManager[None]:
    """Within it, this thread's figures draw their texts as :func:`drawable_text` shows them."""
    _install_drawable_texts()
    return thread_flag(_DRAWING, "active", True)


#: Inches left between a figure's edge and a drawing moved in from past it.
_EDGE_PAD = 0.05
#: Inches a drawing may reach past an edge unmoved: less than a pixel at the figures' dpi.
_SLACK = 0.01


def _overhang(figure: Figure) -> tuple[float, float, float, float]:
    """How far (inches) the drawing of ``figure`` reaches past its left, bottom, right and top
    edges (0 where it stays inside)."""
    box = figure.get_tightbbox()
    if box is None:
        return (0.0, 0.0, 0.0, 0.0)
    width, height = figure.get_size_inches()
    return (
        max(0.0, -box.x0),
        max(0.0, -box.y0),
        max(0.0, box.x1 - width),
        max(0.0, box.y1 - height),
    )


def _make_room(figure: Figure) -> bool:
    """Moves the subplots in from the edges that some text or legend reaches past (a legend
    beside a world drawn to scale, for which ``tight_layout`` makes no room when the axes keep
    their aspect), keeping the figure's size; True when the drawing then fits (at once for a
    figure that already fits, which is left as it is)."""
    for _ in range(8):
        left, bottom, right, top = _overhang(figure)
        if max(left, bottom, right, top) <= _SLACK:
            return True
        engine = figure.get_layout_engine()
        if engine is not None and not engine.adjust_compatible:
            return False
        width, height = figure.get_size_inches()
        params = figure.subplotpars
        moved = [
            params.left + (left + _EDGE_PAD) / width if left > _SLACK else params.left,
            params.bottom + (bottom + _EDGE_PAD) / height if bottom > _SLACK else params.bottom,
            params.right - (right + _EDGE_PAD) / width if right > _SLACK else params.right,
            params.top - (top + _EDGE_PAD) / height if top > _SLACK else params.top,
        ]
        if moved[0] >= moved[2] or moved[1] >= moved[3]:
            return False
        figure.subplots_adjust(left=moved[0], bottom=moved[1], right=moved[2], top=moved[3])
    return max(_overhang(figure)) <= _SLACK


def save_figure(
    figure: Figure, path: str | os.PathLike[str], *, tight: bool = True, dpi: float | None = None
) -> None:
    """Lays ``figure`` out (``tight_layout`` unless ``tight`` is False) and writes it to ``path``
    in the format of its suffix (:func:`figure_format`: PNG, PDF or SVG), atomically, at ``dpi``
    (the figure's own when None). Its texts are drawn as :func:`drawable_text` shows them. A
    figure whose texts or legend reach past its edges has its subplots moved in from those edges
    to make room, at its own size (grown to hold its drawing only where that cannot be done); a
    figure that fits is written as it is.

    Raises:
        InvalidArgumentError: ``path`` ends in a suffix other than those of
            :data:`FIGURE_SUFFIXES`; nothing is written.
    """
    refusal = figure_suffix_refusal(path)
    if refusal is not None:
        raise InvalidArgumentError(refusal)
    import matplotlib

    kind = figure_format(path)
    options: dict[str, Any] = {"format": kind, **({} if dpi is None else {"dpi": dpi})}
    if kind in _UNDATED:
        options["metadata"] = _UNDATED[kind]
    with (
        missing_glyphs_as_boxes(),
        _texts_drawable(),
        matplotlib.rc_context({"svg.hashsalt": "mazesim"}),
    ):
        if tight:
            figure.tight_layout()
        if not _make_room(figure):
            options.update(bbox_inches="tight", pad_inches=0.1)
        with atomic_file(path) as handle:
            figure.savefig(handle, **options)
