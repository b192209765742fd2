"""Webots' ``Emitter`` and ``Receiver`` devices, carried by the world's
:class:`~mazesim.webots.radio.Radio`.

The e-puck's own ``emitter`` and ``receiver`` use the E-puck PROTO's channel 1, no range limit
and the type "radio" (the PROTO's Emitter and Receiver set only their ``channel``, so their
``range`` and ``type`` are the nodes' defaults, -1 and "radio");
an Emitter or Receiver node of the world file (in an extension slot, or among a robot's children)
brings its own ``channel``, ``range``, ``maxRange`` and ``bufferSize`` fields, and its ``type``
and ``aperture``, with the node's defaults (channel 0, range -1, unlimited buffers, "radio",
aperture -1) where the file gives none. An infra-red device's ``aperture`` between 0 (excluded)
and 2 pi makes a cone around its x axis in its robot (its z axis in a file before R2022a, see
:mod:`mazesim.webots.radio`), turned as its mount and its own ``rotation`` turn it.

Semantics follow Webots' reference manual (https://cyberbotics.com/doc/reference/emitter,
https://cyberbotics.com/doc/reference/receiver): ``send`` returns 0 when the packets queued in
the current step would exceed the emitter's ``bufferSize``; a receiver listens from ``enable``
on and makes what arrived available at each end of its sampling period; a packet that would
make the queue's bytes exceed the receiver's ``bufferSize`` (256 MiB for Webots' unlimited -1:
:data:`MAX_UNLIMITED_QUEUE_BYTES`) is lost; reading an empty queue
prints Webots' error. A receiver hears only emitters of its own ``type``.
"""

from __future__ import annotations

import math
import struct
from collections import deque
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

from mazesim.errors import InvalidArgumentError, WrongTypeError, _a_type, _shown
from mazesim.webots.devices import Device, _print_error, _Sensor
from mazesim.webots.frames import ENU_TO_NUE, Axes, axes_or_none
from mazesim.webots.node_types import node_type
from mazesim.webots.radio import (
    CHANNEL_BROADCAST,
    INFRA_RED,
    RADIO,
    UNLIMITED,
    Cone,
    Packet,
    transmission_type,
)
from mazesim.webots.webots_api import webots_property

if TYPE_CHECKING:
    from mazesim.webots.simulation import RobotSimulation

__all__ = ["Emitter", "Receiver", "emitter_from_fields", "receiver_from_fields"]

#: The E-puck PROTO's emitter and receiver channel.
E_PUCK_CHANNEL = 1
#: The E-puck PROTO's emitter range: the Emitter node's default, -1 (no limit), since the PROTO
#: (V7 to R2025a) sets only the emitter's ``channel``.
E_PUCK_RANGE = UNLIMITED

#: The axes of a device unturned in a robot's Z-up inside (a file since R2022a).
Z_UP_AXES: Axes = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
#: The axes of a device unturned in a robot's Y-up inside (a file before R2022a, its PROTOs and
#: the plain robots saved from them): x right, y up, z back.
Y_UP_AXES: Axes = ENU_TO_NUE


#: The most bytes an emitter queues in one step when its node's ``bufferSize`` is -1: Webots'
#: "unlimited" buffer, bounded here so that one ``send`` cannot take the machine's memory (every
#: receiver in range keeps its own copy of a packet).
MAX_UNLIMITED_BUFFER_BYTES = 16 * 1024 * 1024

#: The most bytes a receiver queues when its node's ``bufferSize`` is -1: Webots' "unlimited"
#: queue, bounded here so that a robot that listens and never reads cannot take the machine's
#: memory (a packet that would pass it is lost, as one past a receiver's own ``bufferSize``).
MAX_UNLIMITED_QUEUE_BYTES = 256 * 1024 * 1024


