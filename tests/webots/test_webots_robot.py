"""``Robot`` as controllers written for other robots or older worlds call it."""

from __future__ import annotations

import pytest

import mazesim
from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations


def test_a_device_name_of_older_worlds_gets_the_e_pucks_own_names(
    capsys: pytest.CaptureFixture[str],
) -> None:
    prepare(mazesim.load_world("arena"), seconds=1.0)
    controller.Robot.created = None
    robot = controller.Robot()
    assert robot.getDevice("left wheel") is None, "as in Webots: no such device"
    err = capsys.readouterr().err
    assert 'Device "left wheel" was not found on robot "e-puck"' in err
    assert "'left wheel motor', 'left wheel sensor'" in err
    assert robot.getDevice("lidar") is None
    assert "mazesim:" not in capsys.readouterr().err, "no hint without a similar name"
    simulations.release()


def test_a_name_the_controller_module_lacks_raises_attribute_error_as_webots_module() -> None:
    with pytest.raises(AttributeError, match="module 'controller' has no attribute 'NoSuchClass'"):
        _ = controller.NoSuchClass  # type: ignore[attr-defined]


def test_a_controller_of_webots_swig_api_may_call_robot_del_before_it_exits() -> None:
    # Webots' Python API made by SWIG gives its objects a __del__ that does nothing; a sumo
    # project's controller calls robot.__del__() and exit() once step returns -1.
    prepare(mazesim.load_world("arena"), seconds=0.064)
    controller.Robot.created = None
    robot = controller.Robot()
    while robot.step(32) != -1:
        pass
    robot.__del__()
    assert robot.getTime() == pytest.approx(0.064)
    simulations.release()


def test_a_robot_whose_construction_raised_is_not_the_process_s_one(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # A Supervisor() that raised while finding its devices left itself as the process's robot,
    # so a controller's fallback Robot() took the broken one's devices (AttributeError).
    from mazesim.webots import robot as robots

    prepare(mazesim.load_world("arena"), seconds=1.0)
    controller.Robot.created = None

    def broken(simulation: object) -> None:
        raise RuntimeError("a device could not be made")

    with monkeypatch.context() as patched:
        patched.setattr(robots, "Equipment", broken)
        with pytest.raises(RuntimeError):
            controller.Supervisor()
    assert controller.Robot.created is None
    robot = controller.Robot()
    assert robot.getDevice("ps0") is not None and robot.step(32) != -1
    simulations.release()
