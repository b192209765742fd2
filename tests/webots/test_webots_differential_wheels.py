"""A Webots 5-8 ``DifferentialWheels`` robot drives by its world node's fields, as Webots'
controller library and node do (``mazesim.webots.differential_drive``): ``speedUnit``,
``maxSpeed`` (rad/s: Webots' error beyond, no clamp of the speed set), ``encoderResolution`` and
``encoderNoise`` (negative: the encoders do not count; positive: each step's count is off by a
uniform factor), the node's defaults where it writes none; a C controller and its Python twin
alike."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.differential_drive import EPUCK_WHEELS, WheelsNode
from mazesim.webots.importer import import_wbt_text
from mazesim.webots.scene import read_scene
from native_controllers import NEEDS_COMPILERS, run_twins, write_source

ARENA = "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\nRectangleArena { floorSize 1 1 }\n"


def differential_wheels_world(fields: str, header: str = "#VRML_SIM R2023b utf8") -> str:
    """An e-puck as a ``DifferentialWheels`` node writing ``fields``, in the middle of a 1 m
    arena, facing +x."""
    return ARENA.replace("#VRML_SIM R2023b utf8", header) + (
        "DifferentialWheels {\n  translation 0 0 0\n  children [\n"
        '    Solid { name "left wheel" translation 0 0.026 0.02 }\n'
        '    Solid { name "right wheel" translation 0 -0.026 0.02 }\n'
        f'  ]\n  name "e-puck"\n  controller "<extern>"\n{fields}}}\n'
    )


#: Fields unlike the e-puck's: 0.01 rad/s a unit, 5 rad/s at most, 100 counts a radian.
OWN_FIELDS = "  speedUnit 0.01\n  maxSpeed 5\n  encoderResolution 100\n  encoderNoise 0\n"


pytestmark = pytest.mark.usefixtures("fresh_robot")


def drive(text: str, *, noise: bool = False, seed: int = 0) -> controller.DifferentialWheels:
    """A ``DifferentialWheels`` controller's robot in the world ``text``."""
    world, report = import_wbt_text(text, "old.wbt")
    scene = read_scene(text, report.get("robot_model"), report.get("robot_line"))
    prepare(world, seconds=10.0, noise=noise, seed=seed, report=report, scene=scene)
    return controller.DifferentialWheels()


def test_the_scene_reads_the_node_s_fields_and_webots_defaults() -> None:
    own = read_scene(differential_wheels_world(OWN_FIELDS)).wheels_node
    assert own == WheelsNode(speed_unit=0.01, max_speed=5.0, encoder_resolution=100.0,
                             encoder_noise=0.0)  # fmt: skip
    bare = read_scene(differential_wheels_world("")).wheels_node
    assert bare == WheelsNode(speed_unit=1.0, max_speed=10.0, encoder_resolution=-1.0,
                              encoder_noise=-1.0)  # fmt: skip
    # Webots 6 made speedUnit's default 1 (0.1 before): a Webots 5 file's 1 reads as 0.1.
    old = read_scene(differential_wheels_world("", "#VRML_SIM V5.10.0 utf8")).wheels_node
    assert old is not None and old.speed_unit == 0.1
    six = read_scene(differential_wheels_world("", "#VRML_SIM V6.4.0 utf8")).wheels_node
    assert six is not None and six.speed_unit == 1.0
    # Another robot node says nothing: Webots 8's EPuck PROTO's fields serve.
    assert read_scene(ARENA + 'E-puck { controller "<extern>" }\n').wheels_node is None


def test_an_e_puck_without_the_node_drives_by_webots_8_s_epuck_fields() -> None:
    robot = drive(ARENA + 'E-puck { controller "<extern>" }\n')
    assert (robot.getSpeedUnit(), robot.getMaxSpeed()) == (0.00628, 6.28)
    assert robot._equipment.differential_drive.node == EPUCK_WHEELS


def test_encoders_count_the_node_s_resolution_a_radian_and_speeds_are_in_its_units(
    capsys: pytest.CaptureFixture[str],
) -> None:
    robot = drive(differential_wheels_world(OWN_FIELDS))
    assert math.isnan(robot.getLeftSpeed()) and math.isnan(robot.getRightSpeed())
    robot.enableEncoders(32)
    robot.setSpeed(300, -300)  # 3 rad/s forward and back: a turn on the spot
    for _ in range(5):
        robot.step(32)
    angles = robot._simulation.wheel_angles()
    assert angles[0] == pytest.approx(5 * 0.032 * 3.0, rel=1e-9)
    assert robot.getLeftEncoder() == pytest.approx(100.0 * angles[0], rel=1e-12)
    assert robot.getRightEncoder() == pytest.approx(100.0 * angles[1], rel=1e-12)
    assert capsys.readouterr().err == ""
    # 600 units is 6 rad/s, above maxSpeed 5: Webots' error, and the speed kept as set.
    robot.setSpeed(600, 100)
    assert capsys.readouterr().err.strip() == (
        "Error: wb_differential_wheels_set_speed(600,100) overflows maxSpeed/speedUnit: 5/0.01=500."
    )
    assert (robot.getLeftSpeed(), robot.getRightSpeed()) == (600.0, 100.0)
    robot.setEncoders(7.0, -7.0)
    assert (robot.getLeftEncoder(), robot.getRightEncoder()) == (7.0, -7.0)
    before = robot._simulation.wheel_angles()
    robot.step(32)
    turned = [a - b for a, b in zip(robot._simulation.wheel_angles(), before)]
    assert turned[0] == pytest.approx(0.032 * 6.0, rel=1e-9), "6 rad/s: under the motors' 6.28"
    assert robot.getLeftEncoder() == pytest.approx(7.0 + 100.0 * turned[0], rel=1e-12)