def _packet_bytes(message: Any, length: int | None, most: int) -> bytes:
    """A message as the bytes sent: str as UTF-8, bytes as they are, a list of numbers as
    doubles (native order); ``length`` keeps only the first bytes. A packet longer than
    ``most`` bytes (the emitter's buffer) is refused before it is built."""
    if length is not None and (
        isinstance(length, bool)
        or not isinstance(length, (int, float))
        or not math.isfinite(length)
    ):
        raise InvalidArgumentError(
            f"Emitter.send: length refused: expected a number of bytes, found {_shown(length)}"
        )
    sized = message if isinstance(message, (str, bytes, bytearray, memoryview)) else None
    try:
        claimed = len(message) if sized is not None else 8 * len(message)
    except TypeError:
        claimed = 0  # not a sized value: refused below
    if length is not None:
        claimed = min(claimed, max(0, int(length)))
    if claimed > most:
        raise InvalidArgumentError(
            f"Emitter.send: packet refused: expected at most {most} bytes (the emitter's "
            f"bufferSize, or mazesim's bound of {MAX_UNLIMITED_BUFFER_BYTES} bytes a step for "
            f"a bufferSize of -1), found {claimed} bytes; send it in smaller packets"
        )
    if isinstance(message, str):
        try:
            data = message.encode("utf-8")
        except UnicodeEncodeError as error:  # a lone surrogate: no UTF-8 for it
            raise InvalidArgumentError(
                "Emitter.send: packet refused: expected text that UTF-8 encodes, found "
                f"{_shown(message[error.start : error.end])} at character {error.start} (a "
                "lone surrogate); send bytes, or text without it"
            ) from None
    elif isinstance(message, (bytes, bytearray, memoryview)):
        data = bytes(message)
    else:
        data = _numbers_packet(message)
    return data if length is None else data[: max(0, int(length))]


def _numbers_packet(message: Any) -> bytes:
    """A list of numbers (a tuple, a numpy array) packed as Webots' ``Emitter.send`` packs it
    (its emitter.py since R2024a): its first item chooses the format, doubles (``d``) for a
    float and 4-byte ints (``i``) for an int or a bool, native order; an empty list is no
    packet (b"")."""
    items: list[Any] = []
    try:
        items = list(message.tolist() if hasattr(message, "tolist") else message)
    except TypeError:
        kind = None  # not a sequence
    else:
        first = items[0] if items else 0
        kind = "d" if isinstance(first, float) else "i" if isinstance(first, int) else None
    if kind is not None and not items:
        return b""
    try:
        if kind is None:
            raise TypeError
        return struct.pack(f"{len(items)}{kind}", *items)
    except (TypeError, ValueError, struct.error):
        what = "numbers" if kind is None else "ints (its first item is one)"
        raise WrongTypeError(
            f"expected an Emitter packet as str, bytes or a list of {what}, found "
            f"{_a_type(message)}" + ("" if kind is None else f" holding {_shown(items[:8])}")
        ) from None


class _Tuned:
    """What an emitter and a receiver share: a channel, read with ``getChannel`` or the
    ``channel`` property (assigning it calls ``setChannel``)."""

    CHANNEL_BROADCAST = CHANNEL_BROADCAST
    _channel: int
    #: The node's ``allowedChannels`` (empty: every channel).
    _allowed: tuple[int, ...] = ()

    def _allow(self, channel: int, allowed: Sequence[int]) -> None:
        """Takes the node's ``channel`` and ``allowedChannels``: a channel the list leaves out
        becomes its first, as Webots sets it when it loads the world ("'channel' is not
        included in 'allowedChannels'")."""
        self._allowed = tuple(int(c) for c in allowed)
        self._channel = int(channel)
        if self._allowed and self._channel not in self._allowed:
            self._channel = self._allowed[0]

    def setChannel(self, channel: int) -> None:
        raise NotImplementedError

    def _tuned_to(self, channel: int, function: str) -> int | None:
        """The channel a ``setChannel`` call asks for, as Webots takes it: a C ``int``, so a
        number beyond the int32 range is refused (Webots' Python API would pass its low 32 bits
        on, a channel the call never named); a channel below -1 (:attr:`CHANNEL_BROADCAST`),
        or one the node's ``allowedChannels`` leaves out, prints Webots' error and is ignored
        (None), as ``wb_emitter_set_channel`` and ``wb_receiver_set_channel`` do."""
        tuned = int(channel)
        if not -(2**31) <= tuned < 2**31:
            raise InvalidArgumentError(
                f"{type(self).__name__}.setChannel: channel refused: expected a channel that "
                f"fits Webots' int32, in [-1, {2**31 - 1}] (-1: every channel), found {tuned}"
            )
        if tuned < CHANNEL_BROADCAST:
            _print_error(
                f"Error: {function}() called with an invalid channel={tuned}. "
                "Please use a channel inside the range [-1,inf)."
            )
            return None
        if self._allowed and tuned not in self._allowed and tuned != self._channel:
            _print_error(
                f"Error: {function}() called with channel={tuned}, which is not between allowed "
                "channels. Please use an allowed channel."
            )
            return None
        return tuned

    def getChannel(self) -> int:
        """The channel (-1: every channel)."""
        return self._channel

    channel = webots_property("getChannel", "setChannel")


