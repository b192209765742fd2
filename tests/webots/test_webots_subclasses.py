"""Controllers' own subclasses of Webots' classes, as Webots allows them: a Motor or Camera
subclass whose ``__init__`` calls ``super().__init__(name)`` (with other arguments of its own,
or none, its device's name written in that call), and a Robot subclass that keeps its own
``self.keyboard``."""

from __future__ import annotations

import math
from collections.abc import Iterator

import pytest

import mazesim
from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations


@pytest.fixture(autouse=True)
def robot_world() -> Iterator[None]:
    prepare(mazesim.load_world("arena"), seconds=1.0)
    controller.Robot.created = None
    yield
    controller.Robot.created = None
    simulations.release()


def test_motor_subclass_init_runs_and_isinstance_holds() -> None:
    class EpuckMotor(controller.Motor):
        def __init__(self, name: str) -> None:
            super().__init__(name)  # type: ignore[call-arg]
            self.setPosition(float("inf"))
            self.made_here = True

    robot = controller.Robot()
    motor = EpuckMotor("left wheel motor")
    assert isinstance(motor, EpuckMotor) and isinstance(motor, controller.Motor)
    assert motor.made_here and math.isinf(motor.getTargetPosition())
    # The robot's device is that same object: the run drives what the subclass set.
    assert robot.getDevice("left wheel motor") is motor


def test_camera_subclass_with_other_arguments_enables_itself() -> None:
    class Eye(controller.Camera):
        def __init__(self, name: str, period: int) -> None:
            super().__init__(name)  # type: ignore[call-arg]
            self.enable(period)

    robot = controller.Robot()
    eye = Eye("camera", 64)
    assert isinstance(eye, Eye) and eye.getSamplingPeriod() == 64
    assert robot.getDevice("camera") is eye


def test_camera_subclass_naming_its_device_in_its_own_init_is_the_robots_camera() -> None:
    class Eye(controller.Camera):
        def __init__(self) -> None:
            super().__init__("camera")  # type: ignore[call-arg]
            self.enable(64)
            self.tracked = "rubber duck"

    robot = controller.Robot()
    eye = Eye()
    assert isinstance(eye, Eye) and eye.getName() == "camera"
    assert eye.getSamplingPeriod() == 64 and eye.tracked == "rubber duck"
    # As when the name is given to the class: the robot's camera is that same object.
    assert robot.getDevice("camera") is eye


def test_subclass_naming_a_device_of_another_type_in_its_init_gives_none(
    capsys: pytest.CaptureFixture[str],
) -> None:
    class Eye(controller.Camera):
        def __init__(self) -> None:
            super().__init__("ps0")  # type: ignore[call-arg]

    controller.Robot()
    assert Eye() is None
    assert "is a DistanceSensor, not a Camera" in capsys.readouterr().err


def test_subclass_of_the_wrong_device_type_gives_none(capsys: pytest.CaptureFixture[str]) -> None:
    class Wheel(controller.Motor):
        pass

    controller.Robot()
    assert Wheel("ps0") is None  # type: ignore[call-arg]
    assert "is a DistanceSensor, not a Motor" in capsys.readouterr().err


def test_robot_subclass_keeps_its_own_keyboard() -> None:
    class Teleop(controller.Robot):
        def __init__(self) -> None:
            super().__init__()
            self.keyboard = self.getKeyboard()
            self.keyboard.enable(32)
            self.mouse = None  # type: ignore[assignment]

    robot = Teleop()
    assert robot.keyboard is robot.getKeyboard()
    assert robot.keyboard.getSamplingPeriod() == 32
    assert robot.mouse is None


def test_a_wrapper_subclass_that_skips_robot_init_keeps_its_own_keyboard() -> None:
    # A wrapper of another controller object (deepbots' KeyboardPrinter) subclasses Supervisor
    # and never calls its __init__: its own ``self.keyboard`` is an attribute like any other.
    robot = controller.Supervisor()

    class Printer(controller.Supervisor):
        def __init__(self, wrapped: controller.Supervisor) -> None:
            self.wrapped = wrapped
            self.keyboard = controller.Keyboard()
            self.keyboard.enable(32)

    printer = Printer(robot)
    assert isinstance(printer.keyboard, controller.Keyboard)
    assert printer.keyboard.getSamplingPeriod() == 32
    assert printer.wrapped is robot