def test_a_node_without_encoder_fields_never_counts_as_webots_default_says(
    capsys: pytest.CaptureFixture[str],
) -> None:
    robot = drive(differential_wheels_world(""))
    robot.enableEncoders(32)
    robot.setSpeed(3, 3)  # speedUnit 1: 3 rad/s
    for _ in range(10):
        robot.step(32)
    assert robot._simulation.wheel_angles()[0] == pytest.approx(0.96, rel=1e-9)
    assert (robot.getLeftEncoder(), robot.getRightEncoder()) == (0.0, 0.0)
    robot.setEncoders(4.0, 5.0)
    robot.step(32)
    assert (robot.getLeftEncoder(), robot.getRightEncoder()) == (4.0, 5.0)
    robot.setSpeed(math.nan, 1.0)
    assert "invalid NaN value" in capsys.readouterr().err
    assert robot.getLeftSpeed() == 3.0


def test_noisy_encoders_stray_within_the_node_s_noise_and_repeat_with_the_seed() -> None:
    fields = OWN_FIELDS.replace("encoderNoise 0", "encoderNoise 0.2")

    def counts(seed: int) -> tuple[list[float], float]:
        robot = drive(differential_wheels_world(fields), noise=True, seed=seed)
        robot.enableEncoders(32)
        robot.setSpeed(300, 300)
        for _ in range(20):
            robot.step(32)
        exact = 100.0 * robot._simulation.wheel_angles()[0]
        seen = [robot.getLeftEncoder(), robot.getRightEncoder()]
        controller.Robot.created = None
        simulations.release()
        return seen, exact

    seen, exact = counts(1)
    assert all(0.8 * exact <= c <= 1.2 * exact and c != exact for c in seen)
    assert seen[0] != seen[1], "each wheel has its own draws"
    assert counts(1)[0] == seen and counts(2)[0] != seen


#: A Webots 8 controller reading the node's fields, driving and reading its encoders.
TWIN_C = """#include <stdio.h>
#include <webots/robot.h>
#include <webots/differential_wheels.h>
int main(void) {
  wb_robot_init();
  printf("speeds %g %g\\n", wb_differential_wheels_get_left_speed(),
         wb_differential_wheels_get_right_speed());
  printf("unit %g max %g\\n", wb_differential_wheels_get_speed_unit(),
         wb_differential_wheels_get_max_speed());
  wb_differential_wheels_enable_encoders(64);
  int step = 0;
  while (wb_robot_step(32) != -1) {
    step++;
    wb_differential_wheels_set_speed(step < 10 ? 300 : 600, 200);
    printf("%d %.9f %.9f\\n", step, wb_differential_wheels_get_left_encoder(),
           wb_differential_wheels_get_right_encoder());
  }
  wb_robot_cleanup();
  return 0;
}
"""
TWIN_PY = """from controller import DifferentialWheels
robot = DifferentialWheels()
print("speeds %g %g" % (robot.getLeftSpeed(), robot.getRightSpeed()))
print("unit %g max %g" % (robot.getSpeedUnit(), robot.getMaxSpeed()))
robot.enableEncoders(64)
step = 0
while robot.step(32) != -1:
    step += 1
    robot.setSpeed(300 if step < 10 else 600, 200)
    print("%d %.9f %.9f" % (step, robot.getLeftEncoder(), robot.getRightEncoder()))
"""


@NEEDS_COMPILERS
def test_a_c_controller_drives_by_the_node_s_fields_as_its_python_twin(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    text = differential_wheels_world(OWN_FIELDS)
    world, report = import_wbt_text(text, "old.wbt")
    scene = read_scene(text, report.get("robot_model"), report.get("robot_line"))
    c_source = write_source(tmp_path, "twin_c", TWIN_C)
    python_source = write_source(tmp_path, "twin_py", TWIN_PY, ".py")
    (in_c, in_python), (c_out, python_out) = run_twins(
        capfd, c_source, python_source, world=world, report=report, scene=scene, seconds=0.64,
        noise=False,
    )  # fmt: skip
    assert (in_c.exit_status, in_python.exit_status) == (0, 0), in_python.error
    assert c_out == python_out
    lines = python_out.splitlines()
    assert lines[:2] == ["speeds nan nan", "unit 0.01 max 5"]
    rows = {int(r.split()[0]): [float(v) for v in r.split()[1:]] for r in lines[2:]}
    # Read every 64 ms: step 4 reads the counts of steps 2 to 4, at 3 and 2 rad/s (set at step 1).
    assert rows[4] == pytest.approx([3 * 0.032 * 300, 3 * 0.032 * 200], rel=1e-9)
    assert rows[5] == rows[4]
