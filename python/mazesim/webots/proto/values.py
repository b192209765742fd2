"""PROTO field values as templates see them: VRML text turned into numbers, strings, vectors
(``{x, y, z}``), colours (``{r, g, b}``), rotations (``{x, y, z, a}``), nodes
(``{node_name, fields}``) and arrays for ``MF`` types, as Webots' template documentation says."""

from __future__ import annotations

import json
import math
from typing import Any

from .syntax import Field, Node, Token, parse_nodes

__all__ = ["field_value"]

_KEYS = {
    "Vec2f": ("x", "y"),
    "Vec3f": ("x", "y", "z"),
    "Color": ("r", "g", "b"),
    "Rotation": ("x", "y", "z", "a"),
}


def _parse_value(text: str) -> Field | None:
    nodes = parse_nodes(f"V {{ value {text} }}", "<field value>")
    return nodes[0].field("value") if nodes else None


def _scalars(tokens: list[Token]) -> list[Any]:
    return [token.value() for token in tokens if token.kind in ("string", "word")]


def _node_value(node: Node) -> dict[str, Any]:
    fields: dict[str, Any] = {}
    for item in node.fields:
        if item.nodes:
            converted = [_node_value(n) for n in item.nodes]
            bracketed = any(t.kind == "[" for t in item.tokens)
            fields[item.name] = converted if bracketed else converted[0]
            continue
        scalars = _scalars(item.tokens)
        keys = {2: _KEYS["Vec2f"], 3: _KEYS["Vec3f"], 4: _KEYS["Rotation"]}.get(len(scalars))
        if item.name.lower().endswith("color") and len(scalars) == 3:
            keys = _KEYS["Color"]
        if keys and all(isinstance(s, float) for s in scalars):
            fields[item.name] = dict(zip(keys, scalars))
        elif len(scalars) == 1:
            fields[item.name] = scalars[0]
        else:
            fields[item.name] = scalars
    return {"node_name": node.type_name, "fields": fields}


def field_value(kind: str, text: str) -> Any:
    """The template value of a field of VRML type ``kind`` written as ``text``."""
    parsed = _parse_value(text) if text.strip() else None
    single = kind.startswith("SF")
    base = kind[2:]
    if parsed is None:
        return None if single else []
    if base == "Node":
        nodes = [_node_value(n) for n in parsed.nodes]
        return (nodes[0] if nodes else None) if single else nodes
    scalars = [s for s in _scalars(parsed.tokens)]
    if base in ("Int32", "Float"):
        numbers = [_whole(s) if base == "Int32" else s for s in scalars if isinstance(s, float)]
        return (numbers[0] if numbers else 0) if single else numbers
    if base == "Bool":
        flags = [bool(s) for s in scalars if isinstance(s, bool)]
        return (flags[0] if flags else False) if single else flags
    if base == "String":
        strings = [s for s in scalars if isinstance(s, str)]
        return (strings[0] if strings else "") if single else strings
    keys = _KEYS.get(base)
    if keys is None:
        return scalars[0] if single and scalars else scalars
    numbers = [s for s in scalars if isinstance(s, float)]
    groups = [
        dict(zip(keys, numbers[i : i + len(keys)])) for i in range(0, len(numbers), len(keys))
    ]
    groups = [g for g in groups if len(g) == len(keys)]
    return (groups[0] if groups else dict.fromkeys(keys, 0.0)) if single else groups


def _whole(number: float) -> int:
    """An SFInt32 field's value (a number written with a fraction is cut to its whole part).

    Raises:
        ValueError: The number is not finite (``nan``, ``inf``, ``1e400``).
    """
    if not math.isfinite(number):
        raise ValueError(f"an SFInt32 field: expected a whole number, found {number}")
    return int(number)


def to_javascript(value: Any) -> str:
    """A JavaScript literal of a template value (None is ``undefined``, as for a NULL node)."""
    if value is None:
        return "undefined"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value) if value == value and abs(value) != float("inf") else "0"
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, list):
        return "[" + ", ".join(to_javascript(v) for v in value) + "]"
    items = ", ".join(f"{json.dumps(str(k))}: {to_javascript(v)}" for k, v in value.items())
    return "{" + items + "}"


def to_lua(value: Any) -> str:
    """A Lua literal of a template value (None is ``nil``; arrays count from 1)."""
    if value is None:
        return "nil"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value) if value == value and abs(value) != float("inf") else "0"
    if isinstance(value, str):
        escaped = value.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")
        return f'"{escaped}"'
    if isinstance(value, list):
        return "{" + ", ".join(to_lua(v) for v in value) + "}"
    items = ", ".join(f"[{to_lua(str(k))}] = {to_lua(v)}" for k, v in value.items())
    return "{" + items + "}"
