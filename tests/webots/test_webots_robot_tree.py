"""Devices anywhere in a plain ``Robot`` e-puck's tree (saved expanded, with extra Compass,
TouchSensor, GPS and Camera children) are the robot's devices under their Webots names, and the
robot is recognised as the e-puck once, without contradiction; Webots 7's ``EPuck`` too."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import mazesim
from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.importer import import_wbt, import_wbt_text, robot_warnings

WORLD = Path(__file__).resolve().parents[1] / "data" / "controllers" / "worlds"
PLAIN = WORLD / "plain-robot-epuck-devices.wbt"


def test_plain_robot_children_devices_are_listed_with_their_names() -> None:
    _, report = import_wbt(PLAIN)
    assert report["robot_model"] == "E-puck" and robot_warnings(report) == []
    devices = {d["name"]: d for d in report["extension_devices"]}
    # The e-puck's own devices (ps0, the wheel motor and sensor) are not listed again.
    assert set(devices) == {"compass", "bumper", "gps", "front camera"}
    assert devices["compass"]["type"] == "Compass" and devices["compass"]["slot"] == "children"
    assert devices["compass"]["translation"] == [0.0, 0.0, 0.04]
    assert devices["front camera"]["fields"]["width"] == 32


def test_controller_gets_the_children_devices() -> None:
    world, report = import_wbt(PLAIN)
    prepare(world, seconds=1.0, report=report)
    controller.Robot.created = None
    try:
        robot = controller.Robot()
        compass = robot.getDevice("compass")
        assert isinstance(compass, controller.Compass)
        compass.enable(32)
        assert isinstance(robot.getDevice("bumper"), controller.TouchSensor)
        assert isinstance(robot.getDevice("gps"), controller.GPS)
        assert robot.getDevice("front camera").getWidth() == 32
        robot.step(32)
        north = compass.getValues()
        assert abs(north[0] ** 2 + north[1] ** 2 - 1.0) < 0.05
    finally:
        controller.Robot.created = None
        simulations.release()


def test_webots_7_epuck_is_the_e_puck() -> None:
    _, report = import_wbt_text(
        "#VRML_SIM V7.4.3 utf8\nEPuck { translation 0.2 0 0.1 }\n", "old.wbt"
    )
    assert report["robot_model"] == "E-puck" and report["robot_profile"] == "e-puck"
    assert robot_warnings(report) == []
    assert not any("not an e-puck" in w for w in report["warnings"])


GROUND_SLOT = """#VRML_SIM R2023b utf8
E-puck {
  groundSensorsSlot [
    DistanceSensor {
      translation 0.01 0 0.005
      rotation 0 1 0 1.5708
      name "ir0"
      type "infra-red"
      lookupTable [ 0 1000 0, 0.05 0 0 ]
    }
  ]
}
"""


def test_downward_ground_sensor_reads_the_line() -> None:
    _, report = import_wbt_text(GROUND_SLOT, "ground.wbt")
    (device,) = report["extension_devices"]
    assert device["name"] == "ir0" and abs(device["pitch"] - math.pi / 2) < 1e-3
    prepare(mazesim.load_world("line-follow"), seconds=2.0, noise=False, report=report)
    controller.Robot.created = None
    try:
        robot = controller.Robot()
        sensor = robot.getDevice("ir0")
        sensor.enable(32)
        simulation = simulations.current()
        readings = []
        for y in (0.22, 0.30):  # the black line (reflectance 0.2) at y = 0.22, white beside it
            # The PROTO mounts the slot 3 cm ahead, 0.3 mm up: the sensor is 4 cm ahead.
            simulation.simulator.set_pose(0.66, y, 0.0)
            robot.step(32)
            readings.append(sensor.getValue())
        on_line, off_line = readings
        # 5.3 mm above the floor: 894 on white (d = 5.3 mm), 470 on the line (d = 5.3 mm / 0.2).
        assert off_line == pytest.approx(894, abs=5) and on_line == pytest.approx(470, abs=5)
    finally:
        controller.Robot.created = None
        simulations.release()


def test_supervisor_reads_a_proto_instances_own_fields(tmp_path: Path) -> None:
    world_file = tmp_path / "beacon.wbt"
    world_file.write_text(
        "#VRML_SIM R2023b utf8\n"
        "DEF BEACON Beacon { translation 0.3 0 0 receiver_channel 2 range 0.25 enabled TRUE "
        'label "b1" tint 1 0 0\n  hidden position_0_0 4\n}\n'
        'E-puck { supervisor TRUE controller "<extern>" }\n'
    )
    from mazesim.webots.scene import read_scene

    prepare(
        mazesim.load_world(str(world_file)), seconds=1.0, scene=read_scene(world_file.read_text())
    )
    controller.Robot.created = None
    try:
        supervisor = controller.Supervisor()
        beacon = supervisor.getFromDef("BEACON")
        channel = beacon.getField("receiver_channel")
        assert channel.getType() == controller.Field.SF_INT32 and channel.getSFInt32() == 2
        assert beacon.getField("range").getSFFloat() == 0.25
        assert beacon.getField("enabled").getSFBool() is True
        assert beacon.getField("label").getSFString() == "b1"
        assert beacon.getField("tint").getSFColor() == [1.0, 0.0, 0.0]
        assert beacon.getField("position_0_0") is None  # engine state, not a field
        channel.setSFInt32(5)
        assert channel.value == 5
    finally:
        controller.Robot.created = None
        simulations.release()


# An e-puck saved expanded (R2023b) whose Emitter its author set to channel 99 and whose
# Receiver to channel 3, a range on neither: Webots reads the nodes' own fields, with the
# Emitter's default range (-1, no limit); the e-puck's device names stay.
EXPANDED_RADIO = """#VRML_SIM R2023b utf8
Robot {
  children [
    DistanceSensor { translation 0.03 0.01 0.03 name "ps0" }
    DEF EPUCK_RECEIVER Receiver {
      channel 3
    }
    DEF EPUCK_EMITTER Emitter {
      channel 99
      bufferSize 64
    }
  ]
  name "r0"
  model "GCtronic e-puck"
  controller "<extern>"
}
"""


def test_an_expanded_e_pucks_radio_nodes_keep_their_own_fields() -> None:
    _, report = import_wbt_text(EXPANDED_RADIO, "expanded.wbt")
    assert report["robot_model"] == "E-puck"
    prepare(mazesim.World.builtin("arena"), seconds=1.0, report=report)
    controller.Robot.created = None
    try:
        robot = controller.Robot()
        emitter, receiver = robot.getDevice("emitter"), robot.getDevice("receiver")
        assert (emitter.getChannel(), emitter.getRange(), emitter.getBufferSize()) == (99, -1, 64)
        assert receiver.getChannel() == 3
    finally:
        controller.Robot.created = None
        simulations.release()
