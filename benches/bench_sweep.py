"""A sweep on Ray against the same sweep in a single process: env-steps per second.

Not a test: run it by hand (Ray must be installed)::

    .venv/bin/python benches/bench_sweep.py [--trainer hrl] [--runs 8] [--envs 64] [--steps 1500]
        [--higher-episodes 32] [--json]

The sweep: ``--runs`` settings (seeds) of a trainer on a generated 5 x 5 maze, ``--envs`` envs
for ``--steps`` training steps each, then greedy evaluation episodes of at most 600 steps (32
for ``flat-q``, 16 for ``hrl`` and ``baseline``; ``flat-q`` is another name of ``baseline``).
``hrl`` trains its lower level with those envs and steps, then its higher level for
``--higher-episodes`` episodes of at most 600 steps. One env-step is one control step of 64 ms
of one robot;
training and evaluation both count. Modes:

- single process, 1 thread: :func:`mazesim.distributed.run_sequential`, batch engine on 1 core;
- single process, N threads: the same with the batch engine on every core;
- Ray, cold: :func:`mazesim.distributed.run_sweep` as ``mazesim sweep`` runs it, starting (and
  stopping) a local Ray instance with one CPU per core and one single-threaded task per CPU;
- Ray, warm: the same sweep on a Ray instance that is already up (as on a cluster).

Ray's overhead is read against the single-process runs: a perfect scale-out would give Ray, warm
N times the 1-thread rate. "Tasks busy" is the time spent inside the tasks (training and
evaluation) over wall time x workers: what the rest (Ray's scheduling, start-up, moving results,
writing the output folder) costs, independent of how fast each task ran. The load average of the
machine is printed before and after, since other work on it falls on every mode.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import tempfile
import time
from typing import Any

from mazesim.distributed import SweepSummary, parse_sweep_config, run_sequential, run_sweep
from mazesim.distributed.cluster import local_cpus, ray_session


def sweep_text(trainer: str, runs: int, envs: int, steps: int, higher_episodes: int) -> str:
    seeds = ", ".join(str(seed) for seed in range(runs))
    text = (
        "[sweep]\nname = 'bench'\ncpus_per_task = 1\n\n[grid]\n"
        f"trainer = '{trainer}'\nseed = [{seeds}]\nmaze_size = 5\nenvs = {envs}\n"
        f"steps = {steps}\nepisode_steps = 600\n"
    )
    if trainer == "flat-q":
        return text + "eval_episodes = 32\n"
    if trainer == "hrl":
        text += f"higher_episodes = {higher_episodes}\n"
    return text + "eval_episodes = 16\n"


def measure(trainer: str, runs: int, envs: int, steps: int, higher_episodes: int) -> dict[str, Any]:
    sweep = parse_sweep_config(sweep_text(trainer, runs, envs, steps, higher_episodes))
    cores = local_cpus()
    rates: dict[str, dict[str, float]] = {}

    def record(mode: str, summary: SweepSummary, seconds: float, workers: int) -> None:
        in_tasks = sum(run["training_seconds"] + run["evaluation_seconds"] for run in summary.runs)
        rates[mode] = {
            "env_steps": summary.env_steps,
            "seconds": seconds,
            "env_steps_per_second": summary.env_steps / seconds,
            "task_seconds": in_tasks,
            "busy_share": in_tasks / (seconds * workers),
        }

    with tempfile.TemporaryDirectory(prefix="mazesim-bench-sweep-") as scratch:
        for threads in sorted({1, cores}):
            started = time.perf_counter()
            summary = run_sequential(sweep, os.path.join(scratch, f"seq{threads}"), threads=threads)
            seconds = time.perf_counter() - started
            record(f"single process, {threads} thread(s)", summary, seconds, 1)

        started = time.perf_counter()
        summary = run_sweep(sweep, os.path.join(scratch, "ray-cold"), cpus=cores)
        seconds = time.perf_counter() - started
        record(f"ray, cold ({cores} CPUs, start included)", summary, seconds, cores)

        started = time.perf_counter()
        with ray_session(cpus=cores):
            startup = time.perf_counter() - started
            started = time.perf_counter()
            summary = run_sweep(sweep, os.path.join(scratch, "ray-warm"))
            seconds = time.perf_counter() - started
            record(f"ray, warm ({cores} CPUs)", summary, seconds, cores)
    single = rates["single process, 1 thread(s)"]["env_steps_per_second"]
    warm = rates[f"ray, warm ({cores} CPUs)"]["env_steps_per_second"]
    return {
        "trainer": trainer,
        "runs": runs,
        "envs": envs,
        "steps": steps,
        "cores": cores,
        "ray_startup_seconds": startup,
        "modes": rates,
        "ray_warm_efficiency": warm / (cores * single),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--trainer",
        default="hrl",
        choices=("hrl", "baseline", "flat-q"),
        help="the sweep's trainer (default hrl)",
    )
    parser.add_argument("--runs", type=int, default=8, help="settings of the sweep (default 8)")
    parser.add_argument("--envs", type=int, default=64, help="envs per run (default 64)")
    parser.add_argument("--steps", type=int, default=1500, help="training steps (default 1500)")
    parser.add_argument(
        "--higher-episodes",
        type=int,
        default=32,
        help="hrl: higher-level training episodes (default 32)",
    )
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args()
    load_before = os.getloadavg()
    report = measure(args.trainer, args.runs, args.envs, args.steps, args.higher_episodes)
    report["load_average_before"] = load_before
    report["load_average_after"] = os.getloadavg()
    report["machine"] = f"{platform.machine()}, {os.cpu_count()} cores, {platform.python_version()}"
    if args.json:
        print(json.dumps(report, indent=2))
        return
    print(
        f"{args.trainer} sweep of {args.runs} runs x {args.envs} envs x {args.steps} steps "
        f"(+ {'higher level and ' if args.trainer == 'hrl' else ''}evaluation) "
        f"on {report['machine']}"
    )
    print(f"load average before {load_before[0]:.2f}, after {report['load_average_after'][0]:.2f}")
    for mode, row in report["modes"].items():
        print(
            f"  {mode:<40} {row['env_steps_per_second']:>10,.0f} env-steps/s "
            f"({row['env_steps']:,} in {row['seconds']:.1f} s; "
            f"tasks busy {100 * row['busy_share']:.0f}% of the wall time)"
        )
    print(
        f"Ray start-up {report['ray_startup_seconds']:.1f} s; Ray (warm) reaches "
        f"{100 * report['ray_warm_efficiency']:.0f}% of {report['cores']} x the 1-thread rate"
    )


if __name__ == "__main__":
    main()
