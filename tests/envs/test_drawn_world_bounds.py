"""A world drawn for an episode must lie within the positions in metres the observation space
holds (the goal tasks' ``achieved_goal`` and ``desired_goal``, the pose of ``include_pose=True``),
which are made from the world sampler's first draw: a world sampler drawing mazes of different
sizes is refused at its first too-large draw, at a reset or an autoreset, by the one check the
maze-size curriculum applies to its stages; an observation of no metres takes every size."""

from __future__ import annotations

import re

import gymnasium
import numpy as np
import pytest

import mazesim
from mazesim.envs import EPuckMazeEnv, EPuckMazeVectorEnv
from mazesim.envs.goal import MazeGoalEnv, MazeGoalVectorEnv
from mazesim.envs.options import _reaches_outside
from mazesim.errors import InvalidArgumentError

GOAL_TASK = "mazesim/UnseenMazeGoal-v0"
REFUSAL = re.escape("expected each episode's world to lie within the positions in metres")


class Alternating:
    """A world sampler drawing 3 x 3 mazes when the env is made, then alternately 3 x 3 and
    6 x 6 mazes, recording the side of each draw."""

    def __init__(self) -> None:
        self.sides: list[int] = []

    def __call__(self, rng: np.random.Generator) -> mazesim.World:
        draws = len(self.sides)
        side = 6 if draws > 0 and draws % 2 == 0 else 3
        self.sides.append(side)
        return mazesim.generate_maze(side, side, seed=int(rng.integers(2**32)))


def test_the_six_by_six_mazes_reach_outside_what_the_three_by_three_space_holds() -> None:
    small = mazesim.generate_maze(3, 3, seed=1).bounds
    large = mazesim.generate_maze(6, 6, seed=1).bounds
    assert not _reaches_outside(small, small)
    assert _reaches_outside(large, small)
    assert not _reaches_outside(small, large)


def refused_at_the_first_large_draw(sampler: Alternating, error: pytest.ExceptionInfo) -> None:
    assert sampler.sides == [3, 3, 6]  # made, one 3 x 3 episode, then the 6 x 6 draw
    message = str(error.value)
    assert "draw mazes of one size" in message
    assert "seed 0 when the env was made" in message


def test_a_goal_env_refuses_the_first_larger_maze_at_its_reset() -> None:
    sampler = Alternating()
    env = MazeGoalEnv(world=sampler, start_goal="random")
    observation, _ = env.reset(seed=1)
    assert env.observation_space.contains(observation)
    with pytest.raises(InvalidArgumentError, match=REFUSAL) as error:
        env.reset()
    refused_at_the_first_large_draw(sampler, error)
    env.close()


def test_a_goal_task_made_with_gymnasium_refuses_it_too() -> None:
    sampler = Alternating()
    env = gymnasium.make(GOAL_TASK, world=sampler)
    env.reset(seed=2)
    with pytest.raises(InvalidArgumentError, match=REFUSAL) as error:
        env.reset()
    refused_at_the_first_large_draw(sampler, error)
    env.close()


@pytest.mark.parametrize("num_envs", [1, 2])
def test_the_goal_vector_env_refuses_it_at_reset_or_autoreset(num_envs: int) -> None:
    sampler = Alternating()
    envs = MazeGoalVectorEnv(num_envs, world=sampler, start_goal="random", max_episode_steps=2)
    if num_envs == 2:  # the second environment's first draw
        with pytest.raises(InvalidArgumentError, match=REFUSAL) as error:
            envs.reset(seed=3)
    else:  # the autoreset after the first episode's time limit
        observations, _ = envs.reset(seed=3)
        assert envs.observation_space.contains(observations)
        with pytest.raises(InvalidArgumentError, match=REFUSAL) as error:
            for _ in range(4):
                envs.step(np.zeros((1, 2), dtype=np.float32))
    refused_at_the_first_large_draw(sampler, error)
    envs.close()


@pytest.mark.parametrize("vector", [False, True])
def test_the_pose_of_include_pose_refuses_it_and_no_pose_takes_every_size(vector: bool) -> None:
    for include_pose in (True, False):
        sampler = Alternating()
        env: EPuckMazeEnv | EPuckMazeVectorEnv = (
            EPuckMazeVectorEnv(1, world=sampler, include_pose=include_pose, max_episode_steps=2)
            if vector
            else EPuckMazeEnv(world=sampler, include_pose=include_pose)
        )
        for episode in range(4):
            if include_pose and episode == 1:
                with pytest.raises(InvalidArgumentError, match=REFUSAL) as error:
                    env.reset()
                refused_at_the_first_large_draw(sampler, error)
                break
            observation, _ = env.reset(seed=4 if episode == 0 else None)
            assert env.observation_space.contains(observation)
        if not include_pose:
            assert sampler.sides == [3, 3, 6, 3, 6]
        env.close()


def test_the_goal_observation_with_the_pose_observes_no_metres_and_takes_every_size() -> None:
    sampler = Alternating()
    env = gymnasium.make("mazesim/UnseenMazeExplore-v0", world=sampler, include_pose=True)
    env.reset(seed=5)
    for _ in range(3):
        observation, _ = env.reset()
        assert env.observation_space.contains(observation)
    assert sampler.sides == [3, 3, 6, 3, 6]
    env.close()
