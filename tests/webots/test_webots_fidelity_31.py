"""Small Webots projects written as users write them, each checked against what Webots
documents (its reference manual, cyberbotics.com/doc/reference): a robot's identity and custom
data, the e-puck's LEDs read back, a keyboard nobody types on, and a motor's target position and
a velocity above its maximum read back, in Python and in C (#32)."""

from __future__ import annotations

import functools
from pathlib import Path

import pytest

from swarm_project import run_project

PROJECT = Path(__file__).resolve().parent.parent / "data" / "webots-fidelity-31"

run = functools.partial(run_project, PROJECT)


def test_robot_identity_and_custom_data(tmp_path: Path) -> None:
    """Robot (reference manual): ``getCustomData`` gives the node's ``customData`` field and
    ``setCustomData`` changes it; ``getModel`` the ``model`` field ("GCtronic e-puck" in the
    E-puck PROTO); ``getDeviceByIndex(i)`` for i below ``getNumberOfDevices()`` names each
    device once; ``getTime`` after one step of ``basicTimeStep`` 32 ms is 0.032 s."""
    _, logs = run("robot_identity", tmp_path, 1.0)
    log = logs["robot_identity"]
    assert (log["before"], log["after"]) == ("start", "changed")
    assert log["model"] == "GCtronic e-puck"
    assert log["count"] == len(log["names"]) == len(set(log["names"]))
    for name in ["left wheel motor", "right wheel motor", "ps0", "ps7", "led0", "led9"]:
        assert name in log["names"]
    assert log["step"] == 32.0
    assert log["time"] == pytest.approx(0.032)


def test_led_get_returns_the_value_set(tmp_path: Path) -> None:
    """LED (reference manual): ``get`` returns the value last given to ``set``, 0 (off) at
    start; the e-puck has led0 to led9."""
    _, logs = run("led_values", tmp_path, 1.0)
    log = logs["led_values"]
    assert log["initial"] == [0] * 10
    assert log["set"] == [i % 2 for i in range(10)]


def test_keyboard_get_key_without_a_key_is_minus_one(tmp_path: Path) -> None:
    """Keyboard (reference manual): ``getKey`` returns -1 when no key is pressed (the queue
    is empty); ``getSamplingPeriod`` the period given to ``enable``."""
    _, logs = run("keyboard_idle", tmp_path, 1.0)
    log = logs["keyboard_idle"]
    assert log["keys"] == [-1] * 5
    assert log["period"] == 32


def test_motor_target_position_and_velocity_clamp(tmp_path: Path) -> None:
    """Motor (reference manual): ``getTargetPosition`` returns the last ``setPosition``
    (infinity for velocity control; the E-puck PROTO's wheels start at 0); a velocity above
    ``maxVelocity`` (6.28 rad/s for the e-puck) is clamped by the simulator with a warning,
    but ``getVelocity`` gives the velocity asked, 100: Webots' controller library returns what
    was set (src/controller/c/motor.c, ``wb_motor_get_velocity`` returns ``m->velocity``)."""
    _, logs = run("motor_targets", tmp_path, 1.0)
    log = logs["motor_targets"]
    assert log["left_target"] == "inf"
    assert log["right_target"] == 2.0
    assert log["max_velocity"] == pytest.approx(6.28)
    assert log["left_velocity"] == 100.0
    assert log["initial"] == 0.0


def test_a_c_controller_reads_back_leds_and_motor_target(tmp_path: Path, own_cache: Path) -> None:
    """The same in C: ``wb_led_get`` gives what ``wb_led_set`` set, ``wb_motor_get_target_position``
    the position set, and ``wb_motor_get_velocity`` the velocity asked, 100, not the 6.28 rad/s
    the simulator clamps it to."""
    _, logs = run("led_motor_c", tmp_path, 1.0)
    log = logs["led_motor_c"]
    assert log["leds"] == [i % 2 for i in range(10)]
    assert log["target"] == 2.0
    assert log["velocity"] == 100.0
