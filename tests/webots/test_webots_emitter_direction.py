"""A Receiver's emitter direction in the receiver's own frame, as Webots gives it: the robot's
inside as the world writes it (Z-up since R2022a, Y-up before), turned by the receiver's mount
and its own ``rotation``."""

from __future__ import annotations

import math
from typing import Any

import pytest

from mazesim.webots.importer import import_wbt_text
from mazesim.webots.radio_devices import Emitter, Receiver, receiver_from_fields
from mazesim.webots.scene import read_scene
from radio_pair import RadioPair

#: A plain Robot of a world written in Webots' old NUE frame, its receivers among its children.
PLAIN_ROBOT_NUE = """#VRML_SIM R2021a utf8
WorldInfo { coordinateSystem "NUE" }
DEF epuck0 Robot {
  rotation 0 1 0 -1.5708
  children [
    Receiver { name "receiver2" channel 2 }
    Transform {
      rotation 0 1 0 1.5708
      children [ Receiver { name "receiver3" } ]
    }
  ]
  name "epuck0"
  controller "flocking"
}
"""


class _Listening:
    """An e-puck facing north 0.3 m east of another that emits: the emitter is on its left."""

    def __init__(self, text: str) -> None:
        pair = RadioPair(heading=math.pi / 2)
        self.pair, self.robots = pair, pair.robots
        self.robots[1].scene = read_scene(text)
        _, self.report = import_wbt_text(text)

    def entry(self, name: str) -> dict[str, Any]:
        """The import report's extension device of this name."""
        devices = self.report["extension_devices"]
        return next(dict(d) for d in devices if d["name"] == name)

    def direction(self, receiver: Receiver) -> list[float]:
        """What the receiver reads of one packet from the other e-puck."""
        receiver.enable(int(self.robots[1].basic_time_step_ms))
        Emitter("emitter", self.robots[0], channel=-1).send("ping")
        self.pair.receivers = [receiver]
        self.pair.step()
        return receiver.getEmitterDirection()

    def extension_receiver(self, name: str) -> Receiver:
        entry = self.entry(name)
        return receiver_from_fields(name, self.robots[1], {"channel": -1}, entry.get("axes"))


def test_the_e_puck_protos_receiver_since_r2022a_reads_x_forward_y_left() -> None:
    listening = _Listening("#VRML_SIM R2023b utf8\nE-puck { }\n")
    receiver = Receiver("receiver", listening.robots[1], channel=-1)
    assert listening.direction(receiver) == pytest.approx([0.0, 1.0, 0.0], abs=1e-6)


def test_the_e_puck_protos_receiver_before_r2022a_reads_x_right_y_up_z_back() -> None:
    """The Y-up PROTO's receiver: an emitter on the robot's left is at -x."""
    listening = _Listening("#VRML_SIM R2018b utf8\nE-puck { }\n")
    receiver = Receiver("receiver", listening.robots[1], channel=-1)
    assert listening.direction(receiver) == pytest.approx([-1.0, 0.0, 0.0], abs=1e-6)


def test_a_receiver_in_the_turned_ground_slot_before_r2022a_reads_x_down_y_right() -> None:
    """The Y-up PROTO turns its groundSensorsSlot -1.57 rad about its back axis: the Reynolds
    flocks of that time read their neighbours' bearing from y and z (``x = -d[2]``,
    ``y = -d[1]``: forward and left)."""
    text = '#VRML_SIM R2018b utf8\nE-puck { groundSensorsSlot [ Receiver { name "r2" } ] }\n'
    listening = _Listening(text)
    direction = listening.direction(listening.extension_receiver("r2"))
    assert direction == pytest.approx([0.0, -1.0, 0.0], abs=2e-3)


def test_a_receivers_own_rotation_in_a_slot_turns_its_frame() -> None:
    text = (
        "#VRML_SIM R2023b utf8\n"
        'E-puck { turretSlot [ Receiver { name "r2" rotation 0 0 1 1.5708 } ] }\n'
    )
    listening = _Listening(text)
    direction = listening.direction(listening.extension_receiver("r2"))
    # Its x axis points to the robot's left, at the emitter.
    assert direction == pytest.approx([1.0, 0.0, 0.0], abs=1e-4)


def test_a_plain_robots_receivers_in_an_nue_world_read_in_its_y_up_inside() -> None:
    listening = _Listening(PLAIN_ROBOT_NUE)
    # Unturned among its children: x right, y up, z back.
    unturned = listening.direction(listening.extension_receiver("receiver2"))
    assert unturned == pytest.approx([-1.0, 0.0, 0.0], abs=1e-4)
    # Turned a quarter left about up by a Transform: x forward, z right.
    turned = listening.direction(listening.extension_receiver("receiver3"))
    assert turned == pytest.approx([0.0, 0.0, -1.0], abs=1e-4)


def test_malformed_axes_leave_the_receiver_unturned_in_the_robots_inside() -> None:
    listening = _Listening("#VRML_SIM R2023b utf8\nE-puck { }\n")
    for axes in (None, [[1.0, 0.0]], [[math.nan, 0, 0], [0, 1, 0], [0, 0, 1]], "xyz"):
        receiver = receiver_from_fields("r", listening.robots[1], {"channel": -1}, axes)
        assert receiver._axes == ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
