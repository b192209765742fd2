"""Every registered task, one env through ``gymnasium.make``, against CartPole-v1 in the same run.

Not a test: run it by hand or with ``make bench-tasks`` (gymnasium must be installed)::

    .venv/bin/python benches/bench_tasks.py [--rounds 15] [--round 3000] [--json]

Each task (every id of gymnasium's registry that starts with ``mazesim/``) and CartPole-v1 are
made with ``gymnasium.make`` (so with its wrappers: the time limit, the order and passive checks),
reset with seed 0 and stepped with uniformly random actions from a pool drawn beforehand (the
policy costs nothing); an episode that ends is reset (new random mazes included).

The measure is the processor time of one step (``time.process_time``), which other jobs on the
machine disturb far less than the wall clock: each task runs ``--rounds`` rounds of ``--round``
steps, each round followed by a round of its own CartPole-v1, so that both see the same machine.
A step's cost is the median round's processor time over its steps, the resets in the round
included: a reset's cost is amortised over the steps of its episode. Every registered time limit
(500, 1000, 1500, 3000 steps) divides the default round of 3,000 steps, so each round of a task
holds as many resets as any other (random actions seldom end an episode before its limit). The
figure to read is CartPole-v1's time over the task's: its rate as a multiple of CartPole-v1's.

The native vector env's lead: each task with a vector entry point is also made with
``gymnasium.make_vec(..., vectorization_mode="vector_entry_point")`` of ``--vector-envs``
environments and stepped in rounds of as many env-steps, alternating with the single env; the
lead is the single env's processor time per step over the vector env's per env-step (its
threads' time included).

Exits with status 1 if any task steps slower than CartPole-v1 (a ratio below 1), or its native
vector env is not faster per env-step than its single env (a lead below 1).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import sys
import time
from dataclasses import dataclass, field
from typing import Any

import gymnasium

import mazesim  # noqa: F401  (registers the tasks)

POOL = 16
REFERENCE = "CartPole-v1"
PREFIX = "mazesim/"


def task_ids() -> list[str]:
    """Every registered mazesim id, in registration order, but a task's former ids."""
    from mazesim.envs.tasks import FORMER_IDS

    return [
        env_id
        for env_id in gymnasium.registry
        if env_id.startswith(PREFIX) and env_id not in FORMER_IDS
    ]


def action_pool(env: Any) -> list[Any]:
    """Resets ``env`` with seed 0 and draws the pool of random actions it is stepped with."""
    env.reset(seed=0)
    env.action_space.seed(0)
    return [env.action_space.sample() for _ in range(POOL)]


@dataclass
class Runner:
    """One env made by ``gymnasium.make`` and the processor time of its rounds."""

    env_id: str
    env: Any = None
    pool: list[Any] = field(default_factory=list)
    times: list[float] = field(default_factory=list)
    resets: int = 0
    steps: int = 0

    def __post_init__(self) -> None:
        self.env = gymnasium.make(self.env_id)
        self.pool = action_pool(self.env)

    def run(self, count: int, record: bool = True) -> None:
        """Steps ``count`` times, resetting ended episodes; records the round's processor time
        per step."""
        env, pool = self.env, self.pool
        resets = 0
        start = time.process_time()
        for k in range(count):
            _, _, terminated, truncated, _ = env.step(pool[k % POOL])
            if terminated or truncated:
                env.reset()
                resets += 1
        elapsed = time.process_time() - start
        if record:
            self.times.append(elapsed / count)
            self.resets += resets
            self.steps += count

    def result(self) -> dict[str, float]:
        """Microseconds of processor time of a step (its share of the resets included) and the
        mean episode length of the recorded rounds."""
        return {
            "step_us": statistics.median(self.times) * 1e6,
            "episode_steps": self.steps / max(self.resets, 1),
        }


