"""Webots' device calls that controllers use, against what Webots documents and does: a motor's
acceleration ramps its speed (``WbMotor::computeCurrentDynamicVelocity``), a supervisor
reads its own node's ``controller`` field as the world file writes it, and a proximity sensor
gives its PROTO's aperture (#32)."""

from __future__ import annotations

import math
from collections.abc import Iterator

import pytest

import mazesim
from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.scene import read_scene

HEADER = "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\n"


@pytest.fixture(autouse=True)
def release() -> Iterator[None]:
    yield
    controller.Robot.created = None
    simulations.release()


def wheel_turn(acceleration: float | None, steps: int = 32) -> float:
    """The left wheel's angle after ``steps`` steps of 32 ms at 6 rad/s asked for, with that
    acceleration set (None: none set)."""
    prepare(mazesim.load_world("arena"), seconds=10.0, noise=False)
    controller.Robot.created = None
    robot = controller.Robot()
    sensor = robot.getDevice("left wheel sensor")
    sensor.enable(32)
    for name in ("left wheel motor", "right wheel motor"):
        motor = robot.getDevice(name)
        motor.setPosition(math.inf)
        if acceleration is not None:
            motor.setAcceleration(acceleration)
        motor.setVelocity(6.0)
    for _ in range(steps):
        robot.step(32)
    return float(sensor.getValue())


def test_a_motors_acceleration_ramps_its_speed_as_in_webots() -> None:
    # At 2 rad/s^2 the speed grows by 0.064 rad/s a step: after k steps it is 0.064 k, and the
    # wheel has turned 0.032 * 0.064 * (1 + ... + 32) = 1.08 rad in 1.024 s, not 6 * 1.024.
    ramped = wheel_turn(2.0)
    assert ramped == pytest.approx(0.032 * 0.064 * 528, abs=0.02)
    controller.Robot.created = None
    simulations.release()
    assert wheel_turn(None) == pytest.approx(6.0 * 1.024, abs=0.05)


def test_a_negative_acceleration_is_refused_with_webots_error(
    capsys: pytest.CaptureFixture[str],
) -> None:
    prepare(mazesim.load_world("arena"), seconds=1.0, noise=False)
    controller.Robot.created = None
    motor = controller.Robot().getDevice("left wheel motor")
    motor.setAcceleration(-3.0)
    assert motor.getAcceleration() == -1.0
    assert "called with negative 'acceleration' argument" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("field", "read"),
    [('controller "mine"', "mine"), ("", "e-puck_avoid_obstacles"), ('controller ""', "")],
)
def test_a_supervisor_reads_its_own_controller_field(field: str, read: str) -> None:
    text = HEADER + f"DEF ME E-puck {{ supervisor TRUE {field} }}\n"
    report = {"robot_model": "E-puck"}
    prepare(
        mazesim.load_world("arena"), seconds=1.0, noise=False, report=report, scene=read_scene(text)
    )
    controller.Robot.created = None
    supervisor = controller.Supervisor()
    assert supervisor.getSelf().getField("controller").getSFString() == read


def test_the_proximity_sensors_give_their_protos_aperture() -> None:
    # E-puckDistanceSensor.proto (R2022a-R2025a): aperture 0.1; the ground sensors are not its.
    prepare(mazesim.load_world("arena"), seconds=1.0, noise=False)
    controller.Robot.created = None
    robot = controller.Robot()
    assert [robot.getDevice(f"ps{i}").getAperture() for i in range(8)] == [0.1] * 8
