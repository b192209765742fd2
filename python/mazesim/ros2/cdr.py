"""ROS 2's wire encoding (plain CDR, little-endian, as ``rmw_cyclonedds_cpp`` writes it) of the
messages the bridge sends and receives, with :mod:`struct`.

Cyclone DDS's Python serializer takes 50-100 µs a message; these take a few, which is what lets
the bridge publish its whole topic set at thousands of steps per second. Every encoder is checked
against ``rosbags``' independent serializer (``tests/ros2/test_ros2_cdr.py``). Offsets are
aligned as CDR aligns them: from the start of the payload, after the 4-byte encapsulation header.
"""

from __future__ import annotations

import functools
import struct
from collections.abc import Sequence

from mazesim.errors import InvalidActionError

#: A message carries any double, NaN and infinities included (a LaserScan's ranges, REP 117):
#: the surface check lets them through to these encoders (``mazesim._checks``).
_takes_nan = True

__all__ = [
    "CdrReader",
    "CdrWriter",
    "Stamp",
    "Transform",
    "decode_clock",
    "decode_float64_array",
    "decode_string",
    "decode_twist",
    "decode_twist_stamped",
    "encode_clock",
    "encode_float64_multi_array",
    "encode_imu",
    "encode_joint_state",
    "encode_laser_scan",
    "encode_occupancy_grid",
    "encode_odometry",
    "encode_range",
    "encode_string",
    "encode_tf_message",
    "encode_twist",
    "encode_twist_stamped",
    "stamp_of",
]

#: ``(sec, nanosec)`` of a ``builtin_interfaces/msg/Time``.
Stamp = tuple[int, int]
#: A ``geometry_msgs/msg/TransformStamped``: stamp, parent frame, child frame, translation
#: ``(x, y, z)`` and rotation ``(x, y, z, w)``.
Transform = tuple[Stamp, str, str, tuple[float, float, float], tuple[float, float, float, float]]

#: The encapsulation header of plain CDR, little-endian (CDR_LE).
CDR_LE = b"\x00\x01\x00\x00"
_TIME = struct.Struct("<iI")
_U32 = struct.Struct("<I")
_ZERO36 = struct.Struct("<36d").pack(*([0.0] * 36))
_NANOSECONDS = 1_000_000_000
_POINT_QUATERNION = struct.Struct("<7d")
_VECTORS = struct.Struct("<6d")


def stamp_of(nanoseconds: int) -> Stamp:
    """The ``(sec, nanosec)`` of a time in nanoseconds."""
    return divmod(nanoseconds, _NANOSECONDS)


class CdrWriter:
    """Appends CDR fields to a message, aligning each as CDR does."""

    __slots__ = ("buffer",)

    def __init__(self) -> None:
        self.buffer = bytearray(CDR_LE)

    def align(self, size: int) -> None:
        """Pads with zeros to the next multiple of ``size`` bytes of the payload."""
        padding = -(len(self.buffer) - 4) % size
        if padding:
            self.buffer += bytes(padding)

    def pack(self, layout: struct.Struct, alignment: int, *values: float | int) -> None:
        """Appends ``values`` packed by ``layout``, aligned to ``alignment`` bytes."""
        self.align(alignment)
        self.buffer += layout.pack(*values)

    def string(self, text: str) -> None:
        """Appends a string: its length with the closing NUL, its UTF-8 bytes, the NUL."""
        data = text.encode()
        self.align(4)
        self.buffer += _U32.pack(len(data) + 1)
        self.buffer += data
        self.buffer += b"\x00"

    def header(self, stamp: Stamp, frame: str) -> None:
        """Appends a ``std_msgs/msg/Header``."""
        self.align(4)
        self.buffer += _TIME.pack(*stamp)
        self.string(frame)

    def bytes(self) -> bytes:
        """The message, padded to a multiple of 4 bytes as DDS sends it."""
        self.align(4)
        return bytes(self.buffer)


