"""The radio between the robots of a world: what Webots' Emitter and Receiver nodes carry.

A :class:`Radio` is the medium of one world. Emitters :meth:`~Radio.send` packets; once per basic
time step the process that owns the world calls :meth:`~Radio.transmit` with every robot's
pose after the step's motion, and each packet sent since the last transmission reaches the
listening receivers of the other robots: those of the emitter's type ("radio", "serial" or
"infra-red"), on its channel (or listening to all, channel -1; a packet sent on channel -1
reaches every channel) and within its range (-1: no limit). Receivers
:meth:`~Radio.collect` what arrived at their next sampling instant. The rules follow Webots'
reference manual (https://cyberbotics.com/doc/reference/emitter and
https://cyberbotics.com/doc/reference/receiver):

- "the Emitter node will need at least one basic time step to send the packet but the Receiver
  node will receive it immediately": a packet sent before ``Robot.step`` is in the queue of a
  receiver sampling every basic step when that step returns;
- "a packet will not be sent to its emitter robot";
- a packet reaches only receivers of its emitter's ``type``: Webots' source
  (``WbReceiver::transmitPacket``, "media types must match") compares the two devices' types,
  so a "radio" receiver hears neither a "serial" nor an "infra-red" emitter; a type Webots does
  not know counts as "radio", as Webots takes it after its warning;
- "A value of -1 (the default) for range is considered to be an infinite range"; the distance
  is the one between the two robots' centres where they stand after the step that delivers the
  packet, as Webots' ``WbReceiver::postPhysicsStep`` checks the range and cones and measures the
  direction and strength after that step's physics (a world run calls :meth:`~Radio.transmit`
  with the poses after the step's motion);
- the signal strength is "the inverse of the distance between the emitter and the receiver
  squared", the emitter's direction "a normalized (length=1) vector that indicates the direction
  of the emitter with respect to the receiver's coordinate system" (x forward, y left, z up);
- packets are "received in the same order they were sent"; packets of several robots sent in
  the same step arrive in the order of the robots, then of sending, so a run is repeatable;
- "Signals of type "radio" (the default) and "serial" are transmitted without taking obstacles
  into account. Signals of type "infra-red," however, do take potential obstacles between the
  emitter and the receiver into account. Any solid object (solid, robots, etc ...) with a
  defined bounding object is a potential obstacle [...] The structure of the emitting or
  receiving robot itself will not block an "infra-red" transmission": an infra-red packet
  reaches a receiver only when the segment between the two robots' centres, seen from above,
  meets none of the obstacles of the radio's :attr:`~Radio.sight` (the world's walls where a
  supervisor moved them, the other robots' bodies and the movable bodies, all as they stand
  after the step that delivers the packet);
- an infra-red Emitter's ``aperture`` is the "opening angle of the emission cone (in radians);
  for "infra-red" only", an infra-red Receiver's that of its reception cone, -1 (the default)
  all around: such a packet reaches a receiver only when the receiving robot's centre lies
  within the emitter's cone and the sending robot's within the receiver's. Webots' source
  (``WbReceiver::checkApertureAndRange``) takes an aperture above 0 only, around the device's
  x axis; the reference manual names its z axis, which mazesim takes for a file before R2022a
  (:class:`Cone`).

A run of one robot has a radio too: nothing reaches its own receiver.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from mazesim.webots.line_of_sight import LineOfSight, Sight

__all__ = [
    "CHANNEL_BROADCAST",
    "INFRA_RED",
    "RADIO",
    "SERIAL",
    "UNLIMITED",
    "Cone",
    "Packet",
    "Radio",
    "transmission_type",
]

#: The channel of an emitter that sends on every channel, or a receiver that listens to all.
CHANNEL_BROADCAST = -1
#: A range, buffer size or maximum range without limit.
UNLIMITED = -1

#: The transmission types of Webots' Emitter and Receiver nodes (their ``type`` field), the
#: first the nodes' default.
RADIO = "radio"
SERIAL = "serial"
INFRA_RED = "infra-red"


def transmission_type(value: object) -> str:
    """A node's ``type`` field as the transmission type Webots takes: "radio", "serial" or
    "infra-red", anything else (absent, misspelt) "radio"."""
    return value if isinstance(value, str) and value in (SERIAL, INFRA_RED) else RADIO


#: An infra-red device's cone: its axis (x, y, z in its robot's frame, x forward, y left, z
#: up) and half its ``aperture`` (radians).
Cone = tuple[float, float, float, float]


@dataclass(frozen=True)
class Packet:
    """A packet in a receiver's queue.

    Attributes:
        data: The bytes sent.
        channel: The channel it was sent on.
        signal_strength: 1 / r^2 for the distance r (metres) between the robots as it
            arrived; infinite at distance 0.
        direction: Unit vector toward the emitter in the receiving robot's frame (x forward, y left,
            z up).
    """

    data: bytes
    channel: int
    signal_strength: float
    direction: tuple[float, float, float]


@dataclass
class _Sent:
    """A packet on its way: who sent it, on which channel, how far it carries."""

    robot: int
    order: int
    channel: int
    range_m: float
    data: bytes
    kind: str
    cone: Cone | None


@dataclass
class _Tuning:
    """A receiver's channel, whether it listens (is enabled) and its transmission type."""

    channel: int
    listening: bool
    cone: Cone | None = None
    kind: str = RADIO
    arrived: list[Packet] = field(default_factory=list)


def _reaches(sent: _Sent, channel: int) -> bool:
    """Whether a packet sent on ``sent.channel`` is heard on ``channel``."""
    return CHANNEL_BROADCAST in (sent.channel, channel) or sent.channel == channel


