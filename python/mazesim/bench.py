"""``mazesim bench``: env-steps per second and memory per env of the canonical workload.

The workload (docs/performance.md): per env a distinct generated 5 x 5 maze of 0.25 m cells and
0.01 m walls, the e-puck with ps0-7 and gs0-2 all read every step, a 32 ms control step of one
physics step, and wheel speeds from a Braitenberg rule computed in numpy from the observations.
Each batch size runs in a fresh process, so its resident memory is measured on its own.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from typing import Any

import numpy as np

import mazesim
from mazesim.benchmark.report import single_env_rate
from mazesim.benchmark.workloads import braitenberg, braitenberg_one
from mazesim.cli import MAX_COUNT, non_negative_int
from mazesim.errors import InvalidArgumentError

__all__ = ["braitenberg", "braitenberg_one", "measure", "register", "single_env_rate"]

#: Seconds a measurement aims to last when --steps is not given.
TARGET_SECONDS = 1.5

WORKLOAD: dict[str, Any] = {
    "maze": "5 x 5 cells of 0.25 m, walls 0.01 m, a distinct generated maze per env (loops 0.1)",
    "robot": "e-puck: ps0-7 and gs0-2 read every step",
    "control_step_ms": 32,
    "physics_steps_per_control_step": 1,
    "policy": "Braitenberg rule in numpy on ps0-7",
}


def _rss_bytes() -> int:
    with open("/proc/self/statm") as statm:
        return int(statm.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def _auto_steps(envs: int) -> int:
    # About 1 microsecond per env-step per core: aim at TARGET_SECONDS on one core.
    return int(min(20_000, max(30, TARGET_SECONDS * 1e6 / envs)))


def measure(envs: int, steps: int, threads: int, seed: int = 0) -> dict[str, Any]:
    """Runs the workload on ``envs`` envs for ``steps`` steps in this process.

    Returns:
        ``{"envs", "env_steps_per_s", "bytes_per_env", "steps", "seconds"}``.
    """
    rss_before = _rss_bytes()
    worlds = [mazesim.generate_maze(5, 5, seed=seed + i, loops=0.1) for i in range(envs)]
    batch = mazesim.BatchSimulator(worlds, robot="e-puck", seeds=seed, threads=threads)
    del worlds
    obs = np.zeros((envs, batch.observation_width), np.float32)
    poses = np.zeros((envs, 3), np.float32)
    colliding = np.zeros(envs, bool)
    crossings = np.zeros(envs, np.int32)
    actions = np.zeros((envs, 2), np.float32)
    batch.reset(obs, poses, colliding, crossings)
    bytes_per_env = (_rss_bytes() - rss_before) / envs
    # Warm up (caches, thread pool), then time.
    for _ in range(3):
        batch.step(braitenberg(obs[:, :8], actions), obs, poses, colliding, crossings)
    started = time.perf_counter()
    for _ in range(steps):
        batch.step(braitenberg(obs[:, :8], actions), obs, poses, colliding, crossings)
    seconds = time.perf_counter() - started
    return {
        "envs": envs,
        "env_steps_per_s": envs * steps / seconds,
        "bytes_per_env": int(bytes_per_env),
        "steps": steps,
        "seconds": seconds,
    }


def _measure_in_child(envs: int, steps: int, threads: int) -> dict[str, Any]:
    code = (
        f"import json, mazesim.bench as b; print(json.dumps(b.measure({envs}, {steps}, {threads})))"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise InvalidArgumentError(
            f"the benchmark at {envs} envs failed: {done.stderr.strip().splitlines()[-1:]}"
        )
    result: dict[str, Any] = json.loads(done.stdout)
    return result


def _env_counts(text: str) -> list[int]:
    try:
        counts = [int(part) for part in text.split(",") if part.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected env counts like 1,64,1024, found {text!r}"
        ) from None
    if not counts or min(counts) < 1 or max(counts) > MAX_COUNT:
        raise argparse.ArgumentTypeError(f"expected env counts in [1, {MAX_COUNT}], found {text!r}")
    return counts


def run(args: argparse.Namespace) -> int:
    """Runs ``mazesim bench``."""
    results = []
    show = sys.stderr.isatty() and not args.json
    for envs in args.envs:
        steps = args.steps or _auto_steps(envs)
        if show:
            print(f"measuring {envs} envs x {steps} steps ...", file=sys.stderr, flush=True)
        result = _measure_in_child(envs, steps, args.threads)
        results.append({k: result[k] for k in ("envs", "env_steps_per_s", "bytes_per_env")})
    single = single_env_rate(20_000 if args.steps == 0 else max(args.steps, 1000))
    workload = dict(WORKLOAD, threads=args.threads or os.cpu_count(), cpus=os.cpu_count())
    if args.json:
        print(
            json.dumps(
                {"workload": workload, "results": results, "single_env_python_steps_per_s": single}
            )
        )
        return 0
    print(f"workload: {WORKLOAD['maze']}; {WORKLOAD['robot']}; 32 ms steps; Braitenberg")
    print(f"threads: {workload['threads']} of {os.cpu_count()} cpus")
    print(f"{'envs':>7}  {'env-steps/s':>13}  {'bytes/env':>10}")
    for r in results:
        print(f"{r['envs']:>7}  {r['env_steps_per_s']:>13,.0f}  {r['bytes_per_env']:>10,}")
    print(f"one env stepped from Python: {single:,.0f} steps/s")
    return 0


def register(commands: Any) -> None:
    """Adds ``mazesim bench`` to the command line."""
    parser = commands.add_parser(
        "bench",
        help="measure env-steps per second and memory per env of the canonical workload",
        description=(
            "Run the canonical workload (a distinct 5 x 5 maze per env, the e-puck with all 11 "
            "sensors read each step, 32 ms steps, Braitenberg wheel speeds) at each batch size, "
            "each in a fresh process, and print env-steps per second and resident bytes per env."
        ),
    )
    parser.add_argument(
        "--envs",
        type=_env_counts,
        default=[1, 64, 1024, 4096, 65536],
        metavar="N,N,...",
        help="batch sizes (default: 1,64,1024,4096,65536)",
    )
    parser.add_argument(
        "--steps",
        type=non_negative_int,
        default=0,
        metavar="K",
        help="steps per batch size (default: enough for about 1.5 s each)",
    )
    parser.add_argument(
        "--threads",
        type=non_negative_int,
        default=0,
        metavar="T",
        help="worker threads (default: 0 = all cores)",
    )
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.set_defaults(run=run)