class Emitter(_Tuned, Device):
    """An emitter: ``send``, channel, range and buffer size; its ``kind`` (the node's ``type``,
    "radio", "serial" or "infra-red") is the only type of receiver that hears it, and an
    infra-red one sends only along a line of sight, within its ``cone`` (None: all around)."""

    _node_type = node_type("EMITTER")

    def __init__(
        self,
        name: str,
        simulation: RobotSimulation,
        channel: int = E_PUCK_CHANNEL,
        range_m: float = E_PUCK_RANGE,
        max_range: float = UNLIMITED,
        buffer_size: int = UNLIMITED,
        kind: str = RADIO,
        cone: Cone | None = None,
        allowed_channels: Sequence[int] = (),
    ) -> None:
        super().__init__(name, simulation)
        self._allow(channel, allowed_channels)
        self._kind = transmission_type(kind)
        self._cone = cone
        self._max_range = float(max_range)
        self._range = self._clamped(float(range_m))
        self._buffer_size = int(buffer_size)
        self._queued_bytes = 0
        self._queued_at = -1

    def _clamped(self, range_m: float) -> float:
        """A range no longer than ``maxRange`` (-1 counts as infinite for both)."""
        if self._max_range == UNLIMITED:
            return range_m
        if range_m == UNLIMITED or range_m > self._max_range:
            return self._max_range
        return range_m

    def send(self, message: Any, length: int | None = None) -> int:
        """Sends a packet (str, bytes, or a list of numbers packed as Webots' Python does:
        doubles when its first item is a float, 4-byte ints when it is an int or a bool).

        Returns:
            1 when the packet was queued, 0 when the emitter's buffer is full (or the packet is
            empty: a packet has at least 1 byte).
        """
        unlimited = self._buffer_size == UNLIMITED
        buffer = MAX_UNLIMITED_BUFFER_BYTES if unlimited else self._buffer_size
        # A packet larger than a finite buffer is not sent (0), as in Webots; one larger than
        # the bound of an unlimited buffer is refused.
        data = _packet_bytes(message, length, max(buffer, MAX_UNLIMITED_BUFFER_BYTES))
        if not data:
            _print_error("Error: wb_emitter_send(): invalid size=0 argument.")
            return 0
        simulation = self._simulation
        if self._queued_at != simulation.steps:
            self._queued_at, self._queued_bytes = simulation.steps, 0
        if self._queued_bytes + len(data) > buffer:
            return 0
        self._queued_bytes += len(data)
        simulation.radio.send(
            simulation.robot_index, self._channel, self._range, data, self._kind, self._cone
        )
        return 1

    def setChannel(self, channel: int) -> None:
        """Sets the channel (:attr:`CHANNEL_BROADCAST` sends on every channel)."""
        tuned = self._tuned_to(channel, "wb_emitter_set_channel")
        if tuned is not None:
            self._channel = tuned

    def getRange(self) -> float:
        """The range in metres (-1: no limit)."""
        return self._range

    def setRange(self, range: float) -> None:
        """Sets the range in metres, at most the node's ``maxRange``."""
        self._range = self._clamped(float(range))

    def getBufferSize(self) -> int:
        """The bytes the emitter may queue in one step (-1: unlimited)."""
        return self._buffer_size


