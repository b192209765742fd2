"""Webots' renaming of a Solid a supervisor imports beside one of the same name.

Webots keeps the names of the top-level Solids (a robot is one) apart: a world file whose two
Solids share a name is read with a warning, but a node a supervisor imports
(``importMFNodeFromString``) whose name a sibling already has is renamed at once, ``NAME(N)``
with the smallest N from 1 that no sibling ``NAME(k)`` has (``WbNodeOperations::
resolveSolidNameClashIfNeeded`` and ``WbSolid::resolveNameClashIfNeeded``, Webots' sources,
Apache-2.0; facts only). Three E-pucks a swarm's supervisor imports without a ``name`` beside
the world's ``e-puck`` are ``e-puck(1)``, ``e-puck(2)`` and ``e-puck(3)``: their controllers
tell each other apart by ``getName()``.

:func:`unique_names` writes that renaming into the imported text, so that the robot's name,
its node's ``name`` field and the run's summary all have it.
"""

from __future__ import annotations

import re
from collections.abc import Iterable

from mazesim.errors import MazesimError
from mazesim.webots.proto.syntax import Field, Node, first_value, parse_nodes
from mazesim.webots.proto_fields import declared_fields
from mazesim.webots.scene import BASE_NAMES

__all__ = ["default_name", "unique_names"]


def default_name(type_name: str) -> str | None:
    """The ``name`` a node of ``type_name`` has when it writes none: its PROTO's declared
    default, or a base Solid type's; None when mazesim does not know it."""
    return declared_fields(type_name).strings.get("name") or BASE_NAMES.get(type_name)


def unique_names(text: str, taken: Iterable[str]) -> str:
    """``text`` (nodes a supervisor imports at the top of the scene) with each top-level node
    whose name clashes with one of ``taken`` (its siblings' names) or with an earlier node of
    the text renamed as Webots renames it; unchanged when it does not parse (the import says
    why) or no name clashes."""
    try:
        nodes = parse_nodes(text, "<imported>", max_depth=None)
    except MazesimError:
        return text
    names = set(taken)
    edits: list[tuple[int, int, str]] = []
    for node in nodes:
        if node.use_name is not None:
            continue
        written = first_value([node], "name", Field.string)
        name = written if written is not None else default_name(node.type_name)
        if name is None:
            continue
        if name in names:
            name = _renamed(name, names)
            edits.append(_edit(text, node, name, written is not None))
        names.add(name)
    for start, end, replacement in sorted(edits, reverse=True):
        text = text[:start] + replacement + text[end:]
    return text


def _renamed(name: str, names: set[str]) -> str:
    """``name`` without its ``(N)``, followed by the smallest index from 1 after which no name
    of ``names`` of that form is numbered without a gap (Webots' "first available index")."""
    match = re.fullmatch(r"(.+)\(\d+\)", name)
    base = match.group(1) if match else name
    pattern = re.compile(re.escape(base) + r"\((\d+)\)")
    indices = sorted(int(m.group(1)) for n in names if (m := pattern.fullmatch(n)))
    index = 1
    for used in indices:
        if used != index:
            break
        index += 1
    return f"{base}({index})"


def _edit(text: str, node: Node, name: str, written: bool) -> tuple[int, int, str]:
    """The span of ``text`` to replace, and by what, to give ``node`` the ``name``: its
    ``name`` field's string, or a field written after its opening brace."""
    # Names are kept as the file writes them (escapes and all): quoted as they are.
    quoted = f'"{name}"'
    if written:
        item = node.field("name")
        token = next(t for t in item.tokens if t.kind == "string") if item else None
        if token is not None:
            return token.start, token.end, quoted
    brace = text.index("{", node.type_start) + 1
    return brace, brace, f" name {quoted}"
