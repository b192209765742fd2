"""The lights of Webots' light-holding PROTOs (TexturedBackgroundLight, ConstructionLamp) as
the e-puck's light sensors see them, and a world whose lights are all off."""

from __future__ import annotations

import math
from collections.abc import Iterator

import pytest

import mazesim
from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.lights import DEFAULT_IRRADIANCE, irradiance
from mazesim.webots.scene import read_scene

#: A dark world lit by one lamp: the background light's luminosity is negative (no direct light,
#: its ambient 1 left), and a ConstructionLamp 0.3 m to the robot's left (+y), 4 cm up, shines
#: along -y, back at it.
LAMP_WORLD = """#VRML_SIM R2025a utf8
WorldInfo { basicTimeStep 32 }
TexturedBackgroundLight {
  texture "mountains"
  luminosity -20
}
ConstructionLamp {
  translation 0 0.3 0.04
  rotation 0 0 1 -1.5708
  spotLightIntensity 0.1
  spotLightRadius 1
}
"""


@pytest.fixture(autouse=True)
def release() -> Iterator[None]:
    yield
    controller.Robot.created = None
    simulations.release()


def light_readings(text: str) -> list[float]:
    """The eight light sensors of an e-puck at the arena's start after one step, noise-free."""
    prepare(mazesim.load_world("arena"), seconds=1.0, noise=False, scene=read_scene(text))
    controller.Robot.created = None
    robot = controller.Robot()
    sensors = [robot.getDevice(f"ls{i}") for i in range(8)]
    for sensor in sensors:
        sensor.enable(32)
    robot.step(32)
    return [sensor.getValue() for sensor in sensors]


def test_a_negative_luminosity_leaves_the_background_ambient_and_a_lamp_lights() -> None:
    scene = read_scene(LAMP_WORLD)
    assert scene.lights is not None and len(scene.lights) == 2
    background, lamp = scene.lights
    assert (background.intensity, background.ambient) == (0.0, 1.0)
    # The lamp's SpotLight: 7 mm along its +x (turned to -y) and 5 mm up, shining along -y.
    assert lamp.position == pytest.approx((0.0, 0.293, 0.045), abs=1e-4)
    assert lamp.beam == pytest.approx((0.0, -1.0, 0.0), abs=1e-4)
    assert (lamp.intensity, lamp.radius, lamp.attenuation) == (0.1, 1.0, (0.0, 0.0, 1.0))
    values = light_readings(LAMP_WORLD)
    # ls5 faces the lamp and reads it; ls2 faces away and reads the ambient 1 W/m^2 alone, the
    # table's dark end (4095), not the default of a world without lights (2047.5).
    assert values[5] == min(values) and values[5] < 3500.0
    assert values[2] == pytest.approx(4095.0)


def test_the_background_light_of_each_texture() -> None:
    mountains = read_scene("#VRML_SIM R2025a utf8\nTexturedBackgroundLight { luminosity 2 }\n")
    assert mountains.lights is not None
    (sun,) = mountains.lights
    # The PROTO's mountains light, (-0.6, -1, 0.55) y up, is (0.55, -0.6, -1) in ENU.
    norm = math.sqrt(0.6**2 + 1.0 + 0.55**2)
    assert sun.direction == pytest.approx((0.55 / norm, -0.6 / norm, -1.0 / norm))
    assert (sun.intensity, sun.ambient) == pytest.approx((5.4, 1.0))
    # Webots adds the ambient intensity unscaled by the intensity: facing away from the sun
    # (east, the sun shining from the west) a sensor gets the ambient alone.
    assert irradiance(mountains.lights, (0.0, 0.0, 0.03), 0.0) == pytest.approx(1.0)
    west = irradiance(mountains.lights, (0.0, 0.0, 0.03), math.pi)
    assert west == pytest.approx(1.0 + 5.4 * 0.55 / norm)
    factory = read_scene('#VRML_SIM R2025a utf8\nTexturedBackgroundLight { texture "factory" }\n')
    assert factory.lights == []
    assert irradiance(factory.lights, (0.0, 0.0, 0.03), 0.0) == 0.0
    assert read_scene("#VRML_SIM R2025a utf8\nWorldInfo { }\n").lights is None
    assert irradiance(None, (0.0, 0.0, 0.03), 0.0) == DEFAULT_IRRADIANCE


def test_a_spot_light_gives_nothing_outside_its_cut_off_angle() -> None:
    spot = """#VRML_SIM R2025a utf8
SpotLight {
  location 0 0.3 0.03
  direction 1 0 0
  cutOffAngle 0.5
  attenuation 0 0 1
  intensity 0.1
}
"""
    values = light_readings(spot)
    # The robot is at the origin, 90 degrees off the spot's beam: every sensor reads the dark.
    assert values == pytest.approx([4095.0] * 8)


def test_lights_inside_groups_and_poses_are_placed_by_their_parents() -> None:
    """The lamp of ``LAMP_WORLD`` held in a Transform 0.3 m along +y, turned a quarter turn
    (its own pose now relative to the Transform), and a PointLight in a Group in a Pose: each
    is where its parents' poses put it, as Webots places it; the lamp lights the robot as the
    one at the top of the file does."""
    nested = """#VRML_SIM R2025a utf8
WorldInfo { basicTimeStep 32 }
TexturedBackgroundLight {
  texture "mountains"
  luminosity -20
}
Transform {
  translation 0 0.3 0
  rotation 0 0 1 -1.5708
  children [
    ConstructionLamp {
      translation 0 0 0.04
      spotLightIntensity 0.1
      spotLightRadius 1
    }
  ]
}
"""
    pose = """Pose {
  translation 1 2 0
  rotation 0 0 1 1.5708
  children [ Group { children [ PointLight { location 0.5 0 0.1 } ] } ]
}
"""
    scene = read_scene(nested + pose)
    assert scene.lights is not None and len(scene.lights) == 3
    _, lamp, point = scene.lights
    assert lamp.position == pytest.approx((0.0, 0.293, 0.045), abs=1e-4)
    assert lamp.beam == pytest.approx((0.0, -1.0, 0.0), abs=1e-4)
    assert point.position == pytest.approx((1.0, 2.5, 0.1), abs=1e-4)
    assert light_readings(nested) == pytest.approx(light_readings(LAMP_WORLD), abs=1e-6)
