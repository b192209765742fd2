"""Small worlds exercising device and supervisor calls real e-puck controllers make, each
checked against what Webots' reference manual documents (#32): the robot's ``customData``,
a motor's target position and a velocity above its ``maxVelocity`` (Webots warns and clamps),
a distance sensor's lookup table, an LED's value, the e-puck's accelerometer and gyro at rest,
a camera's image as an array and as bytes, ``stepBegin``/``stepEnd`` (R2023b), the end of the
run answered by -1, a PROTO's own fields read through ``Node.getField``, the simulation modes
and ``simulationQuit`` with a status."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from mazesim.webots import controller
from supervised_world import supervisor_in

pytestmark = pytest.mark.usefixtures("fresh_robot")


def world(robot_fields: str = "", basic_ms: int = 32) -> str:
    """A world of one e-puck supervisor with ``robot_fields`` on a 2 m arena."""
    return (
        "#VRML_SIM R2023b utf8\n"
        f"WorldInfo {{ basicTimeStep {basic_ms} }}\n"
        "RectangleArena { floorSize 2 2 }\n"
        f'DEF EPUCK E-puck {{ supervisor TRUE controller "<extern>" {robot_fields} }}\n'
    )


def test_custom_data_reads_the_file_s_then_the_one_set_and_the_field_follows(
    tmp_path: Path,
) -> None:
    """Robot.customData: read with wb_robot_get_custom_data, written with
    wb_robot_set_custom_data; a supervisor reads the field (reference manual, Robot)."""
    robot = supervisor_in(tmp_path, world('customData "gain=3"'))
    assert robot.getCustomData() == "gain=3"
    robot.setCustomData("gain=4")
    robot.step(32)
    assert robot.getCustomData() == "gain=4"
    assert robot.getSelf().getField("customData").getSFString() == "gain=4"


def test_a_motor_s_target_position_is_the_one_set_inf_in_velocity_control(
    tmp_path: Path,
) -> None:
    """wb_motor_get_target_position returns the position set by wb_motor_set_position
    (reference manual, Motor); the E-puck's wheels start at 0."""
    robot = supervisor_in(tmp_path, world())
    motor = robot.getDevice("left wheel motor")
    assert motor.getTargetPosition() == 0.0
    motor.setPosition(1.5)
    assert motor.getTargetPosition() == 1.5
    motor.setPosition(math.inf)
    assert motor.getTargetPosition() == math.inf


