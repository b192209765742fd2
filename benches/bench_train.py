"""The lower level's training rounds in the core against the same rounds stepped from Python.

Not a test: run it by hand::

    .venv/bin/python benches/bench_train.py [--envs 2048] [--rounds 3] [--threads 2] [--json]

Two trainers of ``mazesim train``'s lower-level settings (2,048 robots, rounds of 500 control
steps, the pool of 200 generated mazes) run the same rounds in turns, one round each: one in the
core (``BatchSimulator.train_lower_round``, what ``mazesim train`` runs), one stepped from Python
one control step at a time (``run_round(k, stepwise=True)``, what a fleet of several sensor sets
runs). Taking turns puts other load on the machine on both alike. Every round's counts must be
equal (the two give the same tables bit for bit); the figures are the medians of the rounds'
wall times, in env-steps per second, and their ratio.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import time
from typing import Any

from mazesim.learn.lower import LowerSettings, LowerTrainer


def measure(envs: int, rounds: int, threads: int) -> dict[str, Any]:
    """Times ``rounds`` rounds of each loop, in turns; see the module."""
    settings = LowerSettings(num_envs=envs, total_steps=envs * 500 * rounds)
    in_core = LowerTrainer(settings, threads=threads)
    stepwise = LowerTrainer(settings, threads=threads)
    seconds: dict[str, list[float]] = {"core": [], "stepwise": []}
    for k in range(rounds):
        start = time.perf_counter()
        core_stats = in_core.run_round(k)
        seconds["core"].append(time.perf_counter() - start)
        start = time.perf_counter()
        step_stats = stepwise.run_round(k, stepwise=True)
        seconds["stepwise"].append(time.perf_counter() - start)
        if core_stats != step_stats:
            raise SystemExit(f"round {k}: the loops differ: {core_stats} against {step_stats}")
    env_steps = envs * settings.round_steps
    median = {name: statistics.median(times) for name, times in seconds.items()}
    return {
        "envs": envs,
        "round_steps": settings.round_steps,
        "rounds": rounds,
        "threads": threads,
        "seconds_per_round": median,
        "env_steps_per_second": {name: env_steps / t for name, t in median.items()},
        "speedup": median["stepwise"] / median["core"],
        "load_average": os.getloadavg()[0],
        "machine": platform.machine(),
        "cpus": os.cpu_count(),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--envs", type=int, default=2048, help="robots (default: 2048)")
    parser.add_argument("--rounds", type=int, default=3, help="rounds of each loop (default: 3)")
    parser.add_argument("--threads", type=int, default=2, help="worker threads (default: 2)")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args()
    result = measure(args.envs, args.rounds, args.threads)
    if args.json:
        print(json.dumps(result, indent=2))
        return
    rate = result["env_steps_per_second"]
    per_round = result["seconds_per_round"]
    print(f"lower-level rounds, {args.envs} robots x 500 steps, {args.threads} threads")
    print(
        f"  in the core     {per_round['core']:6.2f} s a round  {rate['core']:12,.0f} env-steps/s"
    )
    print(
        f"  from Python     {per_round['stepwise']:6.2f} s a round  "
        f"{rate['stepwise']:12,.0f} env-steps/s"
    )
    print(f"  speed-up        {result['speedup']:.2f}x (load average {result['load_average']:.1f})")


if __name__ == "__main__":
    main()
