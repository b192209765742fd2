"""A light that a robot holds moves with that robot, as every node under a Solid does in
Webots: an e-puck carrying a PointLight (a beacon the others follow by their light sensors)
lights the others from where it stands now, not from where the world file put it (#32)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from mazesim.webots.lights import Light, carried, irradiance
from mazesim.webots.lockstep import run_world
from mazesim.webots.scene import read_scene
from supervised_world import LIGHT_WATCHER, cruising_controller, project_of

#: A lamp on the floor's plane, and a beacon e-puck holding a PointLight 5 cm above its centre
#: that drives 5 rad/s straight ahead (+x), towards a watcher 0.5 m ahead that stands still.
WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
PointLight { location 0 -3 0.05 intensity 0.01 }
E-puck {
  translation 0 0 0
  name "beacon"
  controller "beacon"
  turretSlot [
    PointLight { location 0 0 0.0014 intensity 0.05 attenuation 0 0 1 }
  ]
}
E-puck { translation 0.5 0 0 rotation 0 0 1 3.14159 name "watcher" controller "watcher" }
"""

BEACON = cruising_controller(5.0)

WATCHER = LIGHT_WATCHER


def test_a_light_a_robot_holds_is_its_robots_and_is_carried_with_it() -> None:
    scene = read_scene(WORLD)
    assert scene.lights is not None
    lamp, beacon = scene.lights
    assert lamp.carrier is None
    assert beacon.carrier == 4  # the line of the E-puck node that holds it
    # Held in the turret slot, 48.6 mm up and 9.5 mm behind the centre, plus its location.
    assert beacon.position == pytest.approx((-0.0095, 0.0, 0.05), abs=1e-4)
    light = Light((1.0, 0.0, 0.05), None, beam=(1.0, 0.0, 0.0), carrier=4)
    moved = carried(light, (0.0, 0.0, 0.0), (1.0, 1.0, math.pi / 2))
    assert moved.position == pytest.approx((1.0, 2.0, 0.05))
    assert moved.beam == pytest.approx((0.0, 1.0, 0.0))


def test_a_watcher_sees_a_beacon_robots_light_come_closer(tmp_path: Path) -> None:
    world = project_of(tmp_path, "beacon.wbt", WORLD, {"beacon": BEACON, "watcher": WATCHER})
    beacon, watcher = run_world(str(world), seconds=3.2, noise=False).robots
    assert [beacon.exit_status, watcher.exit_status] == [0, 0], [beacon.error, watcher.error]
    readings = json.loads((tmp_path / "controllers" / "watcher" / "readings.json").read_text())
    # ls0 reads the less the more light it receives (4095 in the dark): the beacon's light
    # comes closer at every step, so the watcher's readings fall.
    assert readings[-1] < readings[0] - 100
    # The last reading is the one the beacon's light gives from where the beacon now stands.
    scene = read_scene(WORLD)
    assert scene.lights is not None
    x, _, _ = beacon.final_pose
    assert x > 0.1
    now = [
        carried(light, (0.0, 0.0, 0.0), beacon.final_pose) if light.carrier else light
        for light in scene.lights
    ]
    before = irradiance(scene.lights, (0.47, 0.0, 0.034), math.pi)
    after = irradiance(now, (0.47, 0.0, 0.034), math.pi)
    assert after > 2 * before
