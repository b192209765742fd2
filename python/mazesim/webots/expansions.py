"""The expanded text of the world files imported in this process, by their text: what a
project's own robot PROTO builds (its body's sensors with their tables and poses, its
``customData`` and ``battery`` defaults...) is in the expansion, not in the file.

The import (:func:`mazesim.webots.importer.import_wbt_text`) remembers each expansion; the
scene (:mod:`mazesim.webots.scene`) reads a robot node that is a PROTO instance from it, on the
same line (the expansion keeps each instance on its own line). A text never imported here has
no expansion: its robot is read as the file writes it.
"""

from __future__ import annotations

from collections import OrderedDict

from mazesim.webots.proto.syntax import unix_line_ends

__all__ = ["expanded_of", "remember"]

#: How many world texts are remembered (a run imports its world, and a supervisor's edits of
#: it, a few times over).
KEPT = 8

_expansions: OrderedDict[str, str] = OrderedDict()


def _key(text: str) -> str:
    """A world text as the import and the scene both count its lines."""
    return unix_line_ends(text).lstrip("\ufeff")


def remember(text: str, expanded: str) -> None:
    """Keeps ``expanded``, the expansion of the world text ``text`` (the newest
    :data:`KEPT`)."""
    key = _key(text)
    if key == expanded:
        return
    _expansions[key] = expanded
    _expansions.move_to_end(key)
    while len(_expansions) > KEPT:
        _expansions.popitem(last=False)


def expanded_of(text: str) -> str | None:
    """The expansion of the world text ``text`` an import in this process made, or None (the
    text was not imported here, or it has no PROTO instance to expand)."""
    return _expansions.get(_key(text))