class _Layout:
    """Builds one :class:`struct.Struct` for a message whose strings and sequence lengths are
    known in advance, padding as CDR aligns (offsets from the start of the payload)."""

    def __init__(self) -> None:
        self.format = "<"
        self.offset = 0

    def field(self, code: str, size: int, alignment: int, count: int = 1) -> _Layout:
        padding = -self.offset % alignment
        if padding:
            self.format += f"{padding}x"
        self.format += f"{count}{code}" if count != 1 else code
        self.offset += padding + size * count
        return self

    def string(self, text: str) -> _Layout:
        """A string of fixed content: its length, then its bytes with the NUL (one ``s``)."""
        length = len(text.encode()) + 1
        self.field("I", 4, 4)
        self.format += f"{length}s"
        self.offset += length
        return self

    def header(self, frame: str) -> _Layout:
        return self.field("i", 4, 4).field("I", 4, 4).string(frame)

    def done(self) -> struct.Struct:
        padding = -self.offset % 4
        return struct.Struct(self.format + (f"{padding}x" if padding else ""))


@functools.cache
def _range_layout(frame: str, variance: bool) -> struct.Struct:
    return _Layout().header(frame).field("B", 1, 1).field("f", 4, 4, 5 if variance else 4).done()


def encode_clock(stamp: Stamp) -> bytes:
    """A ``rosgraph_msgs/msg/Clock``."""
    return CDR_LE + _TIME.pack(*stamp)


def encode_range(
    stamp: Stamp,
    frame: str,
    radiation_type: int,
    field_of_view: float,
    min_range: float,
    max_range: float,
    distance: float,
    variance: float | None,
) -> bytes:
    """A ``sensor_msgs/msg/Range``; ``variance`` is ``None`` for Humble, whose Range has none."""
    name = frame.encode()
    values = (radiation_type, field_of_view, min_range, max_range, distance)
    if variance is None:
        layout = _range_layout(frame, False)
        return CDR_LE + layout.pack(*stamp, len(name) + 1, name, *values)
    layout = _range_layout(frame, True)
    return CDR_LE + layout.pack(*stamp, len(name) + 1, name, *values, variance)


@functools.cache
def _scan_layout(frame: str, count: int) -> struct.Struct:
    return (
        _Layout().header(frame).field("f", 4, 4, 7).field("I", 4, 4).field("f", 4, 4, count)
        .field("I", 4, 4).done()
    )  # fmt: skip


def encode_laser_scan(
    stamp: Stamp,
    frame: str,
    angles: tuple[float, float, float],
    times: tuple[float, float],
    limits: tuple[float, float],
    ranges: Sequence[float],
) -> bytes:
    """A ``sensor_msgs/msg/LaserScan`` without intensities.

    Args:
        angles: ``angle_min``, ``angle_max``, ``angle_increment``.
        times: ``time_increment``, ``scan_time``.
        limits: ``range_min``, ``range_max``.
    """
    name = frame.encode()
    layout = _scan_layout(frame, len(ranges))
    return CDR_LE + layout.pack(
        *stamp, len(name) + 1, name, *angles, *times, *limits, len(ranges), *ranges, 0
    )


@functools.cache
def _odometry_layout(frame: str, child_frame: str) -> struct.Struct:
    return _Layout().header(frame).string(child_frame).field("d", 8, 8, 7).done()


def encode_odometry(
    stamp: Stamp,
    frame: str,
    child_frame: str,
    pose: tuple[float, float, float, float, float, float, float],
    twist: tuple[float, float, float, float, float, float],
) -> bytes:
    """A ``nav_msgs/msg/Odometry`` with zero covariances.

    Args:
        pose: Position ``x, y, z`` then orientation ``x, y, z, w``.
        twist: Linear ``x, y, z`` then angular ``x, y, z``.
    """
    name, child = frame.encode(), child_frame.encode()
    layout = _odometry_layout(frame, child_frame)
    # The layout ends 8-aligned (7 doubles after 8-aligned padding), so the rest follows as is.
    return b"".join(
        (
            CDR_LE,
            layout.pack(*stamp, len(name) + 1, name, len(child) + 1, child, *pose),
            _ZERO36,
            _VECTORS.pack(*twist),
            _ZERO36,
        )
    )


_QUATERNION = struct.Struct("<4d")
_VECTOR = struct.Struct("<3d")
_ZERO9 = struct.Struct("<9d").pack(*([0.0] * 9))


def encode_imu(
    stamp: Stamp,
    frame: str,
    orientation: tuple[float, float, float, float],
    angular_velocity: tuple[float, float, float],
    linear_acceleration: tuple[float, float, float],
) -> bytes:
    """A ``sensor_msgs/msg/Imu`` with zero covariances (unknown)."""
    writer = CdrWriter()
    writer.header(stamp, frame)
    writer.pack(_QUATERNION, 8, *orientation)
    writer.buffer += _ZERO9
    writer.buffer += _VECTOR.pack(*angular_velocity)
    writer.buffer += _ZERO9
    writer.buffer += _VECTOR.pack(*linear_acceleration)
    writer.buffer += _ZERO9
    return writer.bytes()


