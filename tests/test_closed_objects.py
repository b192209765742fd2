"""Every public method of every public class that can be closed, called after ``close()``: it
raises one of mazesim's errors (an env's :class:`~mazesim.envs.errors.EnvClosedError`), or it is
declared harmless here with why. A method that works on a closed object as if it were open, or
fails with another error (an ``AttributeError`` of a released resource, a ``ValueError`` of a
closed file), is a failure of this walk.

The classes and their methods come from the registry of the public surface
(``surface.registry``), so a new closable class or a new method of one is walked as soon as it
exists; its instances are made by the registry's recipes, its methods' arguments by
``surface.values.sample_arguments``.
"""

from __future__ import annotations

import importlib
import inspect
from pathlib import Path
from typing import Any

import pytest

import mazesim
from surface.registry import instance_recipe, needs_instance, python_entry_points
from surface.values import sample_arguments, sample_instance

#: Methods that may go on working after ``close()``, with why that harms nothing. A method not
#: here must raise a MazesimError once its object is closed.
HARMLESS: dict[str, str] = {
    # Closing twice is closing: gymnasium's and Python's files' own rule.
    "close": "a second close() does nothing",
    "close_extras": "gymnasium's part of close(): a second close does nothing",
    # A goal env's reward rule reads only its arguments (gymnasium-robotics' compute_reward).
    "compute_reward": "a pure function of its arguments",
    # A progress display is closed stage by stage: close() ends the bar of the current stage,
    # and the next count opens another.
    "note": "no stage is open after close(): the note is dropped",
    "unit_of": "reads the units the display was made with",
    # A live window opens again when shown a frame after it was closed, as after the user
    # closed it; headless, the frame is only kept.
    "show": "a closed window opens again, as one the user closed does",
    "follow": "sets the world the window draws from the next frame on",
}


def _closable_classes() -> dict[str, list[str]]:
    """Each public class with a ``close()`` that takes no argument (its own or inherited;
    ``module.Class``), and its own public methods."""
    classes: dict[str, list[str]] = {}
    for entry in python_entry_points():
        owner = needs_instance(entry)
        if owner is not None:
            classes.setdefault(owner, []).append(entry.path.rsplit(".", 1)[1])
    closable = {}
    for owner, members in classes.items():
        module, _, name = owner.rpartition(".")
        close = getattr(getattr(importlib.import_module(module), name), "close", None)
        if close is None or not callable(close):
            continue
        required = [
            p
            for p in list(inspect.signature(close).parameters.values())[1:]
            if p.default is p.empty and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)
        ]
        if not required:  # a close(arrived, ...) ends something else than the object
            closable[owner] = members if "close" in members else [*members, "close"]
    return closable


def _make(owner: str, tmp: Path) -> Any:
    world = mazesim.World.builtin("seed-maze")
    recipe = instance_recipe(owner)
    if recipe.startswith("auto:"):
        module, _, name = owner.rpartition(".")
        return sample_instance(getattr(importlib.import_module(module), name), world, tmp)
    return eval(recipe, {"mazesim": mazesim, "world": world, "tmp": tmp})  # noqa: S307


CLOSABLE = _closable_classes()


def test_the_walk_finds_the_closable_classes() -> None:
    """The walk is not empty: the envs, the vector env (whose close() is gymnasium's) and the
    learning curve are among the classes it calls."""
    for owner in (
        "mazesim.envs.maze_env.EPuckMazeEnv",
        "mazesim.envs.vector.EPuckMazeVectorEnv",
        "mazesim.learn.learning_curve.LearningCurve",
    ):
        assert owner in CLOSABLE, sorted(CLOSABLE)


@pytest.mark.parametrize("owner", sorted(CLOSABLE))
def test_every_method_of_a_closed_object_refuses_or_is_harmless(
    owner: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    try:
        made = _make(owner, tmp_path)
    except Exception as error:  # noqa: BLE001 - a class the recipes cannot make is skipped
        pytest.skip(f"no instance of {owner}: {type(error).__name__}")
    made.close()
    world = mazesim.World.builtin("seed-maze")
    escaped = []
    for member in CLOSABLE[owner]:
        method = getattr(made, member)
        try:
            arguments = sample_arguments(inspect.unwrap(method), world, tmp_path)
        except Exception:  # noqa: BLE001, S112 - no valid arguments known: not walked
            continue
        try:
            method(**arguments)
        except mazesim.MazesimError:
            continue
        except Exception as error:  # noqa: BLE001 - any other error is the finding
            escaped.append(f"{member}: {type(error).__module__}.{type(error).__name__}: {error}")
            continue
        if member not in HARMLESS:
            escaped.append(f"{member}: returned on a closed object")
    assert not escaped, f"{owner} after close():\n" + "\n".join(escaped)


def test_a_harmless_method_is_one_the_walk_meets() -> None:
    """Every name declared harmless is a method of a closable class: no stale declaration."""
    members = {member for members in CLOSABLE.values() for member in members}
    assert set(HARMLESS) <= members, set(HARMLESS) - members
