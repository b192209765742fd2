"""A plain value of another type than its parameter takes is refused before the call, at every
checked entry point of the package (issues #35 and #15): a bool for a number, None or a number
for text, an int beyond 64 bits for an int. A call that does not fail on such a value took it
without a word: ``Robot.step(True)`` stepped 1 ms, ``getDevice(None)`` looked for a device named
"None", ``DistanceSensor.enable(2**70)`` enabled the sensor. The check is one mechanism
(``mazesim._checks``, each parameter's annotation), so the walk below covers every entry point
of the registry, a new one included, without a test of its own."""

from __future__ import annotations

import importlib
import inspect
from typing import Any

import pytest

import mazesim
from mazesim import _checks
from mazesim.errors import InvalidArgumentError, WrongTypeError
from surface.registry import EntryPoint, python_entry_points

#: Plain values of each type, as a careless caller gives them.
PLAIN_VALUES = (True, None, 3, 1.5, 2**70)


def _checked(entry: EntryPoint) -> tuple[Any, bool] | None:
    """The function an entry point runs and whether it is a method, when the import hook checks
    it (the compiled core checks its own arguments)."""
    module_name, _, qualname = entry.path.partition(":")
    owner: Any = importlib.import_module(module_name)
    parts = qualname.split(".")
    for part in parts[:-1]:
        owner = getattr(owner, part)
    raw = vars(owner).get(parts[-1]) if inspect.isclass(owner) else getattr(owner, parts[-1])
    target = getattr(raw, "__func__", raw)
    if not getattr(target, "__mazesim_checked__", False):
        return None
    is_method = inspect.isclass(owner) and not isinstance(raw, staticmethod)
    return inspect.unwrap(target), is_method


def _refusals() -> tuple[int, list[str]]:
    """How many (parameter, value) pairs of plain annotations the walk tried, and those the
    check let through although the annotation does not take them."""
    tried, missed = 0, []
    for entry in python_entry_points():
        found = _checked(entry)
        if found is None:
            continue
        parameters = _checks._Parameters(*found)  # noqa: SLF001 - the mechanism under test
        parameters.prepare()
        for name in parameters.plain:
            hint = parameters.by_name.get(name)
            if hint is None:
                continue  # positional-only: given by position only
            for value in PLAIN_VALUES:
                if _checks.refusal(value, hint) is None:
                    continue  # the annotation takes it
                if value == 2**70 and name not in parameters.ints:
                    continue  # a number: float() reads it as 1.2e21
                tried += 1
                try:
                    parameters.check_scalars((), {name: value})
                except InvalidArgumentError:
                    continue
                missed.append(f"{entry.path}({name}={value!r})")
    return tried, missed


def test_every_plain_parameter_refuses_plain_values_of_another_type_before_the_call() -> None:
    tried, missed = _refusals()
    assert tried > 1000, "the walk reaches the registry's plain parameters"
    assert not missed, f"taken without a word: {missed[:20]}"


@pytest.mark.parametrize("value", [True, False])
def test_a_bool_is_not_a_number_of_milliseconds_or_a_speed(value: bool) -> None:
    """``Robot.step(True)`` stepped 1 ms; the compiled core took True for 1 rad/s."""
    from mazesim.webots import controller, prepare
    from mazesim.webots import simulation as simulations

    prepare(mazesim.load_world("arena"), seconds=1.0)
    controller.Robot.created = None
    robot = controller.Robot()
    try:
        with pytest.raises(WrongTypeError, match=r"Robot.step: time_step refused: .*found a bool"):
            robot.step(value)
        assert robot.getTime() == 0.0, "nothing was stepped"
        motor = robot.getDevice("left wheel motor")
        with pytest.raises(WrongTypeError, match="velocity refused"):
            motor.setVelocity(value)
        with pytest.raises(InvalidArgumentError, match="fits in 64 bits"):
            robot.getDevice("ps0").enable(2**70)
        with pytest.raises(WrongTypeError, match="name refused: expected str, found None"):
            robot.getDevice(None)
    finally:
        simulations.release()
    simulator = mazesim.Simulator(mazesim.World.builtin("arena"))
    with pytest.raises(WrongTypeError, match="expected left to be a real number, found a bool"):
        simulator.step(value, 1.0)
    assert simulator.steps == 0
    with pytest.raises(WrongTypeError, match="volts to be a real number, found a bool"):
        mazesim.sharp_volts_to_cm(value)
