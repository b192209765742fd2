"""A robot's own motors beyond the e-puck's two wheels (the four wheels of Webots' tutorial
robot, an arm's joints) are devices found by their names, as in Webots: their joints turn
freely as commanded, a position sensor of the same joint reads the turn, and they move nothing;
a controller that drives them runs instead of stopping at a missing device (#32)."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

import mazesim
from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations

#: A world of one robot that is not an e-puck, with four wheel motors, the first wheel's joint
#: with a position sensor too, and its controller, which drives them.
FOUR_WHEELS_WORLD = (
    Path(__file__).resolve().parent.parent
    / "data"
    / "webots-four-wheels"
    / "worlds"
    / "four_wheels.wbt"
)
#: The import's entries of a four-wheeled robot: each HingeJoint's motor at the robot's origin
#: (the joint's place), the first wheel's position sensor listed after its motor.
FOUR_WHEELS: list[dict[str, Any]] = [
    {"type": "RotationalMotor", "name": "wheel1", "slot": "children", "fields": {}},
    {"type": "PositionSensor", "name": "wheel1 sensor", "slot": "children", "fields": {}},
    {"type": "RotationalMotor", "name": "wheel2", "slot": "children", "fields": {}},
    {"type": "RotationalMotor", "name": "wheel3", "slot": "children", "fields": {}},
    {
        "type": "LinearMotor",
        "name": "lift",
        "slot": "children",
        "fields": {"maxVelocity": 0.1, "minPosition": 0.0, "maxPosition": 0.02},
    },
    {"type": "PositionSensor", "name": "lift sensor", "slot": "children", "fields": {}},
]


@pytest.fixture(autouse=True)
def release() -> Iterator[None]:
    yield
    controller.Robot.created = None
    simulations.release()


def four_wheeled_robot() -> Any:
    prepare(
        mazesim.load_world("arena"),
        seconds=5.0,
        noise=False,
        report={"extension_devices": FOUR_WHEELS},
    )
    controller.Robot.created = None
    return controller.Robot()


def test_a_robots_extra_motors_are_devices_that_turn_their_joints(
    capsys: pytest.CaptureFixture[str],
) -> None:
    robot = four_wheeled_robot()
    err = capsys.readouterr().err
    # Named with its robot: thirty robots of one model warn each of its own.
    assert (
        f"robot {robot.getName()!r}: the RotationalMotor device 'wheel1' in the world drives a "
        "joint mazesim" in err
    )
    wheels = [robot.getDevice(f"wheel{i}") for i in (1, 2, 3)]
    assert all(wheel is not None for wheel in wheels), "Webots finds them by their names"
    sensor = robot.getDevice("wheel1 sensor")
    assert sensor is not None and sensor.getMotor() is wheels[0]
    assert wheels[0].getPositionSensor() is sensor
    assert wheels[0].getMaxVelocity() == 10.0, "Webots' default maxVelocity"
    for wheel in wheels:
        wheel.setPosition(float("inf"))
        wheel.setVelocity(2.0)
    sensor.enable(32)
    step_s = robot.getBasicTimeStep() / 1000.0
    steps = 10
    for _ in range(steps):
        robot.step(int(robot.getBasicTimeStep()))
    assert sensor.getValue() == pytest.approx(2.0 * steps * step_s)
    assert simulations.current().wheel_angles() == (0.0, 0.0), "they move nothing"


def test_a_linear_joint_goes_to_its_target_within_its_limits() -> None:
    robot = four_wheeled_robot()
    lift = robot.getDevice("lift")
    assert lift.getType() == lift.LINEAR
    assert (lift.getMinPosition(), lift.getMaxPosition()) == (0.0, 0.02)
    sensor = lift.getPositionSensor()
    assert sensor is not None and sensor.getType() == sensor.LINEAR
    sensor.enable(32)
    lift.setPosition(0.5)
    assert lift.getTargetPosition() == 0.5
    robot.step(int(robot.getBasicTimeStep()))
    first = sensor.getValue()
    assert 0.0 < first < 0.02, "it moves towards its target, at most maxVelocity"
    for _ in range(40):
        robot.step(int(robot.getBasicTimeStep()))
    assert sensor.getValue() == pytest.approx(0.02), "held at its maxPosition"


def test_a_four_wheeled_robots_controller_runs_in_a_world_run(
    capfd: pytest.CaptureFixture[str],
) -> None:
    from mazesim.webots.lockstep import run_world

    run = run_world(str(FOUR_WHEELS_WORLD), seconds=1.0)
    (rover,) = run.robots
    assert rover.exit_status == 0, rover.error
    # 20 steps of 32 ms at 3 rad/s: the wheel's joint turned 1.92 rad, the body not at all.
    assert "wheel1 turned 1.92 rad" in capfd.readouterr().out
    assert rover.final_pose[:2] == pytest.approx((0.5, 0.5))
