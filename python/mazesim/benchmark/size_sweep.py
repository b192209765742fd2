"""A benchmark run over several batch sizes: each measured in a fresh process, then reported as
a table or as one JSON document (what ``mazesim bench`` prints)."""

from __future__ import annotations

import os
import platform
import time
from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import Any

import mazesim

from .fresh import measure_in_fresh_process
from .steady import BenchSettings
from .workloads import braitenberg_one

__all__ = ["machine", "run_sizes", "single_env_rate", "table"]

#: Called with the control steps done and the steps in all, over the whole run.
RunProgress = Callable[[int, int], None]


def machine() -> dict[str, Any]:
    """The CPU, its cores, the cores this process may use and the load average."""
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as info:
            cpu = next(
                (line.split(":", 1)[1].strip() for line in info if line.startswith("model name")),
                cpu,
            )
    except OSError:
        pass
    usable = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    facts: dict[str, Any] = {"cpu": cpu, "cores": os.cpu_count(), "usable_cores": usable}
    if hasattr(os, "getloadavg"):
        facts["load_average_1min"] = round(os.getloadavg()[0], 2)
    return facts


def run_sizes(
    settings: BenchSettings,
    sizes: Sequence[int],
    progress: RunProgress | None = None,
    steps_per_call: Sequence[int] = (),
) -> list[dict[str, Any]]:
    """Measures ``settings`` at each batch size of ``sizes``, each in a fresh process.

    Args:
        settings: Everything but the batch size.
        sizes: Env counts.
        progress: Called with the env-steps done so far and the env-steps in all, across sizes
            (so that a display's ETA weighs a large batch more than a small one).
        steps_per_call: Steps per call to measure at each size, one run each (by default only
            ``settings.steps_per_call``).

    Returns:
        One report of :func:`~mazesim.benchmark.measure` per size (and steps per call), in the
        order of ``sizes``.
    """
    per_call = list(steps_per_call) or [settings.steps_per_call]
    runs = [replace(settings, envs=n, steps_per_call=k) for n in sizes for k in per_call]
    for run in runs:
        run.check()
    steps_each = settings.warmup_steps + settings.blocks * settings.block_steps
    total = sum(steps_each * run.envs for run in runs)
    reports: list[dict[str, Any]] = []
    done = 0
    for run in runs:

        def report_progress(steps: int, _all: int, base: int = done, envs: int = run.envs) -> None:
            if progress is not None:
                progress(base + steps * envs, total)

        reports.append(measure_in_fresh_process(run, report_progress))
        done += steps_each * run.envs
    return reports


def single_env_rate(steps: int = 20_000) -> float:
    """Steps per second of one ``Simulator`` stepped from a Python loop: all 11 sensors read and
    the Braitenberg rule computed in plain Python each step (numpy's per-call overhead would
    dominate a single robot)."""
    sim = mazesim.Simulator(mazesim.generate_maze(5, 5, seed=0, loops=0.1), seed=0)
    started = time.perf_counter()
    for _ in range(steps):
        ps = sim.distance_sensors().tolist()
        sim.ground_sensors()
        left, right = braitenberg_one(ps)
        sim.step(left, right)
    return steps / (time.perf_counter() - started)


def _bytes(memory: dict[str, Any]) -> str:
    engine = memory.get("engine_bytes_per_env")
    if engine is not None:
        return f"{engine:,.0f}"
    return f"{memory['resident_bytes_per_env']:,.0f} (RSS)"


def table(reports: Sequence[dict[str, Any]]) -> str:
    """The reports as a text table, one line per batch size, under a line of their settings."""
    if not reports:
        return ""
    s = reports[0]["settings"]
    lines = [
        f"workload {s['workload']}, {s['mazes']} 5 x 5 mazes, threads {s['threads'] or 'all'}; "
        f"warm-up {s['warmup_steps']:,} steps, then {s['blocks']} blocks of "
        f"{s['block_steps']} steps; episodes of {s['episode_steps']:,} steps",
        f"{'envs':>7}  {'per call':>8}  {'env-steps/s':>12}  {'blocks (min-max)':>23}  "
        f"{'per CPU-s':>11}  {'contact':>7}  {'bytes/env':>14}",
    ]
    for r in reports:
        low, high = r["env_steps_per_s_range"]
        lines.append(
            f"{r['settings']['envs']:>7,}  {r['settings']['steps_per_call']:>8}  "
            f"{r['env_steps_per_s']:>12,.0f}  "
            f"{f'{low:,.0f}-{high:,.0f}':>23}  {r['env_steps_per_cpu_s']:>11,.0f}  "
            f"{r['contact_share']:>7.1%}  {_bytes(r['memory']):>14}"
        )
    return "\n".join(lines)