class Radio:
    """The medium of one world: packets in transit and the receivers that listen.

    Robots are numbered (their index in the world); receivers are named by robot and device
    name.

    Attributes:
        sight: The world's obstacles, which stop infra-red packets; None: nothing stops them.
    """

    def __init__(self, sight: LineOfSight | None = None) -> None:
        self.sight = sight
        self._in_transit: list[_Sent] = []
        self._receivers: dict[tuple[int, str], _Tuning] = {}
        self._sent = 0

    def send(
        self,
        robot: int,
        channel: int,
        range_m: float,
        data: bytes,
        kind: str = RADIO,
        cone: Cone | None = None,
    ) -> None:
        """Puts a packet on its way; it arrives at the next :meth:`transmit`.

        Args:
            robot: The sending robot.
            channel: The emitter's channel (-1: every channel).
            range_m: The emitter's range in metres (-1: no limit).
            data: The packet.
            kind: The emitter's transmission type (:data:`RADIO`, :data:`SERIAL` or
                :data:`INFRA_RED`, whose packets obstacles stop); only receivers of that type
                hear it.
            cone: An infra-red emitter's emission cone (None: all around).
        """
        kind = transmission_type(kind)
        self._sent += 1
        self._in_transit.append(
            _Sent(
                robot,
                self._sent,
                channel,
                float(range_m),
                bytes(data),
                kind,
                cone if kind == INFRA_RED else None,
            )
        )

    def tune(
        self,
        robot: int,
        receiver: str,
        channel: int,
        listening: bool,
        cone: Cone | None = None,
        kind: str = RADIO,
    ) -> None:
        """Sets a receiver's channel, whether it listens, its reception cone for infra-red
        packets (None: all around) and its transmission type (it hears only emitters of that
        type); a receiver that stops listening keeps what arrived before."""
        tuning = self._receivers.setdefault((robot, receiver), _Tuning(channel, listening))
        tuning.channel = channel
        tuning.listening = listening
        tuning.cone = cone
        tuning.kind = transmission_type(kind)

    def transmit(self, poses: Mapping[int, tuple[float, float, float]]) -> None:
        """Delivers the packets sent since the last call to the listening receivers they reach.

        Args:
            poses: Each robot's x, y (metres) and yaw (radians) where it stands as the packets
                arrive (after the step's motion).
        """
        sent = sorted(self._in_transit, key=lambda p: (p.robot, p.order))
        self._in_transit = []
        sight: Sight | None = None
        for (robot, _), tuning in sorted(self._receivers.items()):
            if not tuning.listening or robot not in poses:
                continue
            for packet in sent:
                if packet.robot == robot or packet.robot not in poses:
                    continue
                if packet.kind != tuning.kind or not _reaches(packet, tuning.channel):
                    continue
                arrived = _arrival(packet, poses[packet.robot], poses[robot])
                if arrived is None:
                    continue
                if packet.kind == INFRA_RED:
                    sender, receiver = poses[packet.robot], poses[robot]
                    if not (
                        _within(packet.cone, sender, receiver)
                        and _within(tuning.cone, receiver, sender)
                    ):
                        continue
                    if self.sight is not None:
                        sight = sight or self.sight.at(poses)
                        if sight.blocked(packet.robot, robot):
                            continue
                tuning.arrived.append(arrived)

    def clear(self) -> None:
        """Drops the packets in transit and those waiting for their receivers (a reset of the
        world, which empties Webots' Emitter and Receiver queues)."""
        self._in_transit = []
        for tuning in self._receivers.values():
            tuning.arrived = []

    def collect(self, robot: int, receiver: str) -> list[Packet]:
        """The packets that reached a receiver since it last collected (emptied)."""
        tuning = self._receivers.get((robot, receiver))
        if tuning is None:
            return []
        arrived, tuning.arrived = tuning.arrived, []
        return arrived


def _within(
    cone: Cone | None, device: tuple[float, float, float], other: tuple[float, float, float]
) -> bool:
    """Whether the robot at ``other`` lies within the cone of a device of the robot at
    ``device`` (x, y, yaw): the angle between the cone's axis and the way from one robot's
    centre to the other's is at most half the aperture."""
    if cone is None:
        return True
    ax, ay, az, half = cone
    c, s = math.cos(device[2]), math.sin(device[2])
    wx, wy = c * ax - s * ay, s * ax + c * ay
    dx, dy = other[0] - device[0], other[1] - device[1]
    norm = math.sqrt(wx * wx + wy * wy + az * az) * math.hypot(dx, dy)
    if norm == 0.0:
        return True
    return math.acos(max(-1.0, min(1.0, (wx * dx + wy * dy) / norm))) <= half


def _arrival(
    sent: _Sent, sender: tuple[float, float, float], receiver: tuple[float, float, float]
) -> Packet | None:
    """The packet as a receiver at ``receiver`` gets it, or None when out of range."""
    dx, dy = sender[0] - receiver[0], sender[1] - receiver[1]
    distance = math.hypot(dx, dy)
    if sent.range_m != UNLIMITED and distance > sent.range_m:
        return None
    if distance > 0.0:
        bearing = math.atan2(dy, dx) - receiver[2]
        direction = (math.cos(bearing), math.sin(bearing), 0.0)
        strength = 1.0 / (distance * distance)
    else:
        direction = (1.0, 0.0, 0.0)
        strength = math.inf
    return Packet(sent.data, sent.channel, strength, direction)
