"""Emitter and Receiver between robots: Webots' channels, range, queue and next-step delivery."""

from __future__ import annotations

import math
import struct
from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest

import mazesim
from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.importer import import_wbt_text
from mazesim.webots.line_of_sight import LineOfSight
from mazesim.webots.radio import INFRA_RED, RADIO, SERIAL, Radio
from mazesim.webots.radio_devices import (
    Emitter,
    Receiver,
    emitter_from_fields,
    receiver_from_fields,
)
from mazesim.webots.rays import WallBoxes
from mazesim.webots.scene import read_scene
from radio_pair import RadioPair

HERE = (0.0, 0.0, 0.0)


def _radio_with_receiver(channel: int = 1) -> Radio:
    radio = Radio()
    radio.tune(1, "receiver", channel, listening=True)
    return radio


def test_a_packet_arrives_at_the_next_transmission_not_before() -> None:
    radio = _radio_with_receiver()
    radio.send(0, 1, -1, b"hello")
    assert radio.collect(1, "receiver") == []
    radio.transmit({0: HERE, 1: (0.5, 0.0, 0.0)})
    (packet,) = radio.collect(1, "receiver")
    assert packet.data == b"hello"
    assert radio.collect(1, "receiver") == [], "collecting empties"


@pytest.mark.parametrize(
    ("sent_on", "listening_on", "heard"),
    [(1, 1, True), (1, 2, False), (-1, 2, True), (3, -1, True), (-1, -1, True)],
)
def test_channels_and_the_broadcast_channel(sent_on: int, listening_on: int, heard: bool) -> None:
    radio = _radio_with_receiver(listening_on)
    radio.send(0, sent_on, -1, b"x")
    radio.transmit({0: HERE, 1: (0.1, 0.0, 0.0)})
    assert bool(radio.collect(1, "receiver")) is heard


def test_range_is_the_distance_between_robots_and_minus_one_has_no_limit() -> None:
    radio = _radio_with_receiver()
    radio.send(0, 1, 0.5, b"near")
    radio.send(0, 1, 0.3, b"short")
    radio.send(0, 1, -1, b"anywhere")
    radio.transmit({0: HERE, 1: (0.3, 0.4, 0.0)})  # 0.5 m away
    assert [p.data for p in radio.collect(1, "receiver")] == [b"near", b"anywhere"]


def test_no_packet_to_its_own_robot_nor_to_a_receiver_not_listening() -> None:
    radio = _radio_with_receiver()
    radio.tune(0, "receiver", 1, listening=True)
    radio.tune(2, "receiver", 1, listening=False)
    radio.send(0, 1, -1, b"x")
    radio.transmit({0: HERE, 1: (1.0, 0.0, 0.0), 2: (1.0, 1.0, 0.0)})
    assert radio.collect(0, "receiver") == []
    assert radio.collect(2, "receiver") == []
    assert len(radio.collect(1, "receiver")) == 1


def test_signal_strength_and_direction_in_the_receivers_frame() -> None:
    radio = _radio_with_receiver()
    radio.send(0, 1, -1, b"x")
    # The receiver is 2 m east of the sender and faces north: the sender is on its left (+y).
    radio.transmit({0: HERE, 1: (2.0, 0.0, math.pi / 2)})
    (packet,) = radio.collect(1, "receiver")
    assert packet.signal_strength == pytest.approx(0.25)
    assert packet.direction == pytest.approx((0.0, 1.0, 0.0), abs=1e-12)


def test_order_is_robot_then_sending_whatever_the_order_of_arrival() -> None:
    radio = _radio_with_receiver()
    radio.send(2, 1, -1, b"c1")
    radio.send(0, 1, -1, b"a1")
    radio.send(2, 1, -1, b"c2")
    radio.transmit({0: HERE, 1: (0.1, 0.0, 0.0), 2: (0.2, 0.0, 0.0)})
    assert [p.data for p in radio.collect(1, "receiver")] == [b"a1", b"c1", b"c2"]


# --- the devices, two robots sharing one radio -------------------------------------------------


