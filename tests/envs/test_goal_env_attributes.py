"""The goal-conditioned tasks answer the attributes every other task's env has (read from the maze
env they wrap), through gymnasium's wrappers as well as unwrapped."""

from __future__ import annotations

import pickle

import pytest

gymnasium = pytest.importorskip("gymnasium")
import numpy as np  # noqa: E402

import mazesim  # noqa: E402,F401
from mazesim.envs.tasks import GOAL_TASKS  # noqa: E402

IDS = [task.env_id for task in GOAL_TASKS]


def _public_names(env: object, own: object) -> list[str]:
    """The public attributes of the wrapped maze env that the goal env does not define itself."""
    return [
        name
        for name in dir(env)
        if not name.startswith("_") and not hasattr(type(own), name) and name not in vars(own)
    ]


@pytest.mark.parametrize("env_id", IDS)
def test_every_public_attribute_of_the_maze_env_is_read_through_the_goal_env(env_id: str) -> None:
    env = gymnasium.make(env_id)
    env.reset(seed=1)
    goal_env = env.unwrapped
    names = _public_names(goal_env.maze, goal_env)
    assert {"observation_names", "world", "options", "goal_disc"} <= set(names)
    for name in names:
        assert getattr(goal_env, name) == getattr(goal_env.maze, name), name
    # What the documentation reads on env.unwrapped of any task, and through the wrappers.
    observation, _ = env.reset(seed=2)
    assert len(env.get_wrapper_attr("observation_names")) == observation["observation"].shape[0]
    assert env.unwrapped.world.name == goal_env.maze.world.name


def test_the_goal_vector_env_reads_the_maze_vector_envs_attributes() -> None:
    envs = gymnasium.make_vec("mazesim/UnseenMazeGoal-v0", num_envs=3)
    observations, _ = envs.reset(seed=0)
    names = _public_names(envs.mazes, envs)
    assert {"observation_names", "options", "goal_discs"} <= set(names)
    assert envs.observation_names == envs.mazes.observation_names
    assert len(envs.observation_names) == observations["observation"].shape[1]
    np.testing.assert_array_equal(envs.goal_discs, envs.mazes.goal_discs)
    assert envs.options == envs.mazes.options
    envs.close()


@pytest.mark.parametrize("name", ["no_such_attribute", "_layout"])
def test_a_missing_or_private_attribute_is_still_an_attribute_error(name: str) -> None:
    goal_env = gymnasium.make("mazesim/EPuckGoal-v0").unwrapped
    with pytest.raises(AttributeError, match=name):
        getattr(goal_env, name)
    assert not hasattr(goal_env, name)


def test_a_pickled_goal_env_steps_on_as_the_original() -> None:
    env = gymnasium.make("mazesim/EPuckGoalDense-v0")
    env.reset(seed=5)
    action = np.array([0.4, 0.6], dtype=np.float32)
    for _ in range(5):
        env.step(action)
    copy = pickle.loads(pickle.dumps(env))
    assert copy.unwrapped.observation_names == env.unwrapped.observation_names
    for _ in range(20):
        first, second = env.step(action), copy.step(action)
        for key in first[0]:
            np.testing.assert_array_equal(first[0][key], second[0][key])
        assert first[1] == second[1]
