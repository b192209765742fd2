"""An argument of a type its parameter does not take is refused with ``WrongTypeError``: the
package's own (an ``InvalidArgumentError``) and a ``TypeError``, as Python's refusal of a wrong
type is; a value of the right type out of its range stays an ``InvalidArgumentError`` (a
``ValueError``, not a ``TypeError``). Both in the Python package (the argument check, and a
function's own check of a type) and in the compiled core's binding (issue #15)."""

from __future__ import annotations

import pickle
import re
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

import mazesim


def _arena() -> mazesim.World:
    return mazesim.World.builtin("arena")


def _env(**options: Any) -> Any:
    from mazesim.envs import EPuckMazeEnv

    return EPuckMazeEnv(**options)


def _goals_env(**options: Any) -> Any:
    from mazesim.marl import maze_goals_v0

    return maze_goals_v0.parallel_env(**options)


def _batch_step(actions: Any) -> None:
    batch = mazesim.BatchSimulator(_arena(), num_envs=2)
    batch.step(actions, *batch.output_buffers())


def _unseen_mazes(count: Any, seed: Any) -> Any:
    from mazesim.learn.evaluate import unseen_mazes

    return unseen_mazes(count, seed)


def _make(**options: Any) -> Any:
    import gymnasium

    return gymnasium.make("mazesim/EPuckMaze-v0", **options)


#: Calls with an argument of the wrong type: name -> the call.
WRONG_TYPES: dict[str, Callable[[], Any]] = {
    # The compiled core's arguments: ints, reals, text, classes, sequences, arrays.
    "seed text": lambda: mazesim.Simulator(_arena(), seed="1"),
    "seed float": lambda: mazesim.Simulator(_arena()).reset(seed=1.5),
    "wheel speed text": lambda: mazesim.Simulator(_arena()).step("fast", 1.0),
    "robot int": lambda: mazesim.Simulator(_arena(), robot=3),
    "world text": lambda: mazesim.Simulator(_arena()).change_world("arena"),
    "robot index text": lambda: mazesim.Simulator(_arena()).distance_sensors("0"),
    "snapshot text": lambda: mazesim.Simulator(_arena()).restore("abc"),
    "world name int": lambda: mazesim.World.builtin(7),
    "codes not a sequence": lambda: mazesim.validate_codes(5),
    "actions a list": lambda: _batch_step([[0.0, 0.0], [0.0, 0.0]]),
    "actions of float64": lambda: _batch_step(np.zeros((2, 2))),
    "unpicklable": lambda: pickle.dumps(mazesim.BatchSimulator(_arena(), num_envs=1)),
    # The Python package: the argument check, and functions' own checks of a type.
    "world path int": lambda: mazesim.load_world(3),
    "render mode int": lambda: _env(render_mode=42),
    "parallel env render mode int": lambda: _goals_env(render_mode=3),
    "figure path int": lambda: mazesim.plotting.save_trajectory_png(_arena(), [0.0], [0.0], 5),
    # True and False are ints to Python, not counts or seeds: the binding took them as 1 and 0.
    "num_envs bool": lambda: mazesim.BatchSimulator(_arena(), num_envs=True),
    "seed bool": lambda: mazesim.Simulator(_arena(), seed=True),
    # int() read it as 1, without a word.
    "seed of True": lambda: _unseen_mazes(1, True),
    # The compiled module's private entry points, whose parameters are of plain types that pyo3
    # converts: its refusal was an InvalidArgumentError only, not naming the argument.
    "temporary file name int": lambda: mazesim._core._temporary_writing(5),
    "temporary writing text": lambda: mazesim._core._temporary_writing("a.tmp", "yes"),
    # gymnasium asks the env's render modes whether they hold 42 before the env is made; it
    # failed inside gymnasium (AttributeError: 'int' object has no attribute 'endswith').
    "gymnasium.make render mode int": lambda: _make(render_mode=42),
}

#: Calls with an argument of the right type out of its range: name -> the call.
WRONG_VALUES: dict[str, Callable[[], Any]] = {
    "seed negative": lambda: mazesim.Simulator(_arena(), seed=-1),
    "seed of 70 bits": lambda: mazesim.Simulator(_arena(), seed=2**70),
    "robot index too large": lambda: mazesim.Simulator(_arena()).distance_sensors(5),
    "world name unknown": lambda: mazesim.World.builtin("no-such-world"),
    "actions of the wrong shape": lambda: _batch_step(np.zeros((3, 2), np.float32)),
    "render mode unknown": lambda: _env(render_mode="holo"),
    "parallel env render mode unknown": lambda: _goals_env(render_mode="holo"),
}


@pytest.mark.parametrize("name", sorted(WRONG_TYPES))
def test_an_argument_of_the_wrong_type_is_a_wrong_type_error(name: str) -> None:
    import mazesim.plotting  # noqa: F401 - the figure call's module

    with pytest.raises(mazesim.WrongTypeError) as caught:
        WRONG_TYPES[name]()
    error = caught.value
    assert isinstance(error, TypeError) and isinstance(error, mazesim.InvalidArgumentError)
    assert str(error).count("expected") >= 1 and "found" in str(error), error


@pytest.mark.parametrize("name", sorted(WRONG_VALUES))
def test_a_value_out_of_range_stays_a_value_refusal(name: str) -> None:
    with pytest.raises(mazesim.MazesimError) as caught:
        WRONG_VALUES[name]()
    assert isinstance(caught.value, (ValueError, LookupError)), caught.value
    assert not isinstance(caught.value, TypeError), caught.value


def test_a_wrong_type_error_pickles_as_itself() -> None:
    error = mazesim.WrongTypeError("expected int, found str")
    again = pickle.loads(pickle.dumps(error))
    assert type(again) is mazesim.WrongTypeError and str(again) == str(error)


def test_wrong_type_error_is_in_the_public_error_tree() -> None:
    from mazesim import errors

    assert "WrongTypeError" in errors.__all__ and "WrongTypeError" in mazesim.__all__
    assert issubclass(mazesim.WrongTypeError, mazesim.MazesimError)


#: What a refusal of a type says it found, by value: the type's name with its article, or None.
FOUND = {
    "None": None,
    "an int": 3,
    "a float": 1.5,
    "a bool": True,
    "a bytes": b"x",
    "an ndarray": np.zeros(2),
    "a uint8": np.uint8(1),
    "an object": object(),
}


@pytest.mark.parametrize("found", sorted(FOUND))
def test_the_binding_and_the_python_side_name_a_wrong_type_alike(found: str) -> None:
    """One wording: "found an int", "found None" (the binding said "found a int", "found a
    NoneType")."""
    value = FOUND[found]
    with pytest.raises(mazesim.WrongTypeError) as binding:
        mazesim.World.from_toml(value)
    assert str(binding.value).endswith(f"found {found}"), binding.value
    with pytest.raises(mazesim.WrongTypeError) as python_side:
        mazesim.load_world(value)
    # (The argument check follows the type with a short repr: "found a bytes b'x'".)
    assert re.search(f"found {found}( |$)", str(python_side.value)), python_side.value
    from mazesim._checks import refusal

    assert re.search(f"found {found}( |$)", str(refusal(value, dict))), refusal(value, dict)


def test_a_path_object_giving_another_type_is_refused_saying_what_it_gives() -> None:
    # os.fspath refuses an int from __fspath__ with its own TypeError, which was read as None.
    class GivesAnInt:
        def __fspath__(self) -> Any:
            return 5

    with pytest.raises(mazesim.WrongTypeError, match="whose __fspath__ gives an int$"):
        mazesim.load_world(GivesAnInt())  # type: ignore[arg-type]