def test_a_velocity_above_max_velocity_is_warned_of_and_clamped(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    """Webots warns "The requested velocity ... exceeds 'maxVelocity'" and turns the wheel at
    maxVelocity (6.28 rad/s for the E-puck)."""
    robot = supervisor_in(tmp_path, world())
    encoder = robot.getDevice("left wheel sensor")
    encoder.enable(32)
    motor = robot.getDevice("left wheel motor")
    motor.setPosition(math.inf)
    motor.setVelocity(10.0)
    assert "exceeds 'maxVelocity' = 6.28" in capfd.readouterr().err
    robot.step(32)
    start = encoder.getValue()
    for _ in range(10):
        robot.step(32)
    assert (encoder.getValue() - start) / 0.32 == pytest.approx(6.28, abs=0.05)


def test_a_distance_sensor_s_lookup_table_is_its_rows_flattened(tmp_path: Path) -> None:
    """wb_distance_sensor_get_lookup_table: the lookupTable's rows, three numbers each
    (distance, value, noise), distances increasing (reference manual, DistanceSensor)."""
    robot = supervisor_in(tmp_path, world())
    table = robot.getDevice("ps0").getLookupTable()
    assert len(table) % 3 == 0 and len(table) >= 6
    distances = table[0::3]
    assert distances == sorted(distances) and distances[0] == 0.0
    # The E-puck's proximity sensor: about 4095 against the shell, its ambient level far.
    assert table[1] > 4000 and table[-2] < 400


def test_an_led_reads_the_value_set_last_0_at_first(tmp_path: Path) -> None:
    """wb_led_get returns the value set last by wb_led_set (0: off)."""
    robot = supervisor_in(tmp_path, world())
    led = robot.getDevice("led0")
    assert led.get() == 0
    led.set(1)
    robot.step(32)
    assert led.get() == 1


def test_the_e_puck_s_accelerometer_and_gyro_at_rest(tmp_path: Path) -> None:
    """At rest on a level floor the accelerometer reads gravity along the robot's z axis
    (9.81 m/s^2 up, ENU since R2022a) and the gyro 0; the E-puck has no compass unless one
    is added in a slot (getDevice returns None)."""
    robot = supervisor_in(tmp_path, world())
    accelerometer, gyro = robot.getDevice("accelerometer"), robot.getDevice("gyro")
    accelerometer.enable(32)
    gyro.enable(32)
    robot.step(32)
    assert accelerometer.getValues() == pytest.approx([0.0, 0.0, 9.81], abs=0.05)
    assert gyro.getValues() == pytest.approx([0.0, 0.0, 0.0], abs=1e-6)
    assert robot.getDevice("compass") is None


def test_a_camera_s_image_as_an_array_and_as_bgra_bytes(tmp_path: Path) -> None:
    """getImageArray: width lists of height lists of [r, g, b]; getImage: width * height * 4
    bytes, B G R A (the E-puck's camera: 52 x 39)."""
    robot = supervisor_in(tmp_path, world())
    camera = robot.getDevice("camera")
    camera.enable(32)
    robot.step(32)
    robot.step(32)
    width, height = camera.getWidth(), camera.getHeight()
    assert (width, height) == (52, 39)
    array = camera.getImageArray()
    assert len(array) == width and len(array[0]) == height and len(array[0][0]) == 3
    image = np.frombuffer(camera.getImage(), np.uint8).reshape((height, width, 4))
    assert [int(v) for v in image[5, 7, :3][::-1]] == list(array[7][5])
    assert controller.Camera.imageGetRed(camera.getImage(), width, 7, 5) == array[7][5][0]


def test_step_begin_and_step_end_make_one_step(tmp_path: Path) -> None:
    """stepBegin(duration) then stepEnd(): one step split in two (R2023b); both 0."""
    robot = supervisor_in(tmp_path, world())
    assert robot.stepBegin(32) == 0
    assert robot.stepEnd() == 0
    assert robot.getTime() == pytest.approx(0.032)


def test_a_proto_s_own_fields_are_read_through_get_field(tmp_path: Path) -> None:
    """Node.getField on a PROTO instance gives the PROTO's fields: the E-puck's
    ``camera_width`` (default 52), ``version`` ("1"), ``kinematic`` (FALSE)."""
    robot = supervisor_in(tmp_path, world("camera_width 80"))
    node = robot.getFromDef("EPUCK")
    assert node.getField("camera_width").getSFInt32() == 80
    assert node.getField("version").getSFString() == "1"
    assert node.getField("kinematic").getSFBool() is False
    assert node.getField("no_such_field") is None


def test_simulation_modes_and_the_pause(tmp_path: Path) -> None:
    """simulationSetMode / simulationGetMode; in the pause mode step(0) returns at once."""
    robot = supervisor_in(tmp_path, world())
    robot.simulationSetMode(robot.SIMULATION_MODE_REAL_TIME)
    assert robot.simulationGetMode() == robot.SIMULATION_MODE_REAL_TIME
    robot.simulationSetMode(robot.SIMULATION_MODE_PAUSE)
    assert robot.step(0) == 0 and robot.getTime() == 0.0


def test_simulation_quit_answers_the_next_step_with_the_end(tmp_path: Path) -> None:
    """simulationQuit(status): Webots quits with that status; the controller's next step
    returns -1."""
    robot = supervisor_in(tmp_path, world())
    assert robot.step(32) == 0
    robot.simulationQuit(3)
    assert robot.step(32) == -1
    assert robot._simulation.quit_status == 3


def test_a_step_not_a_multiple_of_the_basic_step_runs_whole_basic_steps(tmp_path: Path) -> None:
    """The reference manual asks for a multiple of basicTimeStep; a step of 20 ms in a world
    of 16 ms runs whole basic steps (the clock is a multiple of 16 ms)."""
    robot = supervisor_in(tmp_path, world(basic_ms=16))
    assert robot.getBasicTimeStep() == 16.0
    robot.step(20)
    assert round(robot.getTime() * 1000) % 16 == 0 and robot.getTime() >= 0.020


def test_a_distance_sensor_the_world_adds_gives_its_aperture(tmp_path: Path) -> None:
    """wb_distance_sensor_get_aperture: the node's ``aperture``, Webots' default 1.5708 where
    it leaves it out (reference manual, DistanceSensor); a C or C++ controller's library asks
    every distance sensor for it at its start."""
    sensors = (
        'turretSlot [ DistanceSensor { name "wide" } '
        'DistanceSensor { name "narrow" aperture 0.5 type "infra-red" } ]'
    )
    robot = supervisor_in(tmp_path, world(sensors))
    assert robot.getDevice("wide").getAperture() == 1.5708
    assert robot.getDevice("narrow").getAperture() == 0.5
    assert robot.getDevice("ps0").getAperture() == 0.1
