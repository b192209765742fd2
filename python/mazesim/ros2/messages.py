"""ROS 2's message types, laid out as each distribution defines them.

The definitions come from ``rosbags`` (its type stores hold every message of ROS 2's standard
packages per distribution, with the REP-2011 type hashes); this module turns them into Cyclone
DDS types named as ROS 2 names them on the wire (``sensor_msgs/msg/Range`` is the DDS type
``sensor_msgs::msg::dds_::Range_``), so a topic the bridge creates is the topic a ROS 2 node of
that distribution creates.
"""

from __future__ import annotations

import functools
from typing import Any

from mazesim.errors import InvalidArgumentError, RegisteredName, _known_name, _shown
from mazesim.ros2._deps import require_ros2

__all__ = [
    "DISTROS",
    "check_distro",
    "dds_type_name",
    "idl_type",
    "type_hash",
    "typestore",
]

#: The ROS 2 distributions whose layouts the bridge speaks, oldest first.
DISTROS = ("humble", "jazzy")

#: rosbags' integer and float names -> the Cyclone DDS IDL type of the same name.
_NUMBERS = "int8 uint8 int16 uint16 int32 uint32 int64 uint64 float32 float64".split()


def check_distro(distro: RegisteredName) -> str:
    """Returns ``distro`` if the bridge knows its layouts.

    Raises:
        InvalidArgumentError: Another name.
    """
    return _known_name(distro, "a ROS 2 distribution", tuple(DISTROS))


@functools.cache
def typestore(distro: str) -> Any:
    """The ``rosbags`` type store of ``distro`` (every standard message definition)."""
    check_distro(distro)
    require_ros2()
    from rosbags.typesys import Stores, get_typestore

    return get_typestore(Stores[f"ROS2_{distro.upper()}"])


def dds_type_name(msgtype: str) -> str:
    """The DDS type name ROS 2 gives a message: ``pkg/msg/Name`` -> ``pkg::msg::dds_::Name_``."""
    package, kind, name = msgtype.split("/")
    return f"{package}::{kind}::dds_::{name}_"


def type_hash(distro: str, msgtype: str) -> str:
    """The REP-2011 type hash of ``msgtype`` in ``distro``, ``RIHS01_`` and 64 hex digits."""
    return str(typestore(distro).hash_rihs01(msgtype))


def _field_type(distro: str, node: tuple[Any, Any]) -> Any:
    import cyclonedds.idl.types as idl_types

    idl: Any = idl_types
    kind, detail = node
    kind = int(kind)
    if kind == 1:  # a base type: (name, string bound)
        name, bound = detail
        if name == "string":
            return idl.bounded_str[bound] if bound else str
        if name == "bool":
            return bool
        if name in ("byte", "char"):
            return idl.uint8
        if name in _NUMBERS:
            return getattr(idl, name)
        raise InvalidArgumentError(f"expected a ROS 2 base type; found {_shown(name)}")
    if kind == 2:  # another message
        return idl_type(distro, detail)
    element, size = detail
    if kind == 3:  # fixed-size array
        return idl.array[_field_type(distro, element), size]
    if kind == 4:  # sequence, bounded when size > 0
        inner = _field_type(distro, element)
        return idl.sequence[inner, size] if size else idl.sequence[inner]
    raise InvalidArgumentError(f"expected a ROS 2 field type; found node kind {kind}")


@functools.cache
def idl_type(distro: str, msgtype: str) -> Any:
    """The Cyclone DDS type of ``msgtype`` (``pkg/msg/Name``) as ``distro`` lays it out."""
    from cyclonedds.idl import make_idl_struct

    store = typestore(distro)
    if msgtype not in store.fielddefs:
        raise InvalidArgumentError(
            f"expected a message type of ROS 2 {distro}; found {_shown(msgtype)}, which it "
            "does not have"
        )
    _, fields = store.fielddefs[msgtype]
    annotations = {name: _field_type(distro, node) for name, node in fields}
    class_name = dds_type_name(msgtype).rsplit("::", 1)[1]
    return make_idl_struct(class_name, dds_type_name(msgtype), annotations)
