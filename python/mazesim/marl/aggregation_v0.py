"""``aggregation_v0``: a swarm of e-pucks gathers into one cluster in a square arena (the
aggregation task of Gauci et al. 2014; see :class:`mazesim.marl.tasks.AggregationTask` for the
observation, the reward and the dispersion measure).

Example:
    >>> from mazesim.marl import aggregation_v0
    >>> env = aggregation_v0.parallel_env(num_robots=4)
    >>> observations, infos = env.reset(seed=0)
    >>> len(observations), observations["epuck_3"].shape
    (4, (16,))
"""

from __future__ import annotations

from mazesim.marl.entry_points import entry_points
from mazesim.marl.tasks import AggregationTask

__all__ = ["batch_env", "env", "parallel_env", "raw_env", "task"]


def task(num_robots: int = 5, arena_side: float = 1.0, max_cycles: int = 300) -> AggregationTask:
    """The task's rules."""
    return AggregationTask(num_robots, arena_side=arena_side, max_cycles=max_cycles)


parallel_env, raw_env, env, batch_env = entry_points(task)
