"""A supervisor that sets a light's field (moves it, switches it off, dims it) changes what
every robot's light sensors receive, as in Webots, and the world's reset puts the light back
as the file has it (#32). mazesim read the lights once, at import: anilhimam17's T-maze
supervisor put its SpotLight 20 m away and the e-puck, still lit, took the wrong arm."""

from __future__ import annotations

import json
import math
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

from mazesim.webots import controller, simulation
from mazesim.webots.lights import irradiance, lit
from mazesim.webots.lockstep import run_world
from mazesim.webots.scene import read_scene
from supervised_world import LIGHT_WATCHER, project_of, supervisor_in

#: A lamp 10 cm ahead of a still e-puck, and a supervisor Robot that edits it.
WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
DEF LAMP PointLight { location 0.1 0 0.03 intensity 0.0075 attenuation 0 0 1 }
E-puck { translation 0 0 0 name "watcher" controller "watcher" }
Robot { name "keeper" controller "keeper" supervisor TRUE }
"""

#: Moves the lamp 20 m away at its 10th step, puts it back switched off at its 20th and resets
#: the world at its 30th.
KEEPER = """from controller import Supervisor

supervisor = Supervisor()
lamp = supervisor.getFromDef("LAMP")
location, on = lamp.getField("location"), lamp.getField("on")
step = 0
while supervisor.step(32) != -1:
    step += 1
    if step == 10:
        location.setSFVec3f([20, 0, 20])
    elif step == 20:
        location.setSFVec3f([0.1, 0, 0.03])
        on.setSFBool(False)
    elif step == 30:
        supervisor.simulationReset()
"""

WATCHER = LIGHT_WATCHER


def test_the_lights_are_made_of_the_fields_a_supervisor_set() -> None:
    scene = read_scene(WORLD)
    assert scene.light_sources is not None and scene.lights is not None
    (source,) = scene.light_sources
    assert source.line == 3 and source.numbers["location"] == (0.1, 0.0, 0.03)
    assert lit(scene.light_sources) == scene.lights
    point = (0.035, 0.0, 0.03)
    near = irradiance(scene.lights, point, 0.0)
    far = irradiance(lit(scene.light_sources, edits={3: {"location": [20.0, 0.0, 20.0]}}), point, 0)
    assert near > 100 * far > 0.0
    assert lit(scene.light_sources, edits={3: {"on": False}}) == []
    dimmed = lit(scene.light_sources, edits={3: {"intensity": [0.00375]}})
    assert irradiance(dimmed, point, 0.0) == pytest.approx(near / 2)
    assert lit(scene.light_sources, edits={9: {"on": False}}) == scene.lights  # another line


def test_a_supervisor_that_moves_and_switches_off_a_light_darkens_another_robot(
    tmp_path: Path,
) -> None:
    world = project_of(tmp_path, "lamp.wbt", WORLD, {"keeper": KEEPER, "watcher": WATCHER})
    watcher, keeper = run_world(str(world), seconds=1.6, noise=False).robots
    assert [watcher.exit_status, keeper.exit_status] == [0, 0], [watcher.error, keeper.error]
    readings = json.loads((tmp_path / "controllers" / "watcher" / "readings.json").read_text())
    lit_reading = readings[0]
    assert 1000 < lit_reading < 3000  # the lamp 10 cm ahead: between 1 and 2 W/m^2
    # Each edit, made after the keeper's 10th, 20th and 30th step, is seen from the next step.
    assert readings[:10] == [lit_reading] * 10
    assert readings[10:20] == [4095.0] * 10  # 20 m away: dark
    assert readings[20:30] == [4095.0] * 10  # back, but off
    assert readings[30:] == [lit_reading] * (len(readings) - 30)  # the reset: as in the file


@pytest.fixture
def own_light_sensor(tmp_path: Path) -> Iterator[Callable[[str], tuple[Any, Any]]]:
    """Prepares a world's text with its e-puck as its own supervisor; gives the supervisor and
    its ls0, enabled, after a first step."""

    def prepared(text: str) -> tuple[Any, Any]:
        supervisor = supervisor_in(tmp_path, text)
        ls0 = supervisor.getDevice("ls0")
        ls0.enable(32)
        supervisor.step(32)
        return supervisor, ls0

    yield prepared
    controller.Robot.created = None
    simulation.release()


def test_a_supervisor_robot_sees_its_own_edit_of_a_light(
    own_light_sensor: Callable[[str], tuple[Any, Any]],
) -> None:
    text = WORLD.replace('controller "watcher"', 'controller "<extern>" supervisor TRUE')
    supervisor, ls0 = own_light_sensor(text)
    before = ls0.getValue()
    supervisor.getFromDef("LAMP").getField("intensity").setSFFloat(0.0)
    supervisor.step(32)
    assert before < 3000 and ls0.getValue() > before + 1000


def test_irradiance_of_an_edited_light_follows_webots_formula() -> None:
    scene = read_scene(WORLD)
    moved = lit(scene.light_sources, edits={3: {"location": [0.2, 0.0, 0.03]}})
    # A point light of intensity 0.0075 and attenuation 1/d^2 straight ahead 0.2 m away.
    assert irradiance(moved, (0.0, 0.0, 0.03), 0.0) == pytest.approx(0.0075 / 0.2**2)
    assert math.isclose(irradiance(moved, (0.0, 0.0, 0.03), math.pi), 0.0)


#: The lamp held by a Solid 10 cm ahead of an e-puck that is its own supervisor.
HELD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
DEF POST Solid {
  translation 0.1 0 0
  children [
    PointLight { location 0 0 0.03 intensity 0.0075 attenuation 0 0 1 }
  ]
}
E-puck { translation 0 0 0 name "watcher" controller "<extern>" supervisor TRUE }
"""


def test_a_light_moves_with_the_node_that_holds_it() -> None:
    scene = read_scene(HELD)
    assert scene.light_sources is not None and scene.lights is not None
    (source,) = scene.light_sources
    assert source.holders == {3}  # the Solid on line 3
    assert scene.lights[0].position == pytest.approx((0.1, 0.0, 0.03))
    (moved,) = lit(scene.light_sources, edits={3: {"translation": [2.0, 1.0, 0.0]}}) or []
    assert moved.position == pytest.approx((2.0, 1.0, 0.03))
    turned = {3: {"rotation": [0.0, 1.0, 0.0, math.pi / 2]}}  # the location's z turns to x
    (tilted,) = lit(scene.light_sources, edits=turned) or []
    assert tilted.position == pytest.approx((0.13, 0.0, 0.0))


def test_a_supervisor_that_moves_the_solid_holding_a_light_moves_the_light(
    own_light_sensor: Callable[[str], tuple[Any, Any]],
) -> None:
    supervisor, ls0 = own_light_sensor(HELD)
    before = ls0.getValue()
    supervisor.getFromDef("POST").getField("translation").setSFVec3f([20.0, 0.0, 0.0])
    supervisor.step(32)
    away = ls0.getValue()
    supervisor.simulationReset()
    supervisor.step(32)
    supervisor.step(32)
    assert 1000 < before < 3000 and away == 4095.0
    assert ls0.getValue() == before  # the reset put the Solid back
