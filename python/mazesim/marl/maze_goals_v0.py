"""``maze_goals_v0``: every e-puck to its own goal in an unseen maze, touching neither the walls
nor each other (JaxNav's task; see :class:`mazesim.marl.tasks.MazeGoalsTask` for the
observation, the reward and when an agent is done).

Example:
    >>> from mazesim.marl import maze_goals_v0
    >>> env = maze_goals_v0.parallel_env(num_robots=2)
    >>> observations, infos = env.reset(seed=0)
    >>> sorted(observations), observations["epuck_0"].shape
    (['epuck_0', 'epuck_1'], (12,))
"""

from __future__ import annotations

from mazesim.marl.entry_points import entry_points
from mazesim.marl.tasks import MazeGoalsTask

__all__ = ["batch_env", "env", "parallel_env", "raw_env", "task"]


def task(
    num_robots: int = 3,
    maze_size: tuple[int, int] = (4, 4),
    loops: float = 0.5,
    max_cycles: int = 300,
    end_on_collision: bool = True,
    **rewards: float,
) -> MazeGoalsTask:
    """The task's rules (``rewards``: ``goal_reward``, ``collision_penalty``, ``progress_reward``,
    ``step_penalty``)."""
    return MazeGoalsTask(
        num_robots,
        maze_size=maze_size,
        loops=loops,
        max_cycles=max_cycles,
        end_on_collision=end_on_collision,
        **rewards,
    )


parallel_env, raw_env, env, batch_env = entry_points(task)