_MAP_INFO = struct.Struct("<iIfII")


def encode_occupancy_grid(
    stamp: Stamp,
    frame: str,
    resolution: float,
    size: tuple[int, int],
    origin: tuple[float, float, float, float, float, float, float],
    cells: bytes,
) -> bytes:
    """A ``nav_msgs/msg/OccupancyGrid``.

    Args:
        stamp: The header's stamp and the map's load time.
        resolution: Metres a cell.
        size: Width (cells along x) and height (along y).
        origin: The pose of cell (0, 0)'s corner: position ``x, y, z``, orientation ``x, y, z,
            w``.
        cells: Row-major, from the origin along x, one signed byte a cell (0 free, 100
            occupied, -1 unknown).
    """
    writer = CdrWriter()
    writer.header(stamp, frame)
    writer.pack(_MAP_INFO, 4, *stamp, resolution, *size)
    writer.pack(_POINT_QUATERNION, 8, *origin)
    writer.pack(_U32, 4, len(cells))
    writer.buffer += cells
    return writer.bytes()


@functools.cache
def _transform_layout(parent: str, child: str) -> struct.Struct:
    return _Layout().field("I", 4, 4).header(parent).string(child).field("d", 8, 8, 7).done()


def encode_tf_message(transforms: Sequence[Transform]) -> bytes:
    """A ``tf2_msgs/msg/TFMessage``."""
    if len(transforms) == 1:
        stamp, parent, child, translation, rotation = transforms[0]
        names = parent.encode(), child.encode()
        return CDR_LE + _transform_layout(parent, child).pack(
            1, *stamp, len(names[0]) + 1, names[0], len(names[1]) + 1, names[1],
            *translation, *rotation,
        )  # fmt: skip
    writer = CdrWriter()
    writer.pack(_U32, 4, len(transforms))
    for stamp, parent, child, translation, rotation in transforms:
        writer.header(stamp, parent)
        writer.string(child)
        writer.pack(_POINT_QUATERNION, 8, *translation, *rotation)
    return writer.bytes()


@functools.cache
def _array_layout(label: str | None, count: int) -> struct.Struct:
    layout = _Layout()
    if label is not None:
        layout.field("I", 4, 4).string(label).field("I", 4, 4, 2)
    else:
        layout.field("I", 4, 4)
    layout.field("I", 4, 4).field("I", 4, 4)
    if count:
        layout.field("d", 8, 8, count)
    return layout.done()


def encode_float64_multi_array(labels: Sequence[str], data: Sequence[float]) -> bytes:
    """A ``std_msgs/msg/Float64MultiArray`` of one dimension, labelled ``,``-joined ``labels``
    (no dimension when ``labels`` is empty)."""
    label = ",".join(labels) if labels else None
    layout = _array_layout(label, len(data))
    count = len(data)
    if label is not None:
        text = label.encode()
        return CDR_LE + layout.pack(1, len(text) + 1, text, count, count, 0, count, *data)
    return CDR_LE + layout.pack(0, 0, count, *data)


def encode_joint_state(
    stamp: Stamp,
    names: Sequence[str],
    positions: Sequence[float],
    velocities: Sequence[float],
) -> bytes:
    """A ``sensor_msgs/msg/JointState`` with no frame and no efforts."""
    writer = CdrWriter()
    writer.header(stamp, "")
    writer.pack(_U32, 4, len(names))
    for name in names:
        writer.string(name)
    for values in (positions, velocities):
        writer.pack(_U32, 4, len(values))
        if values:
            writer.pack(struct.Struct(f"<{len(values)}d"), 8, *values)
    writer.pack(_U32, 4, 0)
    return writer.bytes()


def encode_string(text: str) -> bytes:
    """A ``std_msgs/msg/String``."""
    writer = CdrWriter()
    writer.string(text)
    return writer.bytes()


def encode_twist(linear: Sequence[float], angular: Sequence[float]) -> bytes:
    """A ``geometry_msgs/msg/Twist``."""
    return CDR_LE + _VECTORS.pack(*linear, *angular)