class Receiver(_Tuned, _Sensor):
    """A receiver: its queue of packets, sampled every sampling period; it hears only
    emitters of its ``kind`` (the node's ``type``), and an infra-red one only within its
    ``cone`` (None: all around)."""

    _node_type = node_type("RECEIVER")

    _api = "wb_receiver"

    def __init__(
        self,
        name: str,
        simulation: RobotSimulation,
        channel: int = E_PUCK_CHANNEL,
        buffer_size: int = UNLIMITED,
        axes: Axes | None = None,
        cone: Cone | None = None,
        kind: str = RADIO,
        allowed_channels: Sequence[int] = (),
    ) -> None:
        super().__init__(name, simulation)
        self._allow(channel, allowed_channels)
        self._kind = transmission_type(kind)
        self._buffer_size = int(buffer_size)
        self._axes = axes or _unturned(simulation)
        self._cone = cone
        self._queue: deque[Packet] = deque()
        self._queued_bytes = 0
        self._resets = simulation.last_reset.count

    def _queued(self) -> deque[Packet]:
        """The queue, emptied when the world was reset since it was last read, as Webots
        empties it."""
        resets = self._simulation.last_reset.count
        if resets != self._resets:
            self._resets = resets
            self._queue.clear()
            self._queued_bytes = 0
        return self._queue

    def _tune(self) -> None:
        simulation = self._simulation
        listening = self._period_ms > 0
        simulation.radio.tune(
            simulation.robot_index, self._name, self._channel, listening, self._cone, self._kind
        )

    def enable(self, samplingPeriod: int) -> None:
        """Listens from now on; what arrives is in the queue at each end of a sampling period."""
        super().enable(samplingPeriod)
        self._tune()

    def disable(self) -> None:
        """Stops listening; the queue keeps its packets."""
        super().disable()
        self._tune()

    def _read(self) -> float:
        """At the end of a sampling period: queues what arrived, losing a packet that would
        overflow the buffer."""
        simulation = self._simulation
        queue = self._queued()
        unlimited = self._buffer_size == UNLIMITED
        most = MAX_UNLIMITED_QUEUE_BYTES if unlimited else self._buffer_size
        for packet in simulation.radio.collect(simulation.robot_index, self._name):
            size = len(packet.data)
            if self._queued_bytes + size > most:
                continue
            queue.append(packet)
            self._queued_bytes += size
        return math.nan

    def _head(self, function: str) -> Packet | None:
        """The head packet, or None with Webots' error when the queue is empty."""
        if not self._queued():
            _print_error(f"Error: wb_receiver_{function}(): the receiver queue is empty.")
            return None
        return self._queue[0]

    def getQueueLength(self) -> int:
        """The number of packets in the queue; a disabled receiver's (0 if it never listened)
        with Webots' message for a disabled device (the usual sign of a forgotten
        ``enable``)."""
        self._warn_disabled("get_queue_length")
        return len(self._queued())

    def nextPacket(self) -> None:
        """Drops the head packet (Webots' error when the queue is empty)."""
        if self._head("next_packet") is not None:
            self._queued_bytes -= len(self._queue.popleft().data)

    def getBytes(self) -> bytes | None:
        """The head packet's bytes (None with Webots' error when the queue is empty)."""
        head = self._head("get_data")
        return None if head is None else head.data

    def getData(self) -> bytes | None:
        """The head packet's bytes, as :meth:`getBytes`."""
        return self.getBytes()

    def _unpacked(self, kind: str, size: int) -> tuple[Any, ...] | None:
        head = self._head("get_data")
        if head is None:
            return None
        return struct.unpack(
            f"{len(head.data) // size}{kind}", head.data[: len(head.data) // size * size]
        )

    def getFloats(self) -> tuple[float, ...] | None:
        """The head packet as doubles (what ``Emitter.send`` of a list of floats sends), as
        Webots' Python ``Receiver.getFloats`` reads it (None with Webots' error when empty)."""
        return self._unpacked("d", 8)

    def getInts(self) -> tuple[int, ...] | None:
        """The head packet as 4-byte integers (what ``Emitter.send`` of a list of ints sends),
        as Webots' ``Receiver.getInts``."""
        return self._unpacked("i", 4)

    def getBools(self) -> tuple[bool, ...] | None:
        """The head packet as one boolean a byte, as Webots' ``Receiver.getBools``."""
        return self._unpacked("?", 1)

    def getString(self) -> str | None:
        """The head packet as UTF-8 text, without the NUL a C controller ends a string with."""
        head = self._head("get_data")
        if head is None:
            return None
        data = head.data[:-1] if head.data.endswith(b"\0") else head.data
        return data.decode("utf-8", errors="replace")

    def getDataSize(self) -> int:
        """The head packet's size in bytes (-1 with Webots' error when the queue is empty)."""
        head = self._head("get_data_size")
        return -1 if head is None else len(head.data)

    def getSignalStrength(self) -> float:
        """1 / r^2 for the distance r at which the head packet was sent (NaN when empty)."""
        head = self._head("get_signal_strength")
        return math.nan if head is None else head.signal_strength

    def getEmitterDirection(self) -> list[float]:
        """Unit vector toward the head packet's emitter in the receiver's own frame, as Webots
        gives it (NaNs when empty): the robot's frame as the world writes its inside (x
        forward, y left, z up since R2022a; before, x right, y up, z back), turned as the
        receiver's mount and its own ``rotation`` turn it."""
        head = self._head("get_emitter_direction")
        if head is None:
            return [math.nan] * 3
        return [sum(a * d for a, d in zip(axis, head.direction)) for axis in self._axes]

    def setChannel(self, channel: int) -> None:
        """Sets the channel (:attr:`CHANNEL_BROADCAST` listens to every channel)."""
        tuned = self._tuned_to(channel, "wb_receiver_set_channel")
        if tuned is not None:
            self._channel = tuned
            self._tune()


def _int_field(fields: Mapping[str, Any], name: str, default: int) -> int:
    value = fields.get(name, default)
    return int(value) if isinstance(value, (int, float)) and math.isfinite(value) else default


def _float_field(fields: Mapping[str, Any], name: str, default: float) -> float:
    value = fields.get(name, default)
    return float(value) if isinstance(value, (int, float)) and math.isfinite(value) else default


def _channels_field(fields: Mapping[str, Any]) -> tuple[int, ...]:
    """The node's ``allowedChannels`` (MFInt32; empty, Webots' default, allows every
    channel): its whole numbers from -1 up, in order; a value of another kind is left out."""
    value = fields.get("allowedChannels", ())
    values = value if isinstance(value, (list, tuple)) else [value]
    return tuple(
        int(v)
        for v in values
        if isinstance(v, (int, float)) and not isinstance(v, bool)
        and math.isfinite(v) and float(v).is_integer() and -1 <= v < 2**31
    )  # fmt: skip


def emitter_from_fields(
    name: str, simulation: RobotSimulation, fields: Mapping[str, Any], axes: Any = None
) -> Emitter:
    """An Emitter node of the world file, with its fields (Webots' node defaults: type
    "radio", channel 0, range -1, maxRange -1, bufferSize -1, aperture -1, allowedChannels
    empty) and its axes in
    the robot's frame (as :func:`receiver_from_fields`)."""
    return Emitter(
        name,
        simulation,
        channel=_int_field(fields, "channel", 0),
        range_m=_float_field(fields, "range", UNLIMITED),
        max_range=_float_field(fields, "maxRange", UNLIMITED),
        buffer_size=_int_field(fields, "bufferSize", UNLIMITED),
        kind=transmission_type(fields.get("type")),
        cone=_cone(simulation, fields, axes),
        allowed_channels=_channels_field(fields),
    )


def receiver_from_fields(
    name: str, simulation: RobotSimulation, fields: Mapping[str, Any], axes: Any = None
) -> Receiver:
    """A Receiver node of the world file, with its fields (Webots' node defaults: type
    "radio", channel 0, bufferSize -1, aperture -1) and its axes in the robot's frame (the
    import report's ``axes``; where absent or malformed, unturned in the robot's inside)."""
    return Receiver(
        name,
        simulation,
        channel=_int_field(fields, "channel", 0),
        buffer_size=_int_field(fields, "bufferSize", UNLIMITED),
        axes=axes_or_none(axes),
        cone=_cone(simulation, fields, axes),
        kind=transmission_type(fields.get("type")),
        allowed_channels=_channels_field(fields),
    )


def _unturned(simulation: RobotSimulation) -> Axes:
    """The axes of a device unturned in the robot's inside (the E-puck PROTO's own)."""
    return Y_UP_AXES if simulation.scene.y_up_devices else Z_UP_AXES


def _cone(simulation: RobotSimulation, fields: Mapping[str, Any], axes: Any) -> Cone | None:
    """An infra-red device's cone: its ``aperture`` field above 0 and at most 2 pi (else
    none, as Webots takes -1 and 0), around its x axis (its z axis in a file before
    R2022a)."""
    aperture = _float_field(fields, "aperture", UNLIMITED)
    if fields.get("type") != INFRA_RED or not 0.0 < aperture <= math.tau:
        return None
    own = axes_or_none(axes) or _unturned(simulation)
    axis = own[2] if simulation.scene.y_up_devices else own[0]
    return (*axis, aperture / 2.0)
