"""Robot-steps per second of the multi-robot RL tasks through their native batch
(:mod:`mazesim.marl`: ``batch_env``, N environments x R robots, observations and rewards
computed on (N, R) arrays, autoreset), against the same environments as PettingZoo
ParallelEnvs stepped one by one. Random actions; a robot-step is one control step (128 ms) of
one robot, counted whether or not its episode is still running. ``docs/multi-robot.md`` quotes
its figures.

    python benches/bench_marl.py [--envs 256] [--steps 200] [--repeats 3] [--threads 0]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from mazesim.marl import aggregation_v0, maze_goals_v0

TASKS = {"maze_goals_v0": maze_goals_v0, "aggregation_v0": aggregation_v0}


def batch_rate(module: object, envs: int, steps: int, repeats: int, threads: int) -> float:
    """Best robot-steps per second of ``repeats`` runs of ``steps`` steps of the native batch."""
    batch = module.batch_env(envs, threads=threads)  # type: ignore[attr-defined]
    batch.reset(0)
    rng = np.random.default_rng(0)
    actions = rng.uniform(-1, 1, size=(steps, envs, batch.num_robots, 2)).astype(np.float32)
    best = 0.0
    for _ in range(repeats):
        start = time.perf_counter()
        for step in actions:
            batch.step(step)
        best = max(best, envs * batch.num_robots * steps / (time.perf_counter() - start))
    return best


def parallel_rate(module: object, envs: int, steps: int) -> float:
    """Robot-steps per second of ``envs`` ParallelEnvs stepped one by one (reset when done)."""
    pool = [module.parallel_env() for _ in range(envs)]  # type: ignore[attr-defined]
    for i, env in enumerate(pool):
        env.reset(seed=i)
    robots = len(pool[0].possible_agents)
    action = np.zeros(2, np.float32)
    start = time.perf_counter()
    for _ in range(steps):
        for env in pool:
            if not env.agents:
                env.reset()
            env.step({agent: action for agent in env.agents})
    return envs * robots * steps / (time.perf_counter() - start)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--envs", type=int, default=256)
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--threads", type=int, default=0, help="batch engine threads (0: all)")
    args = parser.parse_args()
    for name, module in TASKS.items():
        native = batch_rate(module, args.envs, args.steps, args.repeats, args.threads)
        single = parallel_rate(module, min(args.envs, 16), min(args.steps, 100))
        print(
            f"{name}: native batch of {args.envs} envs: {native:,.0f} robot-steps/s; "
            f"ParallelEnvs one by one: {single:,.0f} robot-steps/s ({native / single:.1f}x)"
        )


if __name__ == "__main__":
    main()
