"""Every registered task, one env through ``gymnasium.make``, against CartPole-v1 in the same run.

Not a test: run it by hand or with ``make bench-tasks`` (gymnasium must be installed)::

    .venv/bin/python benches/bench_tasks.py [--steps 20000] [--round 1000] [--json]

Each task (:data:`mazesim.envs.tasks.TASKS` and :data:`~mazesim.envs.tasks.GOAL_TASKS`) and
CartPole-v1 are made with ``gymnasium.make`` (so with its wrappers: the time limit, the order
and passive checks), reset with seed 0 and stepped with uniformly random actions from a pool drawn
beforehand (the policy costs nothing); an episode that ends is reset, so resets (new random mazes
included) are timed with the steps. The contenders run in alternating rounds of ``--round`` steps,
so that other load on the machine falls on all alike; a rate is ``--round`` over the median round
time, and the ratio to CartPole-v1's is the figure to read.

Exits with status 1 if any task steps slower than CartPole-v1 (a ratio below 1).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time
from collections.abc import Callable
from typing import Any

import gymnasium
import numpy as np

import mazesim  # noqa: F401  (registers the tasks)
from mazesim.envs.tasks import GOAL_TASKS, TASKS

POOL = 16
REFERENCE = "CartPole-v1"


def stepper(env_id: str) -> Callable[[int], None]:
    """A function stepping one env made by ``gymnasium.make(env_id)`` a given number of steps."""
    env: Any = gymnasium.make(env_id)
    env.reset(seed=0)
    env.action_space.seed(0)
    pool = [env.action_space.sample() for _ in range(POOL)]

    def run(count: int) -> None:
        for k in range(count):
            _, _, terminated, truncated, _ = env.step(pool[k % POOL])
            if terminated or truncated:
                env.reset()

    return run


def rates(env_ids: list[str], steps: int, round_steps: int) -> dict[str, float]:
    """Steps per second of each env, from the median of alternating rounds."""
    runs = {env_id: stepper(env_id) for env_id in env_ids}
    for run in runs.values():
        run(min(round_steps, 200))  # warm up
    times: dict[str, list[float]] = {env_id: [] for env_id in runs}
    for _ in range(max(3, steps // round_steps)):
        for env_id, run in runs.items():
            start = time.perf_counter()
            run(round_steps)
            times[env_id].append(time.perf_counter() - start)
    return {env_id: round_steps / float(np.median(ts)) for env_id, ts in times.items()}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--steps", type=int, default=20_000, help="steps of each env")
    parser.add_argument("--round", type=int, default=1_000, help="steps between switches")
    parser.add_argument("--json", action="store_true", help="print the result as JSON")
    args = parser.parse_args()
    tasks = [task.env_id for task in TASKS + GOAL_TASKS]
    with_warnings = sys.warnoptions
    if not with_warnings:
        import warnings

        warnings.filterwarnings("ignore", category=DeprecationWarning)  # UnseenMaze-v1 is old
    measured = rates([*tasks, REFERENCE], args.steps, args.round)
    reference = measured[REFERENCE]
    result: dict[str, Any] = {
        "date": time.strftime("%Y-%m-%d", time.gmtime()),
        "machine": f"{platform.machine()}, {os.cpu_count()} cores, {platform.python_version()}",
        "cartpole_steps_per_s": reference,
        "tasks": {
            env_id: {"steps_per_s": measured[env_id], "over_cartpole": measured[env_id] / reference}
            for env_id in tasks
        },
    }
    slow = [env_id for env_id in tasks if measured[env_id] < reference]
    if args.json:
        print(json.dumps(result, indent=2))
    else:
        print(f"{result['date']}, {result['machine']}: one env through gymnasium.make")
        print(f"  {REFERENCE:<34} {reference:>10,.0f} steps/s")
        for env_id, row in result["tasks"].items():
            print(
                f"  {env_id:<34} {row['steps_per_s']:>10,.0f} steps/s "
                f"{row['over_cartpole']:>6.2f} x CartPole-v1"
            )
    if slow:
        print(f"below CartPole-v1's rate: {', '.join(slow)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