def test_a_packet_sent_before_a_step_is_in_the_queue_after_it() -> None:
    pair = RadioPair()
    emitter = Emitter("emitter", pair.robots[0])
    receiver = Receiver("receiver", pair.robots[1])
    pair.receivers.append(receiver)
    receiver.enable(int(pair.robots[1].basic_time_step_ms))
    emitter.send("hello")
    assert receiver.getQueueLength() == 0
    pair.step()
    assert receiver.getQueueLength() == 1
    assert receiver.getString() == "hello"
    assert receiver.getDataSize() == 5
    assert receiver.getSignalStrength() == pytest.approx(1 / 0.3**2)
    assert receiver.getEmitterDirection()[0] == pytest.approx(-1.0)
    receiver.nextPacket()
    assert receiver.getQueueLength() == 0


def test_a_packet_of_another_type_is_refused_naming_the_kinds_sent() -> None:
    """``send`` takes str, bytes or a sequence of numbers (a numpy array too); anything else is
    a WrongTypeError naming what was found, not a TypeError from inside the packing."""
    pair = RadioPair()
    emitter = Emitter("emitter", pair.robots[0])
    for bad, found in ((None, "found None"), (12, "found an int"), (["a"], "found a list")):
        with pytest.raises(mazesim.WrongTypeError, match=found) as refused:
            emitter.send(bad)
        assert "str, bytes or a list of numbers" in str(refused.value)
    assert emitter.send(np.array([1.0, 2.0], dtype=np.float32)) == 1


def _listening_pair() -> tuple[RadioPair, Emitter, Receiver]:
    """Two robots, the first's emitter and the second's receiver, enabled."""
    pair = RadioPair()
    emitter = Emitter("emitter", pair.robots[0])
    receiver = Receiver("receiver", pair.robots[1])
    pair.receivers.append(receiver)
    receiver.enable(int(pair.robots[1].basic_time_step_ms))
    return pair, emitter, receiver


def test_a_list_of_numbers_is_read_back_as_floats_ints_or_bools() -> None:
    """Webots' Python Receiver reads a packet as doubles (``getFloats``, what ``Emitter.send``
    of a list of numbers sends), 4-byte ints (``getInts``) or booleans (``getBools``)."""
    pair, emitter, receiver = _listening_pair()
    emitter.send([7.0, 1.0, 0.25])
    emitter.send(struct.pack("3i", 7, -1, 2))
    emitter.send(bytes([1, 0]))
    pair.step()
    assert receiver.getFloats() == (7.0, 1.0, 0.25)
    receiver.nextPacket()
    assert receiver.getInts() == (7, -1, 2)
    receiver.nextPacket()
    assert receiver.getBools() == (True, False)
    receiver.nextPacket()
    assert receiver.getFloats() is None


def test_a_list_packs_as_its_first_item_chooses_as_webots_python_does() -> None:
    """Webots' emitter.py (R2024a on) packs a list by its first item: doubles for a float,
    4-byte ints for an int or a bool, so ``send([1, 2, 3])`` is 12 bytes ``getInts`` reads."""
    pair, emitter, receiver = _listening_pair()
    emitter.send([1, 2, 3])
    emitter.send((True, False))
    emitter.send([0.5, 2])
    emitter.send(np.array([4, 5], dtype=np.int64))
    pair.step()
    sizes_and_ints = []
    for _ in range(4):
        sizes_and_ints.append((receiver.getDataSize(), receiver.getInts()))
        receiver.nextPacket()
    assert sizes_and_ints[0] == (12, (1, 2, 3))
    assert sizes_and_ints[1] == (8, (1, 0))
    assert sizes_and_ints[2][0] == 16
    assert sizes_and_ints[3] == (8, (4, 5))
    # An int first and a float after: struct refuses it in Webots too.
    with pytest.raises(mazesim.WrongTypeError, match="ints"):
        emitter.send([1, 2.5])