def encode_twist_stamped(
    stamp: Stamp, frame: str, linear: Sequence[float], angular: Sequence[float]
) -> bytes:
    """A ``geometry_msgs/msg/TwistStamped``."""
    writer = CdrWriter()
    writer.header(stamp, frame)
    writer.pack(_VECTORS, 8, *linear, *angular)
    return writer.bytes()


class _Reader:
    """Reads CDR fields of either byte order, aligning as CDR does."""

    __slots__ = ("data", "order", "offset")

    def __init__(self, data: bytes, what: str) -> None:
        if len(data) < 4 or data[0] != 0 or data[1] not in (0, 1):
            raise InvalidActionError(
                f"expected a {what} in plain CDR (encapsulation 00 00 or 00 01); found "
                f"{bytes(data[:4]).hex(' ') or 'no bytes'}"
            )
        self.data = data
        self.order = "<" if data[1] == 1 else ">"
        self.offset = 4

    def unpack(self, layout: str, alignment: int) -> tuple[float | int, ...]:
        self.offset += -(self.offset - 4) % alignment
        result = struct.unpack_from(self.order + layout, self.data, self.offset)
        self.offset += struct.calcsize(self.order + layout)
        return result

    def string(self) -> str:
        (length,) = self.unpack("I", 4)
        start = self.offset
        self.offset += int(length)
        raw = bytes(self.data[start : self.offset])
        # The length counts the closing NUL: only that one is dropped (the text may hold NULs).
        return (raw[:-1] if raw.endswith(b"\x00") else raw).decode()


#: Reads the fields of a message of any layout, field by field.
CdrReader = _Reader


def decode_clock(data: bytes) -> int:
    """The time of a ``rosgraph_msgs/msg/Clock``, in nanoseconds.

    Raises:
        InvalidActionError: The bytes are not a Clock.
    """
    reader = _Reader(data, "rosgraph_msgs/msg/Clock")
    try:
        sec, nanosec = reader.unpack("iI", 4)
    except struct.error as error:
        raise InvalidActionError(f"expected a Clock of 8 bytes; found {len(data) - 4}") from error
    return int(sec) * _NANOSECONDS + int(nanosec)


def decode_twist(data: bytes) -> tuple[float, float]:
    """``linear.x`` and ``angular.z`` of a ``geometry_msgs/msg/Twist``.

    Raises:
        InvalidActionError: The bytes are not a Twist.
    """
    reader = _Reader(data, "geometry_msgs/msg/Twist")
    try:
        values = reader.unpack("6d", 8)
    except struct.error as error:
        raise InvalidActionError(f"expected a Twist of 48 bytes; found {len(data) - 4}") from error
    return float(values[0]), float(values[5])


def decode_twist_stamped(data: bytes) -> tuple[float, float]:
    """``twist.linear.x`` and ``twist.angular.z`` of a ``geometry_msgs/msg/TwistStamped``.

    Raises:
        InvalidActionError: The bytes are not a TwistStamped.
    """
    reader = _Reader(data, "geometry_msgs/msg/TwistStamped")
    try:
        reader.unpack("iI", 4)
        reader.string()
        values = reader.unpack("6d", 8)
    except (struct.error, UnicodeDecodeError) as error:
        raise InvalidActionError(f"expected a TwistStamped; found {len(data)} bytes") from error
    return float(values[0]), float(values[5])


def decode_float64_array(data: bytes) -> list[float]:
    """The ``data`` of a ``std_msgs/msg/Float64MultiArray``.

    Raises:
        InvalidActionError: The bytes are not a Float64MultiArray.
    """
    reader = _Reader(data, "std_msgs/msg/Float64MultiArray")
    try:
        (dimensions,) = reader.unpack("I", 4)
        for _ in range(int(dimensions)):
            reader.string()
            reader.unpack("II", 4)
        reader.unpack("I", 4)
        (count,) = reader.unpack("I", 4)
        return [float(value) for value in reader.unpack(f"{int(count)}d", 8)] if count else []
    except (struct.error, UnicodeDecodeError) as error:
        raise InvalidActionError(
            f"expected a Float64MultiArray; found {len(data)} bytes that do not decode as one"
        ) from error


def decode_string(data: bytes) -> str:
    """The ``data`` of a ``std_msgs/msg/String``.

    Raises:
        InvalidActionError: The bytes are not a String.
    """
    reader = _Reader(data, "std_msgs/msg/String")
    try:
        return reader.string()
    except (struct.error, UnicodeDecodeError) as error:
        raise InvalidActionError(f"expected a String; found {len(data)} bytes") from error
