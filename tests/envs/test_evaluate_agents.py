"""`evaluate` takes every form of agent a user holds: a function observation -> action, an object
with act(), a Stable-Baselines3-like model (its predict), or a factory called per episode; any
other form is refused naming the forms."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

pytest.importorskip("gymnasium")

from mazesim.envs.baselines import FrontierExplorer, evaluate  # noqa: E402
from mazesim.errors import InvalidArgumentError, UnknownNameError  # noqa: E402

TASK = "mazesim/MazeFixed-v1"
SHORT = {"episodes": 2, "max_episode_steps": 20}
FORWARD = np.array([0.6, 0.6], dtype=np.float32)


class Forward:
    """A factory of the documented form: agent(observation_names, maze_size)."""

    def __init__(self, observation_names: Any, maze_size: Any) -> None:
        self.names = observation_names

    def act(self, observation: Any) -> Any:
        return FORWARD


class Stateless:
    """A class made without arguments, once per episode."""

    def act(self, observation: Any) -> Any:
        return FORWARD


class Model:
    """Stable-Baselines3's model form: predict(observation, deterministic) -> (action, state)."""

    def __init__(self) -> None:
        self.deterministic: list[bool] = []

    def predict(self, observation: Any, state: Any = None, deterministic: bool = False) -> Any:
        self.deterministic.append(deterministic)
        return FORWARD, state


def forward(observation: Any) -> Any:
    return FORWARD


def test_a_function_an_object_a_model_and_a_factory_drive_the_same_episodes() -> None:
    expected = evaluate(TASK, Forward, **SHORT)
    model = Model()
    assert evaluate(TASK, forward, **SHORT) == expected
    assert evaluate(TASK, lambda observation: FORWARD, **SHORT) == expected
    assert evaluate(TASK, Forward(None, None), **SHORT) == expected
    assert evaluate(TASK, Stateless, **SHORT) == expected
    explorer = evaluate("mazesim/UnseenMazeExplore-v0", FrontierExplorer, **SHORT)
    assert explorer.episodes == 2  # FrontierExplorer(names, maze_size=None)
    assert evaluate(TASK, model, **SHORT) == expected
    assert model.deterministic and all(model.deterministic)
    assert evaluate(TASK, model.predict, **SHORT) == expected
    assert expected.mean_length == 20


def test_a_function_returning_predicts_pair_is_told_to_pass_the_model() -> None:
    with pytest.raises(InvalidArgumentError, match="pass the model itself"):
        evaluate(TASK, lambda observation: (FORWARD, None), **SHORT)


def test_a_function_of_another_form_is_refused_naming_the_forms() -> None:
    with pytest.raises(InvalidArgumentError, match="a function observation -> action") as caught:
        evaluate(TASK, lambda a, b, c: FORWARD, **SHORT)
    assert "needs 3 arguments" in str(caught.value)
    with pytest.raises(InvalidArgumentError, match="make an object with act"):
        evaluate(TASK, lambda names, size: None, **SHORT)


@pytest.mark.parametrize("task", ["explore", "mazesim/NoSuchTask-v0", "gymnasium/CartPole"])
def test_an_unknown_task_is_refused_naming_the_tasks(task: str) -> None:
    with pytest.raises(UnknownNameError, match="expected evaluate's task to be one of mazesim/"):
        evaluate(task, lambda observation: 0, episodes=1)
