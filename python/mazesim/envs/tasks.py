"""The task suite: registered gymnasium ids, from one maze with a fixed start to unseen mazes.

=====================================  ======================================================
id                                     task
=====================================  ======================================================
``mazesim/EPuckMaze-v0``               seed-maze, its start and goal, raw readings (as it was)
``mazesim/MazeFixed-v0``               tier 1: seed-maze, its fixed start and goal;
                                       goal-conditioned observation
``mazesim/MazeRandomGoal-v0``          tier 2: seed-maze, random start and goal cells
``mazesim/UnseenMaze-v0``              tier 3: a new 5 x 5 maze every episode, random start
                                       and goal, goal-conditioned observation only
``mazesim/UnseenMazeGuided-v0``        tier 4: as tier 3, plus the next waypoint of the
                                       shortest path: the tier a feed-forward policy solves on
                                       mazes it never saw
=====================================  ======================================================

The observations are those of :mod:`mazesim.envs.navigation`; the reward is the one of every
maze env (:mod:`mazesim.envs.reward`). Every option can still be changed at ``make``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

__all__ = ["TASKS", "Task", "register_tasks"]


@dataclass(frozen=True)
class Task:
    """One registered task.

    Attributes:
        env_id: The gymnasium id.
        tier: 0 for the original env, then 1 (easiest) to 4.
        summary: What the task is, in one line.
        max_episode_steps: The time limit in control steps of 32 ms.
        options: The env options that make the task (see ``EnvOptions.create``).
    """

    env_id: str
    tier: int
    summary: str
    max_episode_steps: int
    options: dict[str, Any] = field(default_factory=dict)


#: Every registered task, easiest first.
TASKS: tuple[Task, ...] = (
    Task("mazesim/EPuckMaze-v0", 0, "seed-maze from its start, raw readings", 3000),
    Task(
        "mazesim/MazeFixed-v0",
        1,
        "one maze (seed-maze), fixed start and goal",
        2000,
        {"world": "seed-maze", "observation": "goal"},
    ),
    Task(
        "mazesim/MazeRandomGoal-v0",
        2,
        "one maze (seed-maze), random start and goal cells",
        2000,
        {"world": "seed-maze", "observation": "goal", "start_goal": "random"},
    ),
    Task(
        "mazesim/UnseenMaze-v0",
        3,
        "a new 5 x 5 maze each episode, random start and goal",
        1500,
        {"world": "random", "observation": "goal", "start_goal": "random"},
    ),
    Task(
        "mazesim/UnseenMazeGuided-v0",
        4,
        "a new 5 x 5 maze each episode, random start and goal, the path's next waypoint observed",
        1500,
        {"world": "random", "observation": "guided", "start_goal": "random"},
    ),
)


def register_tasks() -> None:
    """Registers every task (single and vector entry points) that is not registered yet."""
    from gymnasium.envs.registration import register, registry

    for task in TASKS:
        if task.env_id in registry:
            continue
        register(
            id=task.env_id,
            entry_point="mazesim.envs.maze_env:EPuckMazeEnv",
            vector_entry_point="mazesim.envs.vector:EPuckMazeVectorEnv",
            max_episode_steps=task.max_episode_steps,
            kwargs=dict(task.options),
        )