def test_the_sampling_period_holds_packets_until_it_ends(
    capsys: pytest.CaptureFixture[str],
) -> None:
    pair = RadioPair()
    basic = int(pair.robots[1].basic_time_step_ms)
    emitter = Emitter("emitter", pair.robots[0])
    receiver = Receiver("receiver", pair.robots[1])
    pair.receivers.append(receiver)
    receiver.enable(3 * basic)
    emitter.send(b"\x01\x02")
    pair.step()
    pair.step()
    assert receiver.getQueueLength() == 0, "the first sampling period has not ended"
    assert receiver.getBytes() is None
    assert "the receiver queue is empty" in capsys.readouterr().err
    pair.step()
    assert receiver.getQueueLength() == 1
    assert receiver.getBytes() == b"\x01\x02"


def test_a_disabled_receiver_hears_nothing_and_buffers_overflow_by_losing_packets(
    capsys: pytest.CaptureFixture[str],
) -> None:
    pair = RadioPair()
    basic = int(pair.robots[1].basic_time_step_ms)
    emitter = Emitter("emitter", pair.robots[0])
    receiver = Receiver("receiver", pair.robots[1], buffer_size=6)
    pair.receivers.append(receiver)
    emitter.send("lost")
    pair.step()
    # Webots' receiver.c: the queue of a disabled receiver is read with its message.
    assert receiver.getQueueLength() == 0
    assert capsys.readouterr().err == (
        "Error: wb_receiver_get_queue_length() called for a disabled device! "
        "Please use: wb_receiver_enable().\n"
    )
    receiver.enable(basic)
    pair.step()
    assert receiver.getQueueLength() == 0, "sent while the receiver was disabled"
    assert capsys.readouterr().err == "", "enabled: no message"
    for word in ("abc", "def", "ghi"):
        emitter.send(word)
    pair.step()
    assert receiver.getQueueLength() == 2, "the third packet overflows 6 bytes"
    assert receiver.getString() == "abc"
    receiver.nextPacket()
    assert receiver.getString() == "def"


def test_an_emitters_buffer_size_and_max_range_and_the_e_pucks_defaults() -> None:
    pair = RadioPair()
    own = emitter_from_fields(
        "radio", pair.robots[0], {"channel": 4, "range": 2.0, "maxRange": 1.0, "bufferSize": 4}
    )
    assert (own.getChannel(), own.getRange(), own.getBufferSize()) == (4, 1.0, 4)
    own.setRange(-1)
    assert own.getRange() == 1.0, "-1 is infinite, more than maxRange"
    assert own.send(b"abc") == 1
    assert own.send(b"de") == 0, "5 bytes in one step exceed the buffer of 4"
    pair.step()
    assert own.send(b"de") == 1, "the buffer empties as the packets leave"
    e_puck = Emitter("emitter", pair.robots[0])
    assert (e_puck.getChannel(), e_puck.getRange(), e_puck.getBufferSize()) == (1, -1, -1)
    assert e_puck.send(b"") == 0


