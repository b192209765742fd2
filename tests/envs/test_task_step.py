"""A maze env's step in one call into the core (``Simulator.step_task``) gives what the step of
two calls gave (``Simulator.step_observe``, then ``TaskFeatures.observe_env`` or, for the raw
readings, ``GoalDistance.evaluate_one`` in Python), bit for bit, for every registered task."""

from __future__ import annotations

from typing import Any

import gymnasium
import numpy as np
import pytest

import mazesim
from mazesim._core import TaskFeatures
from mazesim.envs import EPuckMazeEnv
from mazesim.envs.navigation import distance_table
from mazesim.envs.tasks import GOAL_TASKS, TASKS
from mazesim.maze import GoalDistance

#: Every registered task, and the raw env with the pose appended, on a random maze.
CASES: list[tuple[str, dict[str, Any]]] = [(task.env_id, {}) for task in TASKS + GOAL_TASKS] + [
    ("mazesim/EPuckMaze-v0", {"include_pose": True, "world": "random", "start_goal": "random"})
]
STEPS = 400


def python_goal(env: EPuckMazeEnv) -> GoalDistance:
    """The Python goal distance of the env's episode, as the raw env's step used."""
    drawn = env._drawn
    return GoalDistance(1, distance_table(env.world, None if drawn is None else drawn.goal))


def two_call_step(env: EPuckMazeEnv, action: Any) -> tuple[Any, ...]:
    """The maze env's step as two calls into the core made it: the reference."""
    simulator = env._simulator
    assert simulator is not None
    left, right = env._actions.single(action)
    readings, pose, colliding, crossing, collisions = simulator.step_observe(
        left, right, env._low, env._high
    )
    if env._features is not None:
        observation, distance, reached = env._features.observe_one(
            readings, pose, left, right, env._max_speed
        )
    else:
        observation = env._layout.assemble_one(readings, pose)
        distance, reached = python_goal(env).evaluate_one(float(pose[0]), float(pose[1]))
    progress, collision, goal = env._weights
    reward = progress * (env._distance - distance) - collision * colliding + goal * reached
    env._distance = distance
    info = {
        "pose": pose,
        "collisions": collisions,
        "colliding": colliding,
        "distance_to_goal": distance,
        "is_success": reached,
    }
    if crossing != 0:
        info["checkpoint"] = crossing
    return observation, reward, reached, False, info


def maze_of(env: Any) -> EPuckMazeEnv:
    inner = env.unwrapped
    return inner.maze if hasattr(inner, "maze") else inner


def reset_both(one: EPuckMazeEnv, two: EPuckMazeEnv, seed: int | None) -> None:
    for env in (one, two):
        observation, info = env.reset(seed=seed)
        if env._features is None:  # the raw env's distance at the start, as Python gave it
            x, y = (float(v) for v in info["pose"][:2])
            assert info["distance_to_goal"] == python_goal(env).evaluate_one(x, y)[0]


@pytest.mark.parametrize(("env_id", "options"), CASES)
def test_the_one_call_step_is_the_two_call_step_bit_for_bit(
    env_id: str, options: dict[str, Any]
) -> None:
    assert mazesim  # registers the tasks
    one = maze_of(gymnasium.make(env_id, **options))
    two = maze_of(gymnasium.make(env_id, **options))
    rng = np.random.default_rng(7)
    for seed in (3, 4):
        reset_both(one, two, seed)
        for _ in range(STEPS):
            # Drive forward mostly, so that the robot moves through cells and hits walls.
            action = np.clip(rng.normal(0.6, 0.5, 2), -1, 1).astype(np.float32)
            got = one.step(action)
            want = two_call_step(two, action)
            np.testing.assert_array_equal(got[0], want[0])
            assert got[0].dtype == want[0].dtype == np.float32
            assert got[1] == want[1] and type(got[1]) is type(want[1])
            assert got[2:4] == want[2:4]
            assert got[4].keys() == want[4].keys()
            np.testing.assert_array_equal(got[4].pop("pose"), want[4].pop("pose"))
            assert got[4] == want[4]
            if got[2]:
                reset_both(one, two, None)
    assert one._simulator is not None and one._simulator.steps > 0


def test_step_task_refuses_features_of_another_sensor_count() -> None:
    env = EPuckMazeEnv(world="seed-maze", observation="goal")
    env.reset(seed=0)
    assert env._features is not None and env._simulator is not None
    width = env._features.core.width - 8  # three sensors instead of the e-puck's eleven
    bounds = np.zeros(width, dtype=np.float32), np.ones(width, dtype=np.float32)
    three = TaskFeatures(1, "goal", False, np.ones(3), *bounds)
    with pytest.raises(mazesim.InvalidArgumentError, match="expected 3 sensor readings"):
        env._simulator.step_task(three, env._bounds, 0.0, 0.0)
