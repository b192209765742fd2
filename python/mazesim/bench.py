"""The canonical workload of ``mazesim bench``: env-steps per second and memory per env.

The workload (docs/performance.md): per env a distinct generated 5 x 5 maze of 0.25 m cells and
0.01 m walls, the e-puck with ps0-7 and gs0-2 all read every step, a 32 ms control step of one
physics step, and wheel speeds from a Braitenberg rule computed in numpy from the observations.
Each batch size runs in a fresh process, so its resident memory is measured on its own.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from typing import Any

import numpy as np

import mazesim
from mazesim.errors import InvalidArgumentError

__all__ = ["braitenberg", "braitenberg_one", "measure", "single_env_rate"]

#: Seconds a measurement aims to last when --steps is not given.
TARGET_SECONDS = 1.5

WORKLOAD: dict[str, Any] = {
    "maze": "5 x 5 cells of 0.25 m, walls 0.01 m, a distinct generated maze per env (loops 0.1)",
    "robot": "e-puck: ps0-7 and gs0-2 read every step",
    "control_step_ms": 32,
    "physics_steps_per_control_step": 1,
    "policy": "Braitenberg rule in numpy on ps0-7",
}


def braitenberg(ps: np.ndarray, out: np.ndarray) -> np.ndarray:
    """Braitenberg wheel speeds (rad/s) from e-puck proximity readings, written into ``out``.

    Each side's activation turns the robot away from that side; a frontal obstacle turns it
    left so it never stalls square to a wall.

    Args:
        ps: (N, 8) raw proximity readings.
        out: (N, 2) float32 buffer for left and right wheel speeds.

    Returns:
        ``out``.
    """
    a = np.clip((ps - np.float32(67.19)) / np.float32(300.0), 0.0, 1.0)
    right_side = a[:, 0] + 0.7 * a[:, 1] + 0.4 * a[:, 2]
    left_side = a[:, 7] + 0.7 * a[:, 6] + 0.4 * a[:, 5]
    front = 0.5 * (a[:, 0] + a[:, 7])
    base = 5.0 * (1.0 - front)
    turn = 4.0 * (right_side - left_side) + 6.0 * front
    np.subtract(base, turn, out=out[:, 0])
    np.add(base, turn, out=out[:, 1])
    np.clip(out, -6.28, 6.28, out=out)
    return out


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


def braitenberg_one(ps: list[float]) -> tuple[float, float]:
    """The Braitenberg rule of :func:`braitenberg` for one robot, in plain Python floats."""
    a = [min(max((v - 67.19) / 300.0, 0.0), 1.0) for v in ps]
    right_side = a[0] + 0.7 * a[1] + 0.4 * a[2]
    left_side = a[7] + 0.7 * a[6] + 0.4 * a[5]
    front = 0.5 * (a[0] + a[7])
    base = 5.0 * (1.0 - front)
    turn = 4.0 * (right_side - left_side) + 6.0 * front
    return base - turn, base + turn


def single_env_rate(steps: int = 100_000) -> float:
    """Steps per second of one Simulator stepped from a Python loop: all 11 sensors read and
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