def test_an_unlimited_emitter_buffer_is_bounded_and_a_packet_beyond_it_refused() -> None:
    """Webots' bufferSize -1 is "unlimited"; here it holds MAX_UNLIMITED_BUFFER_BYTES a step,
    so one send cannot take the machine's memory: a packet larger than that is refused before
    it is built (a 300 MB one, or a sequence of 10**9 numbers), one that would overflow the
    step's bound is not sent (0), as from a full buffer."""
    from mazesim.errors import InvalidArgumentError
    from mazesim.webots.radio_devices import MAX_UNLIMITED_BUFFER_BYTES

    pair = RadioPair()
    e_puck = Emitter("emitter", pair.robots[0])
    assert e_puck.getBufferSize() == -1
    with pytest.raises(InvalidArgumentError, match="bufferSize"):
        e_puck.send(b"x" * (MAX_UNLIMITED_BUFFER_BYTES + 1))
    with pytest.raises(InvalidArgumentError, match="smaller packets"):
        e_puck.send(range(10**9))
    with pytest.raises(InvalidArgumentError, match="length"):
        e_puck.send(b"abc", math.nan)
    with pytest.raises(InvalidArgumentError, match="UTF-8 encodes.*at character 2"):
        e_puck.send("ab\ud800c")  # a lone surrogate: no UTF-8 for it
    half = b"x" * (MAX_UNLIMITED_BUFFER_BYTES // 2)
    assert (e_puck.send(half), e_puck.send(half), e_puck.send(b"y")) == (1, 1, 0)
    pair.step()
    assert e_puck.send(b"y") == 1, "the bound is a step's, as a buffer empties"


def test_an_unlimited_receiver_queue_is_bounded_and_a_packet_beyond_it_lost(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A receiver of bufferSize -1 that listens and never reads keeps at most
    MAX_UNLIMITED_QUEUE_BYTES (it took 3.5 GB before the run died): a packet past the bound is
    lost, as one past a receiver's own bufferSize; reading makes room again."""
    from mazesim.webots import radio_devices

    monkeypatch.setattr(radio_devices, "MAX_UNLIMITED_QUEUE_BYTES", 10)
    pair = RadioPair()
    emitter = Emitter("emitter", pair.robots[0])
    receiver = Receiver("receiver", pair.robots[1])
    pair.receivers.append(receiver)
    receiver.enable(int(pair.robots[1].basic_time_step_ms))
    for word in ("abcd", "efgh", "ijkl"):
        emitter.send(word)
        pair.step()
    assert receiver.getQueueLength() == 2, "the third packet would pass 10 bytes"
    receiver.nextPacket()
    emitter.send("mnop")
    pair.step()
    assert [receiver.getString(), receiver.getQueueLength()] == ["efgh", 2]


def test_the_e_pucks_emitter_reaches_any_distance_as_its_protos_does() -> None:
    # The E-puck PROTO sets only its Emitter's channel, so the range is the node's default, -1:
    # an e-puck's packet reaches a supervisor 1.4 m away (a swarm scattered over a 5 m arena).
    pair = RadioPair()
    pair.radio.tune(1, "receiver", 1, listening=True)
    Emitter("emitter", pair.robots[0]).send(b"configuration")
    pair.radio.transmit({0: HERE, 1: (1.4, 0.0, 0.0)})
    assert [p.data for p in pair.radio.collect(1, "receiver")] == [b"configuration"]


# --- the channels a world file gives --------------------------------------------------------

WITH_CHANNELS = """#VRML_SIM R2023b utf8
E-puck { controller "x" emitter_channel 4 receiver_channel 5 supervisor TRUE }
E-puck { translation 0.5 0 0 name "other" controller "x" }
"""


@pytest.fixture
def robot_of_world() -> Iterator[Any]:
    world, report = import_wbt_text(WITH_CHANNELS)
    scene = read_scene(WITH_CHANNELS, report["robot_model"], report["robot_line"])
    prepare(world, seconds=1.0, report=dict(report), scene=scene)
    controller.Robot.created = None
    yield controller.Supervisor()
    controller.Robot.created = None
    simulations.release()


def test_the_e_puck_protos_channel_fields_tune_its_radio(robot_of_world: Any) -> None:
    assert robot_of_world.getDevice("emitter").getChannel() == 4
    assert robot_of_world.getDevice("receiver").getChannel() == 5
    # Another e-puck that sets none has the PROTO's default, as a supervisor reads it.
    other = robot_of_world.getRoot().getField("children").getMFNode(1)
    assert other.getField("receiver_channel").getSFInt32() == 1


# --- infra-red: a line of sight -------------------------------------------------------------

WALLED = """#VRML_SIM R2023b utf8
E-puck { translation -0.3 0 0 controller "x" }
Solid {
  translation 0 0 0.05
  children [ Shape { geometry DEF W Box { size 0.05 0.6 0.1 } } ]
  boundingObject USE W
}
"""


@pytest.mark.parametrize(
    ("receiver_at", "kind", "heard"),
    [
        ((0.3, 0.0, 0.0), INFRA_RED, False),  # behind the wall
        ((0.3, 0.0, 0.0), RADIO, True),  # radio goes through walls
        ((0.3, 0.0, 0.0), SERIAL, True),  # and so does serial
        ((0.3, 0.9, 0.0), INFRA_RED, True),  # past the wall's end: in sight
        ((-0.1, 0.0, 0.0), INFRA_RED, True),  # in front of the wall
    ],
)
def test_walls_stop_infra_red_packets_only(
    receiver_at: tuple[float, float, float], kind: str, heard: bool
) -> None:
    world, _ = import_wbt_text(WALLED)
    radio = Radio(LineOfSight(WallBoxes(world)))
    radio.tune(1, "receiver", 1, listening=True, kind=kind)
    radio.send(0, 1, -1, b"x", kind)
    radio.transmit({0: (-0.3, 0.0, 0.0), 1: receiver_at})
    assert bool(radio.collect(1, "receiver")) is heard


def test_an_emitter_of_type_infra_red_sends_infra_red_packets() -> None:
    world, _ = import_wbt_text(WALLED)
    pair = RadioPair()
    pair.radio.sight = LineOfSight(WallBoxes(world))
    infra_red = {"type": "infra-red"}
    receiver_from_fields("ir receiver", pair.robots[1], infra_red).enable(32)
    receiver_from_fields("radio receiver", pair.robots[1], {}).enable(32)
    emitter_from_fields("ir", pair.robots[0], infra_red).send(b"ir")
    emitter_from_fields("radio", pair.robots[0], {}).send(b"radio")
    pair.radio.transmit({0: (-0.3, 0.0, 0.0), 1: (0.3, 0.0, 0.0)})
    assert pair.radio.collect(1, "ir receiver") == [], "the wall stops it"
    assert [p.data for p in pair.radio.collect(1, "radio receiver")] == [b"radio"]


# --- the transmission type ------------------------------------------------------------------


@pytest.mark.parametrize("sent", [RADIO, SERIAL, INFRA_RED])
def test_a_packet_reaches_only_receivers_of_its_emitters_type(sent: str) -> None:
    # Webots' WbReceiver::transmitPacket: "media types must match".
    radio = Radio()
    for kind in (RADIO, SERIAL, INFRA_RED):
        radio.tune(1, kind, 1, listening=True, kind=kind)
    radio.send(0, 1, -1, b"x", sent)
    radio.transmit({0: HERE, 1: (0.3, 0.0, 0.0)})
    heard = {kind: len(radio.collect(1, kind)) for kind in (RADIO, SERIAL, INFRA_RED)}
    assert heard == {kind: int(kind == sent) for kind in heard}


@pytest.mark.parametrize(
    ("fields", "kind"),
    [
        ({}, RADIO),  # the nodes' default
        ({"type": "serial"}, SERIAL),
        ({"type": "infra-red"}, INFRA_RED),
        ({"type": "infrared"}, RADIO),  # Webots warns of an unknown type and takes "radio"
    ],
)
def test_the_type_field_gives_an_emitters_and_a_receivers_transmission_type(
    fields: dict[str, Any], kind: str
) -> None:
    pair = RadioPair()
    emitter_from_fields("e", pair.robots[0], fields).send(b"x")
    receiver_from_fields("r", pair.robots[1], fields).enable(32)
    pair.radio.tune(1, "radio", 0, listening=True)
    pair.radio.transmit({0: HERE, 1: (0.3, 0.0, 0.0)})
    assert len(pair.radio.collect(1, "r")) == 1
    assert len(pair.radio.collect(1, "radio")) == int(kind == RADIO)


def test_the_e_pucks_own_emitter_and_receiver_are_of_type_radio() -> None:
    # The E-puck PROTO sets only its Emitter's and Receiver's channel: both are "radio".
    pair = RadioPair()
    Receiver("receiver", pair.robots[1]).enable(32)
    pair.radio.tune(1, "serial", 1, listening=True, kind=SERIAL)
    Emitter("emitter", pair.robots[0]).send(b"x")
    pair.radio.transmit({0: HERE, 1: (0.3, 0.0, 0.0)})
    assert len(pair.radio.collect(1, "receiver")) == 1
    assert pair.radio.collect(1, "serial") == []


# --- infra-red: other robots' bodies and movable bodies -------------------------------------

E_PUCK_RADIUS = 0.037
IN_A_ROW = {0: (-0.3, 0.0, 0.0), 1: (0.0, 0.0, 0.0), 2: (0.3, 0.0, 0.0)}


def _heard_in_a_row(radio: Radio, infra_red: bool, poses: Any = None) -> tuple[bool, bool]:
    """Robot 0 sends one packet, infra-red or radio; whether robots 1 and 2 hear it on a
    receiver of that type."""
    kind = INFRA_RED if infra_red else RADIO
    for robot in (1, 2):
        radio.tune(robot, "receiver", 1, listening=True, kind=kind)
    radio.send(0, 1, -1, b"x", kind)
    radio.transmit(poses or IN_A_ROW)
    return bool(radio.collect(1, "receiver")), bool(radio.collect(2, "receiver"))


def test_a_third_robots_body_stops_infra_red_packets_not_the_senders_nor_the_receivers() -> None:
    sight = LineOfSight(None, [E_PUCK_RADIUS] * 3)
    assert _heard_in_a_row(Radio(sight), infra_red=True) == (True, False)
    assert _heard_in_a_row(Radio(sight), infra_red=False) == (True, True), "radio passes"
    aside = {**IN_A_ROW, 1: (0.0, 0.05, 0.0)}  # a body's edge 13 mm off the line
    assert _heard_in_a_row(Radio(sight), infra_red=True, poses=aside) == (True, True)
    grazing = {**IN_A_ROW, 1: (0.0, 0.03, 0.0)}
    assert _heard_in_a_row(Radio(sight), infra_red=True, poses=grazing) == (True, False)
    # A robot simulated as walls (no radius) has no body of its own here.
    assert _heard_in_a_row(Radio(LineOfSight(None, [None] * 3)), infra_red=True) == (True, True)


class _Objects:
    """A world's movable bodies and a supervisor's moves, as the fleet answers them."""

    def __init__(self, bodies: list[tuple[float, float, float]], moves: Any = None) -> None:
        self.bodies = bodies
        self.moves = moves or {}

    def body_poses(self) -> list[tuple[float, float, float]]:
        return self.bodies

    def node_moves(self) -> dict[int, Any]:
        return dict(self.moves)


@pytest.mark.parametrize("kind", ["box", "circle"])
def test_a_movable_body_stops_infra_red_packets_where_it_is_now(kind: str) -> None:
    body = {"kind": kind, "center": [0.6, 0.6], "size": [0.05, 0.2], "yaw": 0.0, "radius": 0.05}
    report = {"bodies": [body]}
    two = {0: IN_A_ROW[0], 2: IN_A_ROW[2]}
    objects = _Objects([(0.0, 0.0, 0.0)])  # pushed from its start onto the line
    radio = Radio(LineOfSight(None, (), report, objects))
    assert _heard_in_a_row(radio, infra_red=True, poses=two) == (False, False)
    objects.bodies = [(0.0, 0.3, 0.0)]
    radio = Radio(LineOfSight(None, (), report, objects))
    assert _heard_in_a_row(radio, infra_red=True, poses=two)[1], "off the line"


def test_a_wall_a_supervisor_moved_stops_infra_red_packets_where_it_is_now() -> None:
    world, report = import_wbt_text(WALLED)
    (line,) = report["obstacles"][0]["owners"]
    moved = {line: ((0.0, 0.0, 0.0), (0.0, 1.0, 0.0))}  # 1 m to the north
    poses = {0: (-0.3, 0.0, 0.0), 1: (0.3, 0.0, 0.0)}
    for moves, heard in (({}, False), (moved, True)):
        radio = Radio(LineOfSight(WallBoxes(world), (), report, _Objects([], moves)))
        radio.tune(1, "receiver", 1, listening=True, kind=INFRA_RED)
        radio.send(0, 1, -1, b"x", INFRA_RED)
        radio.transmit(poses)
        assert bool(radio.collect(1, "receiver")) is heard


# --- infra-red: the emitter's and the receiver's aperture -----------------------------------

FORWARD_CONE = (1.0, 0.0, 0.0, 0.5)  # along the robot's x axis, 1 rad wide


@pytest.mark.parametrize(
    ("receiver_at", "heard"),
    [
        ((0.3, 0.0, 0.0), True),  # straight ahead
        ((0.3, 0.15, 0.0), True),  # 0.46 rad off the axis
        ((0.3, 0.2, 0.0), False),  # 0.59 rad off
        ((-0.3, 0.0, 0.0), False),  # behind
    ],
)
def test_an_infra_red_emitter_sends_only_within_its_cone(
    receiver_at: tuple[float, float, float], heard: bool
) -> None:
    radio = _radio_with_receiver()
    radio.tune(1, "ir receiver", 1, listening=True, kind=INFRA_RED)
    radio.send(0, 1, -1, b"ir", INFRA_RED, FORWARD_CONE)
    radio.send(0, 1, -1, b"radio", RADIO, FORWARD_CONE)
    radio.transmit({0: HERE, 1: receiver_at})
    assert [p.data for p in radio.collect(1, "ir receiver")] == ([b"ir"] if heard else [])
    assert [p.data for p in radio.collect(1, "receiver")] == [b"radio"], "its cone is ignored"


def test_the_cone_turns_with_the_sending_robot_and_the_receivers_own() -> None:
    radio = _radio_with_receiver()
    radio.tune(1, "ir receiver", 1, listening=True, kind=INFRA_RED)
    radio.send(0, 1, -1, b"ir", INFRA_RED, FORWARD_CONE)
    radio.transmit({0: (0.0, 0.0, math.pi), 1: (-0.3, 0.0, 0.0)})  # facing the receiver
    assert len(radio.collect(1, "ir receiver")) == 1
    radio.tune(1, "ir receiver", 1, True, FORWARD_CONE, INFRA_RED)
    radio.tune(1, "receiver", 1, True, FORWARD_CONE)
    # The receiver's own cone: the sender must lie within it (0.4 rad off its axis: yes).
    for receiver_yaw, heard in ((0.0, False), (math.pi, True), (math.pi - 0.4, True),
                                (math.pi - 0.6, False)):  # fmt: skip
        radio.send(0, 1, -1, b"ir", INFRA_RED)
        radio.send(0, 1, -1, b"radio", RADIO)
        radio.transmit({0: HERE, 1: (0.3, 0.0, receiver_yaw)})
        assert [p.data for p in radio.collect(1, "ir receiver")] == ([b"ir"] if heard else [])
        assert [p.data for p in radio.collect(1, "receiver")] == [b"radio"]


TURNED = ((0.0, 1.0, 0.0), (-1.0, 0.0, 0.0), (0.0, 0.0, 1.0))  # x axis to the robot's left


@pytest.mark.parametrize(
    ("fields", "axes", "cone"),
    [
        ({"type": "infra-red", "aperture": 1.0}, None, (1.0, 0.0, 0.0, 0.5)),
        ({"type": "infra-red", "aperture": 1.0}, TURNED, (0.0, 1.0, 0.0, 0.5)),
        ({"type": "infra-red", "aperture": 2 * math.pi}, None, (1.0, 0.0, 0.0, math.pi)),
        ({"type": "infra-red", "aperture": -1}, None, None),
        ({"type": "infra-red", "aperture": 0}, None, None),  # Webots: above 0 only
        ({"type": "infra-red", "aperture": 7.0}, None, None),  # beyond 2 pi: -1
        ({"type": "infra-red"}, None, None),
        ({"type": "serial", "aperture": 1.0}, None, None),  # "for infra-red only"
        ({"aperture": 1.0}, None, None),
    ],
)
def test_the_aperture_field_gives_an_infra_red_devices_cone_around_its_x_axis(
    fields: dict[str, Any], axes: Any, cone: Any
) -> None:
    pair = RadioPair()
    emitter = emitter_from_fields("e", pair.robots[0], fields, axes)
    receiver = receiver_from_fields("r", pair.robots[0], fields, axes)
    assert emitter._cone == (pytest.approx(cone) if cone else None)
    assert receiver._cone == (pytest.approx(cone) if cone else None)
