"""A project's own PROTO of the e-puck: the devices it adds to Webots' e-puck.

Webots reads a PROTO from the project's ``protos/`` folder before its own, so a project that
keeps its own ``E-puck.proto`` (often a copy of an older release with a GPS or a Compass added)
runs its controllers against that robot. mazesim simulates the e-puck itself; the devices such a
PROTO adds (named otherwise than the stock e-puck's) are put into the instance's ``turretSlot``,
where the import reads extension devices, so ``getDevice("gps")`` finds them as in Webots.
"""

from __future__ import annotations

import re

from mazesim.errors import WorldFormatError

from .definition import parse_definition
from .syntax import Field, Node, first_value, parse_nodes
from .templates import without_comments

__all__ = ["OWN_ROBOT_TYPES", "added_devices", "outermost", "with_devices"]

#: The core robot types whose project PROTO is read for added devices.
OWN_ROBOT_TYPES = frozenset({"E-puck", "EPuck"})
#: Sensor and radio nodes a PROTO may add that the import reads from an extension slot.
_DEVICE_TYPES = frozenset(
    "Accelerometer Camera Compass DistanceSensor Emitter GPS Gyro InertialUnit LED LightSensor "
    "Receiver TouchSensor".split()
)
#: The stock e-puck's own devices (Webots' E-puck PROTO, every release), named as there.
_STOCK_NAMES = frozenset(
    [f"ps{i}" for i in range(8)]
    + [f"ls{i}" for i in range(8)]
    + [f"led{i}" for i in range(10)]
    + [f"gs{i}" for i in range(3)]
    + ["camera", "emitter", "receiver", "accelerometer", "gyro", "tof", "speaker"]
    + ["left wheel motor", "right wheel motor", "left wheel sensor", "right wheel sensor"]
)
#: Template chunks (JavaScript ``%< >%``, Lua ``%{ }%``): left out before reading the nodes.
_TEMPLATE = re.compile(r"%<.*?>%|%\{.*?\}%", re.S)


def added_devices(proto_text: str, origin: str) -> list[tuple[str, str]]:
    """The devices the PROTO file adds to the stock e-puck: ``(name, node text)`` each, the
    node's text on one line without its ``#`` comments (on one line a comment would run to the
    instance's end); empty when it cannot be read."""
    try:
        body = parse_definition(proto_text, origin).body
        nodes = parse_nodes(_TEMPLATE.sub(" ", body), origin)
    except (WorldFormatError, ValueError):
        return []
    stripped = _TEMPLATE.sub(" ", body)
    found: list[tuple[str, str]] = []
    for node in outermost(nodes, _DEVICE_TYPES):
        text = stripped[node.start : node.end]
        name = first_value([node], "name", Field.string) or node.type_name.lower()
        if name not in _STOCK_NAMES and " IS " not in f" {text} ":
            found.append((name, " ".join(without_comments(text).split())))
    return found


def outermost(nodes: list[Node], types: frozenset[str]) -> list[Node]:
    """The nodes of those types (not ``USE``) in the trees, outermost first: none inside
    another."""
    found: list[Node] = []
    pending = list(reversed(nodes))
    while pending:
        node = pending.pop()
        if node.type_name in types and node.use_name is None:
            found.append(node)
            continue
        for item in reversed(node.fields):
            pending.extend(reversed(item.nodes))
    return found


def with_devices(text: str, node: Node, devices: list[tuple[str, str]]) -> tuple[int, str]:
    """Where to insert the devices into the instance ``node`` of ``text`` and what: into its
    ``turretSlot`` list, or a new ``turretSlot`` before its closing brace (never a line break,
    so the world's lines keep their numbers)."""
    nodes = " ".join(device for _, device in devices)
    slot = node.field("turretSlot")
    if slot is not None and text[slot.value_start : slot.value_end].rstrip().endswith("]"):
        close = text.rindex("]", slot.value_start, slot.value_end)
        return close, f" {nodes} "
    return node.end - 1, f" turretSlot [ {nodes} ] "
