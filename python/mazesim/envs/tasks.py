"""The task suite: registered gymnasium ids, from one maze with a fixed start to unseen mazes.

=====================================  ======================================================
id                                     task
=====================================  ======================================================
``mazesim/EPuckMaze-v0``               seed-maze, its start and goal, raw readings (as it was)
``mazesim/MazeFixed-v1``               tier 1: seed-maze, its fixed start and goal;
                                       goal-conditioned observation, 128 ms control step
``mazesim/MazeRandomGoal-v1``          tier 2: seed-maze, random start and goal cells that
                                       join; goal and pose observed, 128 ms control step
``mazesim/UnseenMazeExplore-v0``       tier 3: a new 5 x 5 maze every episode, random start
                                       and goal; the goal and the map explored so far
                                       (open sides, visits round the robot), 128 ms; the
                                       learning tier (formerly ``mazesim/UnseenMaze-v1``)
``mazesim/UnseenMaze-v2``              tier 3: as UnseenMazeExplore-v0, plus the next
                                       waypoint of the shortest path through the maze as the
                                       robot knows it (visited cells' sides, the rest assumed
                                       open); 32 ms: the generalising task whose observation
                                       a mapping robot computes itself
``mazesim/UnseenMazeGuided-v0``        tier 4: as tier 3, plus the next waypoint of the
                                       shortest path through the true maze (a map-given,
                                       privileged task)
``mazesim/EPuckGoal-v0``               goal-conditioned (:mod:`mazesim.envs.goal`): seed-maze,
                                       random start and goal, sparse reward; ``...Dense-v0``
                                       with the dense reward
``mazesim/UnseenMazeGoal-v0``          goal-conditioned: a new 5 x 5 maze every episode, the
                                       explored map observed, sparse; ``...Dense-v0`` dense
=====================================  ======================================================

The observations are those of :mod:`mazesim.envs.navigation`; the reward is the one of every
maze env (:mod:`mazesim.envs.reward`). Every option can still be changed at ``make``.

Version 1 of tiers 1 and 2 (version 0 was never released) and tier 3's
``UnseenMazeExplore-v0`` act every 128 ms instead of every 32 ms,
with time limits of the same order in seconds (500 or 1000 steps): with a 32 ms step an episode
was 1,500 to 2,000 steps whose rewards were each a few thousandths, too long a horizon for a
discount of 0.99, and PPO learned nothing in minutes. Tier 2 also observes the pose (on one known
maze, where the robot is tells the way) and draws start and goal only among cells that join
(seed-maze has four walled-in cells). Tier 3 observes the map the robot has explored in this
episode (``observation="explore"``): with the goal's direction alone a memoryless policy drives in
circles in a maze it cannot see, with its visits it can prefer the corridors it has not tried.

Version 2 of tier 3 (``observation="plan"``) adds the next waypoint of a plan
the robot could make itself: the shortest path through the maze as it knows it, planned again
on entering each new cell. The policy then only has to drive from cell to cell, as in tier 4,
which a feed-forward policy learns in about a million env-steps at 32 ms; the exploring is the
planner's. Its time limit (3000 steps, 96 s) leaves room for the dead ends the plan walks into.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

__all__ = [
    "GOAL_TASKS",
    "LONG_STEP_MS",
    "REWARD_THRESHOLD",
    "TASKS",
    "Task",
    "register_tasks",
    "task_ids",
]


#: The registered ``reward_threshold`` of every task: the default goal bonus.
REWARD_THRESHOLD = 10.0


@dataclass(frozen=True)
class Task:
    """One registered task.

    Attributes:
        env_id: The gymnasium id.
        tier: 0 for the original env, then 1 (easiest) to 4.
        summary: What the task is, in one line.
        max_episode_steps: The time limit in control steps (of 32 ms, or of the task's
            ``control_step_ms``: 128 ms for tiers 1 to 3 of version 1).
        options: The env options that make the task (see ``EnvOptions.create``).
        entry_point: The single env's class.
        vector_entry_point: The native vector env's class (every registered task has one), or
            None (``make_vec`` then runs gymnasium's ``SyncVectorEnv``).
        reward_threshold: The mean episode return gymnasium's spec calls solved: the goal
            bonus of the default reward (:class:`~mazesim.envs.RewardWeights`, 10). An episode
            that reaches the goal earns the bonus plus the progress along the shortest path
            from its start, less its collisions; one that does not earns at most its progress,
            so a mean return at or above the bonus is what a policy reaching the goal in most
            episodes earns. The success rate (``info["is_success"]``) stays the measure the
            docs report. None for the goal-conditioned tasks.
    """

    env_id: str
    tier: int
    summary: str
    max_episode_steps: int
    options: dict[str, Any] = field(default_factory=dict)
    reward_threshold: float | None = REWARD_THRESHOLD
    entry_point: str = "mazesim.envs.maze_env:EPuckMazeEnv"
    vector_entry_point: str | None = "mazesim.envs.vector:EPuckMazeVectorEnv"


#: The control step of tiers 1 to 3 in ms: four physics steps of 32 ms per action, so that a
#: discount of 0.99 looks about 13 s ahead (a few cells) and episodes are a few hundred steps.
LONG_STEP_MS = 128.0

#: Seed-maze with random start and goal cells, at the 128 ms step of tiers 1 to 3.
_SEED_MAZE_GOALS = {
    "world": "seed-maze",
    "observation": "goal",
    "start_goal": "random",
    "control_step_ms": LONG_STEP_MS,
}
#: A new 5 x 5 maze every episode, the explored map observed (``UnseenMazeExplore-v0``).
_UNSEEN_MAZE_GOALS = {
    "world": "random",
    "observation": "explore",
    "start_goal": "random",
    "control_step_ms": LONG_STEP_MS,
}

#: Every registered task, easiest first.
TASKS: tuple[Task, ...] = (
    Task("mazesim/EPuckMaze-v0", 0, "seed-maze from its start, raw readings", 3000),
    Task(
        "mazesim/MazeFixed-v1",
        1,
        "one maze (seed-maze), fixed start and goal",
        500,
        {"world": "seed-maze", "observation": "goal", "control_step_ms": LONG_STEP_MS},
    ),
    Task(
        "mazesim/MazeRandomGoal-v1",
        2,
        "one maze (seed-maze), random start and goal cells, the robot's pose observed",
        500,
        {
            "world": "seed-maze",
            "observation": "goal",
            "include_pose": True,
            "start_goal": "random",
            "control_step_ms": LONG_STEP_MS,
        },
    ),
    Task(
        "mazesim/UnseenMazeExplore-v0",
        3,
        "a new 5 x 5 maze each episode, random start and goal, the explored map observed",
        1000,
        _UNSEEN_MAZE_GOALS,
    ),
    Task(
        "mazesim/UnseenMaze-v2",
        3,
        "a new 5 x 5 maze each episode, random start and goal, the explored map and the next "
        "waypoint of a path planned through it observed",
        3000,
        {"world": "random", "observation": "plan", "start_goal": "random"},
    ),
    Task(
        "mazesim/UnseenMazeGuided-v0",
        4,
        "a new 5 x 5 maze each episode, random start and goal, the path's next waypoint observed",
        1500,
        {"world": "random", "observation": "guided", "start_goal": "random"},
    ),
)


_GOAL_ENV = "mazesim.envs.goal:MazeGoalEnv"
_GOAL_VECTOR_ENV = "mazesim.envs.goal:MazeGoalVectorEnv"

#: The goal-conditioned tasks (:mod:`mazesim.envs.goal`): the sparse reward (0 at the goal, -1
#: elsewhere; a solved episode returns more than -``max_episode_steps``) and the dense one (minus
#: the distance to the goal). Their ``reward_threshold`` is None: the success rate is the measure.
GOAL_TASKS: tuple[Task, ...] = tuple(
    Task(
        env_id,
        tier,
        summary,
        steps,
        {**options, "reward_type": reward_type},
        reward_threshold=None,
        entry_point=_GOAL_ENV,
        vector_entry_point=_GOAL_VECTOR_ENV,
    )
    for env_id, tier, summary, steps, options, reward_type in (
        (
            "mazesim/EPuckGoal-v0",
            2,
            "seed-maze, random goal, sparse",
            500,
            _SEED_MAZE_GOALS,
            "sparse",
        ),
        (
            "mazesim/EPuckGoalDense-v0",
            2,
            "seed-maze, random goal, dense",
            500,
            _SEED_MAZE_GOALS,
            "dense",
        ),
        (
            "mazesim/UnseenMazeGoal-v0",
            3,
            "a new 5 x 5 maze, random goal, sparse",
            1000,
            _UNSEEN_MAZE_GOALS,
            "sparse",
        ),
        (
            "mazesim/UnseenMazeGoalDense-v0",
            3,
            "a new 5 x 5 maze, random goal, dense",
            1000,
            _UNSEEN_MAZE_GOALS,
            "dense",
        ),
    )
)


#: Ids a task was registered under before, and the task's id now. ``mazesim/UnseenMaze-v1`` is
#: the learning tier under its first id: gymnasium took it for an older version of
#: ``UnseenMaze-v2`` (another task, whose observation holds a plan) and warned at every ``make``
#: that it was out of date; the former id still makes the same env, with that warning.
FORMER_IDS: dict[str, str] = {"mazesim/UnseenMaze-v1": "mazesim/UnseenMazeExplore-v0"}


def register_tasks() -> None:
    """Registers every task (single and vector entry points) that is not registered yet, and
    each task's former ids (:data:`FORMER_IDS`)."""
    from gymnasium.envs.registration import register, registry

    now = {former: next(t for t in TASKS if t.env_id == new) for former, new in FORMER_IDS.items()}
    named = [(task.env_id, task) for task in TASKS + GOAL_TASKS] + list(now.items())
    for env_id, task in named:
        if env_id in registry:
            continue
        register(
            id=env_id,
            entry_point=task.entry_point,
            vector_entry_point=task.vector_entry_point,
            max_episode_steps=task.max_episode_steps,
            reward_threshold=task.reward_threshold,
            kwargs=dict(task.options),
        )


def task_ids() -> list[str]:
    """The id of every task mazesim registers, the goal-conditioned ones included, in order."""
    return [task.env_id for task in (*TASKS, *GOAL_TASKS)]