@dataclass
class VectorRunner:
    """A native vector env made by ``gymnasium.make_vec`` and its processor time per env-step."""

    env_id: str
    num_envs: int
    env: Any = None
    pool: list[Any] = field(default_factory=list)
    times: list[float] = field(default_factory=list)

    def __post_init__(self) -> None:
        self.env = gymnasium.make_vec(
            self.env_id, num_envs=self.num_envs, vectorization_mode="vector_entry_point"
        )
        self.pool = action_pool(self.env)

    def run(self, env_steps: int, record: bool = True) -> None:
        """Steps every env (autoreset included) about ``env_steps`` env-steps in all."""
        count = max(1, env_steps // self.num_envs)
        env, pool = self.env, self.pool
        start = time.process_time()
        for k in range(count):
            env.step(pool[k % POOL])
        if record:
            self.times.append((time.process_time() - start) / (count * self.num_envs))


def alternate(runners: tuple[Runner | VectorRunner, ...], rounds: int, round_steps: int) -> None:
    """Runs ``rounds`` rounds of ``round_steps`` steps of each runner in turn, so that all see the
    same machine, then closes their envs."""
    for _ in range(rounds):
        for runner in runners:
            runner.run(round_steps)
    for runner in runners:
        runner.env.close()


def vector_lead(env_id: str, num_envs: int, rounds: int, round_steps: int) -> dict[str, float]:
    """Microseconds of processor time per env-step of the native vector env and of the single
    env, from alternating rounds, and the single env's over the vector env's."""
    single, vector = Runner(env_id), VectorRunner(env_id, num_envs)
    single.run(100, record=False)
    vector.run(num_envs, record=False)
    alternate((single, vector), rounds, round_steps)
    one, each = statistics.median(single.times), statistics.median(vector.times)
    return {"single_us": one * 1e6, "vector_us": each * 1e6, "lead": one / each}


def paired(env_id: str, rounds: int, round_steps: int) -> tuple[dict[str, float], dict[str, float]]:
    """The task's and its own CartPole-v1's times, from alternating rounds."""
    task, reference = Runner(env_id), Runner(REFERENCE)
    for runner in (task, reference):
        runner.run(100, record=False)  # warm up
    alternate((task, reference), rounds, round_steps)
    return task.result(), reference.result()


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=15, help="rounds of each env")
    parser.add_argument("--round", type=int, default=3_000, help="steps of a round")
    parser.add_argument(
        "--vector-envs", type=int, default=256, help="envs of the native vector env (0: skip it)"
    )
    parser.add_argument("--json", action="store_true", help="print the result as JSON")
    args = parser.parse_args()
    if args.rounds < 1 or args.round < 1:
        parser.error("--rounds and --round must be at least 1")
    rows: dict[str, Any] = {}
    for env_id in task_ids():
        task, reference = paired(env_id, args.rounds, args.round)
        rows[env_id] = {
            **task,
            "cartpole_step_us": reference["step_us"],
            "over_cartpole": reference["step_us"] / task["step_us"],
        }
    vectors: dict[str, Any] = {}
    if args.vector_envs > 0:
        for env_id in task_ids():
            if gymnasium.registry[env_id].vector_entry_point is not None:
                vectors[env_id] = vector_lead(env_id, args.vector_envs, args.rounds, args.round)
    try:
        load = f"load average {os.getloadavg()[0]:.1f}"
    except OSError:
        load = "load average unknown"
    result: dict[str, Any] = {
        "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
        "machine": f"{platform.machine()}, {os.cpu_count()} cores, {platform.python_version()}",
        "load": load,
        "rounds": args.rounds,
        "round_steps": args.round,
        "tasks": rows,
        "vector_envs": args.vector_envs,
        "vector": vectors,
    }
    slow = [env_id for env_id, row in rows.items() if row["over_cartpole"] < 1.0]
    behind = [env_id for env_id, row in vectors.items() if row["lead"] < 1.0]
    if args.json:
        print(json.dumps(result, indent=2))
    else:
        print(
            f"{result['date']}, {result['machine']}, {load}: one env through gymnasium.make, "
            f"microseconds of processor time ({args.rounds} rounds of {args.round} steps)"
        )
        print(f"  {'task':<32} {'a step':>7} {'CartPole':>8} {'ratio':>6} {'episode':>8}")
        for env_id, row in rows.items():
            print(
                f"  {env_id:<32} {row['step_us']:>7.2f} {row['cartpole_step_us']:>8.2f} "
                f"{row['over_cartpole']:>5.2f}x {row['episode_steps']:>8.0f}"
            )
        if vectors:
            print(
                f"native vector env of {args.vector_envs} envs, microseconds of processor time "
                f"per env-step"
            )
            print(f"  {'task':<32} {'single':>7} {'vector':>8} {'lead':>6}")
            for env_id, row in vectors.items():
                print(
                    f"  {env_id:<32} {row['single_us']:>7.2f} {row['vector_us']:>8.2f} "
                    f"{row['lead']:>5.2f}x"
                )
    if slow:
        print(f"slower than CartPole-v1: {', '.join(slow)}", file=sys.stderr)
    if behind:
        print(f"native vector env not ahead: {', '.join(behind)}", file=sys.stderr)
    return 1 if slow or behind else 0


if __name__ == "__main__":
    sys.exit(main())
