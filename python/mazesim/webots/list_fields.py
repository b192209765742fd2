"""A node's list fields of values (Webots' ``MFString``, ``MFFloat``, ``MFVec3f``... fields):
what a supervisor reads, sets, inserts and removes by index.

A world file writes a list field in brackets (``url [ "a.png" ]``, ``lookupTable [ 0 0 0, 0.1
1000 0 ]``) and does not say its type: the type is the one the node's definition gives it, here
the PROTO's interface (a project's PROTO read from its file, :mod:`mazesim.webots.proto_fields`)
or Webots' reference manual for the base nodes (:data:`BASE_LIST_KINDS`), else what the values
are (strings an ``MFString``, ``TRUE``/``FALSE`` an ``MFBool``, numbers an ``MFFloat``). A
field's items are kept as Python values (a vector as a list of floats); a supervisor's change
is kept in its scene tree (a later read gives it) and changes nothing simulated: the distance
sensors' ``lookupTable`` stays the one the world was imported with.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

from mazesim.webots.devices import _print_error

if TYPE_CHECKING:
    from mazesim.webots.supervisor import Node

__all__ = ["BASE_LIST_KINDS", "LIST_TYPES", "ListFieldValues", "list_items", "list_kind"]

#: Each list kind's ``Field`` type constant and how many numbers an item holds (-2 a string,
#: -1 a flag, 0 a whole number, 1 a number): Webots' reference manual, Field.
LIST_TYPES: dict[str, tuple[int, int]] = {
    "MFBool": (0x11, -1),
    "MFInt32": (0x12, 0),
    "MFFloat": (0x13, 1),
    "MFVec2f": (0x14, 2),
    "MFVec3f": (0x15, 3),
    "MFRotation": (0x16, 4),
    "MFColor": (0x17, 3),
    "MFString": (0x18, -2),
}

#: The list fields of Webots' base nodes by (node type, field) (Webots' reference manual: Robot,
#: WorldInfo, ImageTexture, Background, Mesh, the sensors with a ``lookupTable``, Coordinate,
#: TextureCoordinate, Normal, Color, LED, ElevationGrid, IndexedFaceSet, IndexedLineSet,
#: Extrusion, ContactProperties); ``"*"`` for a field of that name in every node that has it.
BASE_LIST_KINDS: dict[tuple[str, str], str] = {
    ("*", "url"): "MFString",
    ("*", "controllerArgs"): "MFString",
    ("WorldInfo", "info"): "MFString",
    ("*", "lookupTable"): "MFVec3f",
    **{
        ("Background", f"{side}{kind}Url"): "MFString"
        for side in ("back", "bottom", "front", "left", "right", "top")
        for kind in ("", "Irradiance")
    },
    ("Background", "skyColor"): "MFColor",
    ("Coordinate", "point"): "MFVec3f",
    ("TextureCoordinate", "point"): "MFVec2f",
    ("Normal", "vector"): "MFVec3f",
    ("Color", "color"): "MFColor",
    ("LED", "color"): "MFColor",
    ("ElevationGrid", "height"): "MFFloat",
    ("IndexedFaceSet", "coordIndex"): "MFInt32",
    ("IndexedFaceSet", "texCoordIndex"): "MFInt32",
    ("IndexedFaceSet", "normalIndex"): "MFInt32",
    ("IndexedLineSet", "coordIndex"): "MFInt32",
    ("Extrusion", "crossSection"): "MFVec2f",
    ("Extrusion", "spine"): "MFVec3f",
    ("Extrusion", "scale"): "MFVec2f",
    ("Extrusion", "orientation"): "MFRotation",
    ("ContactProperties", "coulombFriction"): "MFFloat",
    ("ContactProperties", "forceDependentSlip"): "MFFloat",
}


def list_kind(
    types: Sequence[str], name: str, values: Sequence[Any], declared: dict[str, str]
) -> str | None:
    """The list kind (``"MFString"``...) of a node's bracketed field ``name``: the one its PROTO
    declares (``declared``, by field), else the base node's (``types``: the node's type and the
    base type it derives from), else by its values; None for values of mixed kinds or for an
    empty list of neither."""
    if name in declared:
        return declared[name] if declared[name] in LIST_TYPES else None
    for type_name in (*types, "*"):
        if (type_name, name) in BASE_LIST_KINDS:
            return BASE_LIST_KINDS[(type_name, name)]
    if not values:
        return None  # an empty list (``children [ ]`` too) says nothing of its kind
    if all(isinstance(v, str) for v in values):
        return "MFString"
    if all(isinstance(v, bool) for v in values):
        return "MFBool"
    if all(isinstance(v, float) and not isinstance(v, bool) for v in values):
        return "MFFloat"
    return None


def list_items(kind: str, values: Sequence[Any]) -> list[Any]:
    """A list field's items from the values the file writes in its brackets, in order: strings,
    flags, whole numbers, numbers, or lists of numbers (a vector, a colour, a rotation); a
    value of another kind, and an incomplete vector at the end, are left out."""
    size = LIST_TYPES[kind][1]
    if size == -2:
        return [v for v in values if isinstance(v, str)]
    if size == -1:
        return [v for v in values if isinstance(v, bool)]
    numbers = [float(v) for v in values if isinstance(v, (int, float)) and not isinstance(v, bool)]
    if size == 0:
        return [int(v) for v in numbers if v.is_integer()]
    if size == 1:
        return numbers
    return [numbers[i : i + size] for i in range(0, len(numbers) - size + 1, size)]


class ListFieldValues:
    """The ``Field`` methods of a list field of values (mixed into
    :class:`~mazesim.webots.field.Field`): each reads, sets or inserts one item by index
    (negative: from the end, as in Webots), and prints Webots' error for a field of another
    type or an index out of range, where the getter gives Webots' default (0, 0.0, False, or
    None for a vector or a string)."""

    _node: Node
    _name: str
    _type: int
    #: Prints Webots' error for a call on a field of another type (the Field's own).
    _wrong: Callable[[str], None]

    def _items(self, kind: str, function: str) -> list[Any] | None:
        """The field's items when it is a list of ``kind``, else None after Webots' error."""
        kept = self._node._lists.get(self._name)
        if kept is None or LIST_TYPES[kind][0] != self._type:
            self._wrong(function)
            return None
        return kept

    def _at(self, items: list[Any], index: int, function: str, inserting: bool = False) -> int:
        """The position of ``index`` among ``items`` (-1 after Webots' error when out of
        range); an insertion may be at the end (``len``, or -1 counted from it)."""
        count = len(items) + (1 if inserting else 0)
        at = int(index)
        if not -count <= at < count:
            _print_error(
                f"Error: wb_supervisor_field_{function}() called with an out of range index: "
                f"{index}."
            )
            return -1
        return at % count

    def _get(self, kind: str, index: int, default: Any) -> Any:
        function = f"get_mf_{kind[2:].lower()}"
        items = self._items(kind, function)
        at = -1 if items is None else self._at(items, index, function)
        if items is None or at < 0:
            return default
        item = items[at]
        return list(item) if isinstance(item, list) else item

    def _value(self, kind: str, value: Any, function: str) -> Any:
        from mazesim.webots.field import field_value

        size = LIST_TYPES[kind][1]
        checked = field_value(value, size, f"Field.{function}")
        return checked[0] if size in (0, 1) else checked

    def _set(self, kind: str, index: int, value: Any, inserting: bool = False) -> None:
        verb = "insert" if inserting else "set"
        call = f"{verb}MF{kind[2:]}"
        checked = self._value(kind, value, call)
        function = f"{verb}_mf_{kind[2:].lower()}"
        items = self._items(kind, function)
        at = -1 if items is None else self._at(items, index, function, inserting)
        if items is None or at < 0:
            return
        if inserting:
            items.insert(at, checked)
        else:
            items[at] = checked

    def _remove_item(self, index: int) -> None:
        """Removes the item at ``index`` of a list field of values."""
        items = self._node._lists[self._name]
        at = self._at(items, index, "remove_mf")
        if at >= 0:
            del items[at]

    def getMFBool(self, index: int) -> bool:
        """The flag at ``index`` of an ``MFBool`` field."""
        return bool(self._get("MFBool", index, False))

    def getMFInt32(self, index: int) -> int:
        """The whole number at ``index`` of an ``MFInt32`` field."""
        return int(self._get("MFInt32", index, 0))

    def getMFFloat(self, index: int) -> float:
        """The number at ``index`` of an ``MFFloat`` field."""
        return float(self._get("MFFloat", index, 0.0))

    def getMFVec2f(self, index: int) -> list[float] | None:
        """The two numbers at ``index`` of an ``MFVec2f`` field."""
        return self._get("MFVec2f", index, None)

    def getMFVec3f(self, index: int) -> list[float] | None:
        """The three numbers at ``index`` of an ``MFVec3f`` field (a ``lookupTable`` row)."""
        return self._get("MFVec3f", index, None)

    def getMFRotation(self, index: int) -> list[float] | None:
        """The axis and angle at ``index`` of an ``MFRotation`` field."""
        return self._get("MFRotation", index, None)

    def getMFColor(self, index: int) -> list[float] | None:
        """The colour at ``index`` of an ``MFColor`` field."""
        return self._get("MFColor", index, None)

    def getMFString(self, index: int) -> str | None:
        """The string at ``index`` of an ``MFString`` field (an ImageTexture's ``url``)."""
        return self._get("MFString", index, None)

    def setMFBool(self, index: int, value: bool) -> None:
        """Sets the flag at ``index`` of an ``MFBool`` field."""
        self._set("MFBool", index, value)

    def setMFInt32(self, index: int, value: int) -> None:
        """Sets the whole number at ``index`` of an ``MFInt32`` field."""
        self._set("MFInt32", index, value)

    def setMFFloat(self, index: int, value: float) -> None:
        """Sets the number at ``index`` of an ``MFFloat`` field."""
        self._set("MFFloat", index, value)

    def setMFVec2f(self, index: int, values: list[float]) -> None:
        """Sets the two numbers at ``index`` of an ``MFVec2f`` field."""
        self._set("MFVec2f", index, values)

    def setMFVec3f(self, index: int, values: list[float]) -> None:
        """Sets the three numbers at ``index`` of an ``MFVec3f`` field (a ``lookupTable`` row
        is kept; the distance sensors keep the table they were imported with)."""
        self._set("MFVec3f", index, values)

    def setMFRotation(self, index: int, values: list[float]) -> None:
        """Sets the axis and angle at ``index`` of an ``MFRotation`` field."""
        self._set("MFRotation", index, values)

    def setMFColor(self, index: int, values: list[float]) -> None:
        """Sets the colour at ``index`` of an ``MFColor`` field."""
        self._set("MFColor", index, values)

    def setMFString(self, index: int, value: str) -> None:
        """Sets the string at ``index`` of an ``MFString`` field."""
        self._set("MFString", index, value)

    def insertMFBool(self, index: int, value: bool) -> None:
        """Inserts a flag at ``index`` of an ``MFBool`` field (-1: at the end)."""
        self._set("MFBool", index, value, inserting=True)

    def insertMFInt32(self, index: int, value: int) -> None:
        """Inserts a whole number at ``index`` of an ``MFInt32`` field (-1: at the end)."""
        self._set("MFInt32", index, value, inserting=True)

    def insertMFFloat(self, index: int, value: float) -> None:
        """Inserts a number at ``index`` of an ``MFFloat`` field (-1: at the end)."""
        self._set("MFFloat", index, value, inserting=True)

    def insertMFVec2f(self, index: int, values: list[float]) -> None:
        """Inserts two numbers at ``index`` of an ``MFVec2f`` field (-1: at the end)."""
        self._set("MFVec2f", index, values, inserting=True)

    def insertMFVec3f(self, index: int, values: list[float]) -> None:
        """Inserts three numbers at ``index`` of an ``MFVec3f`` field (-1: at the end)."""
        self._set("MFVec3f", index, values, inserting=True)

    def insertMFRotation(self, index: int, values: list[float]) -> None:
        """Inserts an axis and angle at ``index`` of an ``MFRotation`` field (-1: at the end)."""
        self._set("MFRotation", index, values, inserting=True)

    def insertMFColor(self, index: int, values: list[float]) -> None:
        """Inserts a colour at ``index`` of an ``MFColor`` field (-1: at the end)."""
        self._set("MFColor", index, values, inserting=True)

    def insertMFString(self, index: int, value: str) -> None:
        """Inserts a string at ``index`` of an ``MFString`` field (-1: at the end)."""
        self._set("MFString", index, value, inserting=True)
