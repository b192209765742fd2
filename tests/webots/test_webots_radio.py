"""Emitter and Receiver between robots: Webots' channels, range, queue and next-step delivery."""

from __future__ import annotations

import math
import struct
from collections.abc import Iterator
from typing import Any

import pytest

from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.importer import import_wbt_text
from mazesim.webots.radio import Radio
from mazesim.webots.radio_devices import Emitter, Receiver, emitter_from_fields
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


def test_a_list_of_numbers_is_read_back_as_floats_ints_or_bools() -> None:
    """Webots' Python Receiver reads a packet as doubles (``getFloats``, what ``Emitter.send``
    of a list of numbers sends), 4-byte ints (``getInts``) or booleans (``getBools``)."""
    pair = RadioPair()
    emitter = Emitter("emitter", pair.robots[0])
    receiver = Receiver("receiver", pair.robots[1])
    pair.receivers.append(receiver)
    receiver.enable(int(pair.robots[1].basic_time_step_ms))
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


def test_a_disabled_receiver_hears_nothing_and_buffers_overflow_by_losing_packets() -> None:
    pair = RadioPair()
    basic = int(pair.robots[1].basic_time_step_ms)
    emitter = Emitter("emitter", pair.robots[0])
    receiver = Receiver("receiver", pair.robots[1], buffer_size=6)
    pair.receivers.append(receiver)
    emitter.send("lost")
    pair.step()
    receiver.enable(basic)
    pair.step()
    assert receiver.getQueueLength() == 0, "sent while the receiver was disabled"
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
E-puck { controller "x" emitter_channel 4 receiver_channel 5 }
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
    ("receiver_at", "infra_red", "heard"),
    [
        ((0.3, 0.0, 0.0), True, False),  # behind the wall
        ((0.3, 0.0, 0.0), False, True),  # radio goes through walls
        ((0.3, 0.9, 0.0), True, True),  # past the wall's end: in sight
        ((-0.1, 0.0, 0.0), True, True),  # in front of the wall
    ],
)
def test_walls_stop_infra_red_packets_only(
    receiver_at: tuple[float, float, float], infra_red: bool, heard: bool
) -> None:
    world, _ = import_wbt_text(WALLED)
    radio = Radio(WallBoxes(world))
    radio.tune(1, "receiver", 1, listening=True)
    radio.send(0, 1, -1, b"x", infra_red)
    radio.transmit({0: (-0.3, 0.0, 0.0), 1: receiver_at})
    assert bool(radio.collect(1, "receiver")) is heard


def test_an_emitter_of_type_infra_red_sends_infra_red_packets() -> None:
    world, _ = import_wbt_text(WALLED)
    pair = RadioPair()
    pair.radio.walls = WallBoxes(world)
    pair.radio.tune(1, "receiver", 0, listening=True)
    fields = {"type": "infra-red"}
    emitter_from_fields("ir", pair.robots[0], fields).send(b"ir")
    emitter_from_fields("radio", pair.robots[0], {}).send(b"radio")
    pair.radio.transmit({0: (-0.3, 0.0, 0.0), 1: (0.3, 0.0, 0.0)})
    assert [p.data for p in pair.radio.collect(1, "receiver")] == [b"radio"]
