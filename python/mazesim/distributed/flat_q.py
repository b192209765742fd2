"""The sweep's own trainer: seeded flat tabular Q-learning on the batch engine.

One Q-table over the lower level's 4096 distance states (:mod:`mazesim.learn.discretise`: the six
Sharp distances of the ``seed`` robot, Table 4.1) and the twelve primitive actions
(:mod:`mazesim.actions`), trained on all the envs of a :class:`mazesim.BatchSimulator` at once
with :func:`mazesim.learn.qlearning.batch_update` (a constant learning rate) and epsilon-greedy
exploration. It knows no position, so the best it can learn is a way of following corridors that
tends towards the goal: a baseline that makes a sweep real, not a navigator.

**Reward** per control step: ``10 * (metres of progress towards the goal)``, where the distance
to go is measured along the maze's corridors (:class:`GoalDistance`), minus
``collision_penalty`` while touching a wall, plus 5 on reaching the goal disc, which ends the
episode. An episode is cut off (not ended: its last step still bootstraps) after
``episode_steps`` control steps. The progress terms of a path add up to the distance it gained,
so driving back and forth earns nothing.

Expect a low success rate: the six distances do not say where in the maze the robot is, so the
same state asks for different actions in different corridors (the report's flat learner did not
reach its goal either). :mod:`mazesim.learn` is the navigator; this trainer is the sweep's
stand-in and yardstick.

**Seeds.** Everything random comes from the setting's seed: the exploration draws, the sensor
noise of every training episode, and that of evaluation episode ``e``
(:func:`evaluation_seeds`), which depends on ``e`` alone. The batch engine gives the same result
whatever its thread count, so the tables are the same bit for bit wherever the run happens.
"""

from __future__ import annotations

import math
import time
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from mazesim._core import BatchSimulator, RobotProfile, World
from mazesim.actions import WHEEL_SPEED_FRACTIONS
from mazesim.errors import InvalidArgumentError
from mazesim.learn.discretise import NUM_STATES, observation_states
from mazesim.learn.qlearning import LearningRate, batch_update, epsilon_greedy, greedy
from mazesim.maze import CellMaze

if TYPE_CHECKING:
    from mazesim.distributed.config import Setting

__all__ = [
    "CURVE_POINTS",
    "DEFAULTS",
    "GOAL_REWARD",
    "PROGRESS_REWARD",
    "ROBOT",
    "GoalDistance",
    "evaluate",
    "evaluation_seeds",
    "train",
]

#: The robot profile: six Sharp distance sensors in volts.
ROBOT = "seed"
#: Reward per metre of progress towards the goal.
PROGRESS_REWARD = 10.0
#: Reward for reaching the goal disc.
GOAL_REWARD = 5.0
#: Points of the training curve (windows of equal length).
CURVE_POINTS = 20
#: The values of the hyperparameters a setting leaves to the trainer (``None`` in the setting).
DEFAULTS: dict[str, int | float] = {
    "episode_steps": 1500,
    "learning_rate": 0.2,
    "epsilon": 0.1,
    "discount": 0.97,
    "collision_penalty": 0.5,
}
#: Largest batch an evaluation steps at once.
EVALUATION_BATCH = 256

_TRAINING, _EVALUATION = 1, 2


class GoalDistance:
    """Metres from points to the goal along the maze's corridors.

    In a world with a cell maze it is ``cell_size * (cells from the point's cell to the goal's)
    + (straight distance to the point where the point's cell opens towards the goal)``; in a
    world without one, the straight distance to the goal.

    Args:
        world: A world with a goal.
    """

    def __init__(self, world: World) -> None:
        goal = world.goal
        if goal is None:
            raise InvalidArgumentError(
                f"expected a world with a goal, found none in {world.name!r}"
            )
        self.goal_x, self.goal_y, self.radius = goal
        self.maze = CellMaze(world) if world.cell_maze() is not None else None
        if self.maze is None:
            return
        maze = self.maze
        columns, rows = maze.cell_at(self.goal_x, self.goal_y)
        self.cells_to_go = maze.distances_from((int(columns), int(rows)))
        self.exit_x = np.full((maze.rows, maze.cols), self.goal_x)
        self.exit_y = np.full((maze.rows, maze.cols), self.goal_y)
        for cell in maze.cells():
            column, row = cell
            here = self.cells_to_go[row, column]
            for direction in maze.openings(cell) if here > 0 else []:
                next_column, next_row = maze.neighbour(cell, direction)
                if self.cells_to_go[next_row, next_column] == here - 1:
                    center_x, center_y = maze.center(cell)
                    heading = maze.heading_of(direction)
                    self.exit_x[row, column] = center_x + 0.5 * maze.cell_size * math.cos(heading)
                    self.exit_y[row, column] = center_y + 0.5 * maze.cell_size * math.sin(heading)
                    break

    def __call__(self, poses: npt.NDArray[np.float32]) -> npt.NDArray[np.float64]:
        """The distances to go of (N, >= 2) poses (x, y first)."""
        x = poses[:, 0].astype(np.float64)
        y = poses[:, 1].astype(np.float64)
        if self.maze is None:
            return np.hypot(x - self.goal_x, y - self.goal_y)
        columns, rows = self.maze.cell_at(x, y)
        cells = self.cells_to_go[rows, columns]
        along = cells * self.maze.cell_size + np.hypot(
            x - self.exit_x[rows, columns], y - self.exit_y[rows, columns]
        )
        return np.where(cells >= 0, along, np.hypot(x - self.goal_x, y - self.goal_y))

    def reached(self, poses: npt.NDArray[np.float32]) -> npt.NDArray[np.bool_]:
        """Whether each pose's centre is on the goal disc."""
        x = poses[:, 0].astype(np.float64)
        y = poses[:, 1].astype(np.float64)
        return np.asarray(np.hypot(x - self.goal_x, y - self.goal_y) <= self.radius)


