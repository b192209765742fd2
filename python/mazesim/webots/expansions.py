"""The expanded text of the world files imported in this process, by their text: what a
project's own robot PROTO builds (its body's sensors with their tables and poses, its
``customData`` and ``battery`` defaults...) is in the expansion, not in the file.

The import (:func:`mazesim.webots.importer.import_wbt_text`) remembers each expansion; the
scene (:mod:`mazesim.webots.scene`) reads a robot node that is a PROTO instance from it, on the
same line (the expansion keeps each instance on its own line). A text never imported here has
no expansion: its robot is read as the file writes it.

The import also leaves the interfaces of the PROTOs it read from files (a project's
``Victim.proto``): a supervisor's ``getField`` of a field an instance leaves out finds it at
the PROTO's default, as in Webots (:func:`mazesim.webots.proto_fields.declared_fields`). They
are those of the world imported last in the process (a run imports one world, and the
supervisor's edits of it, which declare the same PROTOs).
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Mapping

from mazesim.webots.proto.definition import FieldDeclaration
from mazesim.webots.proto.syntax import unix_line_ends

__all__ = ["expanded_of", "interface_of", "remember"]

#: How many world texts are remembered (a run imports its world, and a supervisor's edits of
#: it, a few times over).
KEPT = 8

_expansions: OrderedDict[str, str] = OrderedDict()
#: The PROTO interfaces of the world imported last, by PROTO name.
_interfaces: dict[str, Mapping[str, FieldDeclaration]] = {}


def _key(text: str) -> str:
    """A world text as the import and the scene both count its lines."""
    return unix_line_ends(text).lstrip("\ufeff")


def remember(
    text: str,
    expanded: str,
    interfaces: Mapping[str, Mapping[str, FieldDeclaration]] | None = None,
) -> None:
    """Keeps ``expanded``, the expansion of the world text ``text`` (the newest
    :data:`KEPT`), and ``interfaces``, the fields of the PROTOs it read, by PROTO name (in
    place of the last world's)."""
    _interfaces.clear()
    _interfaces.update(interfaces or {})
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


def interface_of(type_name: str) -> Mapping[str, FieldDeclaration] | None:
    """The fields the PROTO ``type_name`` declares, as the world imported last read it from
    its file, or None (a built-in node, a PROTO that import did not read)."""
    return _interfaces.get(type_name)