def evaluation_seeds(seed: int, first: int, count: int) -> npt.NDArray[np.uint64]:
    """The sensor-noise seeds of evaluation episodes ``first`` to ``first + count - 1``."""
    return np.array(
        [
            np.random.SeedSequence(seed, spawn_key=(_EVALUATION, episode)).generate_state(
                1, np.uint64
            )[0]
            for episode in range(first, first + count)
        ],
        dtype=np.uint64,
    )


def hyperparameters(setting: Setting) -> dict[str, Any]:
    """The setting's parameters with :data:`DEFAULTS` for those it leaves to the trainer."""
    params = dict(setting.params)
    for name, value in DEFAULTS.items():
        if params.get(name) is None:
            params[name] = value
    return params


def _buffers(batch: BatchSimulator) -> tuple[npt.NDArray[Any], ...]:
    n = batch.num_envs
    return (
        np.zeros((n, batch.observation_width), np.float32),
        np.zeros((n, 3), np.float32),
        np.zeros(n, bool),
        np.zeros(n, np.int32),
    )


def train(setting: Setting, threads: int = 1) -> dict[str, Any]:
    """Trains a flat Q-table for one setting and evaluates its greedy policy.

    Args:
        setting: The setting (see :data:`mazesim.distributed.config.PARAMETERS`).
        threads: Threads of the batch engine (the result does not depend on them).

    Returns:
        A dict with ``tables`` (``q``, ``visits``), ``curves`` (equal-length columns),
        ``evaluation`` (``success_rate``, ``mean_collisions``, ``mean_steps``), ``env_steps``,
        ``eval_env_steps``, ``training_seconds`` and ``evaluation_seconds``.
    """
    started = time.perf_counter()
    params = hyperparameters(setting)
    world = setting.world()
    to_go = GoalDistance(world)
    envs, steps, episode_steps = params["envs"], params["steps"], params["episode_steps"]
    epsilon, discount = params["epsilon"], params["discount"]
    rate = LearningRate(initial=params["learning_rate"], floor=params["learning_rate"], power=0.0)
    exploration = np.random.default_rng(np.random.SeedSequence(setting.seed, spawn_key=(0,)))
    noise_seeds = np.random.default_rng(np.random.SeedSequence(setting.seed, spawn_key=(1,)))

    def draw_seeds() -> npt.NDArray[np.uint64]:
        return noise_seeds.integers(0, 2**63, size=envs, dtype=np.uint64)

    speeds = (WHEEL_SPEED_FRACTIONS * RobotProfile.builtin(ROBOT).max_wheel_speed).astype(
        np.float32
    )
    batch = BatchSimulator(
        world, num_envs=envs, robot=ROBOT, seeds=0, noise=params["noise"], threads=threads
    )
    observations, poses, colliding, crossings = _buffers(batch)
    batch.reset(observations, poses, colliding, crossings, seeds=draw_seeds())
    q = np.zeros((NUM_STATES, len(speeds)), dtype=np.float64)
    visits = np.zeros(q.shape, dtype=np.int64)
    states = observation_states(observations)
    distance = to_go(poses)
    episode_step = np.zeros(envs, dtype=np.int64)

    window = max(1, steps // CURVE_POINTS)
    curve: dict[str, list[float]] = {
        name: [] for name in ("step", "env_steps", "episodes", "success_rate", "mean_reward")
    }
    finished = successes = window_steps = 0
    reward_sum = 0.0
    for step in range(1, steps + 1):
        actions = epsilon_greedy(q, states, epsilon, exploration)
        batch.step(speeds[actions], observations, poses, colliding, crossings)
        episode_step += 1
        next_distance = to_go(poses)
        reached = to_go.reached(poses)
        rewards = (
            PROGRESS_REWARD * (distance - next_distance)
            - params["collision_penalty"] * colliding
            + GOAL_REWARD * reached
        )
        next_states = observation_states(observations)
        batch_update(
            q, visits, states, actions, rewards, next_states, np.where(reached, 0.0, discount), rate
        )
        done = reached | (episode_step >= episode_steps)
        finished += int(done.sum())
        successes += int(reached.sum())
        reward_sum += float(rewards.sum())
        window_steps += 1
        if done.any():
            batch.reset(observations, poses, colliding, crossings, mask=done, seeds=draw_seeds())
            episode_step[done] = 0
            next_states = observation_states(observations)
            next_distance = to_go(poses)
        states, distance = next_states, next_distance
        if step % window == 0 or step == steps:
            curve["step"].append(step)
            curve["env_steps"].append(step * envs)
            curve["episodes"].append(finished)
            curve["success_rate"].append(successes / finished if finished else math.nan)
            curve["mean_reward"].append(reward_sum / (envs * window_steps))
            finished = successes = window_steps = 0
            reward_sum = 0.0
    training_seconds = time.perf_counter() - started

    started = time.perf_counter()
    evaluation = evaluate(setting, q, 0, params["eval_episodes"], threads)
    evaluation_seconds = time.perf_counter() - started
    return {
        "tables": {"q": q, "visits": visits},
        "curves": {name: np.asarray(values) for name, values in curve.items()},
        "evaluation": {
            "success_rate": float(np.mean(evaluation["reached"])),
            "mean_collisions": float(np.mean(evaluation["collisions"])),
            "mean_steps": float(np.mean(evaluation["steps"])),
        },
        "env_steps": envs * steps,
        "eval_env_steps": int(np.sum(evaluation["steps"])),
        "training_seconds": training_seconds,
        "evaluation_seconds": evaluation_seconds,
    }


def evaluate(
    setting: Setting, q: npt.NDArray[np.float64], first: int, count: int, threads: int = 1
) -> dict[str, npt.NDArray[Any]]:
    """Runs greedy episodes ``first`` to ``first + count - 1`` of a setting's evaluation.

    Episode ``e`` starts at the world's start with the sensor-noise seed
    ``evaluation_seeds(seed, e, 1)`` and ends at the goal or after ``episode_steps`` steps, so
    its outcome does not depend on which other episodes run with it: evaluations split into
    chunks (on several machines) give the same episodes as one.

    Returns:
        Per-episode arrays: ``reached`` (bool), ``steps`` (steps taken) and ``collisions``.
    """
    params = hyperparameters(setting)
    world = setting.world()
    to_go = GoalDistance(world)
    speeds = (WHEEL_SPEED_FRACTIONS * RobotProfile.builtin(ROBOT).max_wheel_speed).astype(
        np.float32
    )
    reached_all = np.zeros(count, dtype=bool)
    steps_all = np.zeros(count, dtype=np.int64)
    collisions_all = np.zeros(count, dtype=np.int64)
    for chunk_start in range(0, count, EVALUATION_BATCH):
        n = min(EVALUATION_BATCH, count - chunk_start)
        batch = BatchSimulator(
            world, num_envs=n, robot=ROBOT, seeds=0, noise=params["noise"], threads=threads
        )
        observations, poses, colliding, crossings = _buffers(batch)
        seeds = evaluation_seeds(setting.seed, first + chunk_start, n)
        batch.reset(observations, poses, colliding, crossings, seeds=seeds)
        running = np.ones(n, dtype=bool)
        rows = slice(chunk_start, chunk_start + n)
        for step in range(1, params["episode_steps"] + 1):
            actions = np.where(running, greedy(q, observation_states(observations)), 0)
            wheels = np.where(running[:, None], speeds[actions], np.float32(0.0))
            batch.step(wheels, observations, poses, colliding, crossings)
            arrived = running & to_go.reached(poses)
            ending = arrived | (running & (step == params["episode_steps"]))
            reached_all[rows] |= arrived
            steps_all[rows] = np.where(ending, step, steps_all[rows])
            collisions_all[rows] = np.where(
                ending, batch.collisions().astype(np.int64), collisions_all[rows]
            )
            running &= ~ending
            if not running.any():
                break
    return {"reached": reached_all, "steps": steps_all, "collisions": collisions_all}
