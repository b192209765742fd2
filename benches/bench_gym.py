"""The gymnasium front against the raw batch engine, and the frame rate of rendering.

Not a test: run it by hand (gymnasium must be installed)::

    .venv/bin/python benches/bench_gym.py [--envs 1024] [--steps 200] [--json]

Throughput: ``--envs`` environments, each in its own 5 x 5 maze of 0.25 m cells, the e-puck with
all 11 sensors read with noise every 32 ms control step, and uniformly random actions (a pool
drawn beforehand, so the policy costs nothing). One env-step is one control step of one robot.

- raw: :class:`mazesim.BatchSimulator` stepping the wheel speeds into preallocated buffers;
- vector env: ``gymnasium.make_vec("mazesim/EPuckMaze-v0", vectorization_mode=
  "vector_entry_point", world="random")``, stepped through the gymnasium API: action checks,
  observations, rewards (shortest-path progress), time limits, autoreset and info arrays included;
- sync (reference): ``SyncVectorEnv`` over the same number of single envs, for a few steps.

Raw and vector env are timed in interleaved rounds, so other load on the machine falls on both
alike; the best round of each is reported. Rendering: frames per second of ``env.render()`` of a
single env made with ``render_mode="rgb_array"`` (400 x 400, through gymnasium's wrappers) and of
the numpy rasteriser alone, in seed-maze.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import time
from collections.abc import Callable, Sequence
from typing import Any

import gymnasium
import numpy as np

import mazesim
from mazesim.envs import ENV_ID

POOL = 16


def _rate(run: Callable[[], None], count: int) -> float:
    """Calls ``run`` and returns ``count`` per second of wall time."""
    start = time.perf_counter()
    run()
    return count / (time.perf_counter() - start)


def throughput(num_envs: int, steps: int, rounds: int, threads: int) -> dict[str, float]:
    """Env-steps per second of the raw engine and of the vector env (best of ``rounds``)."""
    envs: Any = gymnasium.make_vec(
        ENV_ID,
        num_envs,
        vectorization_mode="vector_entry_point",
        world="random",
        threads=threads,
    )
    envs.reset(seed=0)
    envs.action_space.seed(0)
    actions = [envs.action_space.sample() for _ in range(POOL)]

    worlds = [mazesim.generate_maze(5, 5, seed=i) for i in range(num_envs)]
    batch = mazesim.BatchSimulator(worlds, robot="e-puck", seeds=0, threads=threads)
    max_speed = np.float32(mazesim.RobotProfile.builtin("e-puck").max_wheel_speed)
    speeds = [a * max_speed for a in actions]
    observations = np.zeros((num_envs, batch.observation_width), dtype=np.float32)
    poses = np.zeros((num_envs, 3), dtype=np.float32)
    colliding = np.zeros(num_envs, dtype=bool)
    crossings = np.zeros(num_envs, dtype=np.int32)
    batch.reset(observations, poses, colliding, crossings)

    def raw() -> None:
        for k in range(steps):
            batch.step(speeds[k % POOL], observations, poses, colliding, crossings)

    def vector() -> None:
        for k in range(steps):
            envs.step(actions[k % POOL])

    raw(), vector()  # warm up
    best = {"raw": 0.0, "vector": 0.0}
    for _ in range(rounds):
        best["raw"] = max(best["raw"], _rate(raw, num_envs * steps))
        best["vector"] = max(best["vector"], _rate(vector, num_envs * steps))
    envs.close()
    return best


def sync_throughput(num_envs: int, steps: int) -> float:
    """Env-steps per second of SyncVectorEnv over single envs."""
    envs: Any = gymnasium.make_vec(ENV_ID, num_envs, vectorization_mode="sync", world="random")
    envs.reset(seed=0)
    envs.action_space.seed(0)
    actions = [envs.action_space.sample() for _ in range(POOL)]
    envs.step(actions[0])

    def run() -> None:
        for k in range(steps):
            envs.step(actions[k % POOL])

    rate = _rate(run, num_envs * steps)
    envs.close()
    return rate


def render_rates(frames: int) -> dict[str, float]:
    """Frames per second of env.render() (400 x 400) and of the rasteriser alone."""
    env: Any = gymnasium.make(ENV_ID, render_mode="rgb_array")
    env.reset(seed=0)
    env.action_space.seed(0)
    for _ in range(50):
        env.step(env.action_space.sample())
    env.render()

    def through_gym() -> None:
        for _ in range(frames):
            env.render()

    renderer = env.unwrapped._renderer
    pose = env.unwrapped._simulator.pose

    def rasteriser() -> None:
        for _ in range(frames):
            renderer.frame(pose)

    rates = {"render_fps": _rate(through_gym, frames), "rasteriser_fps": _rate(rasteriser, frames)}
    env.close()
    return rates


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--envs", type=int, default=1024, help="number of environments")
    parser.add_argument("--steps", type=int, default=200, help="control steps per round")
    parser.add_argument("--rounds", type=int, default=5, help="interleaved timing rounds")
    parser.add_argument("--threads", type=int, default=0, help="engine threads (0: all cores)")
    parser.add_argument("--sync-steps", type=int, default=10, help="SyncVectorEnv steps (0: skip)")
    parser.add_argument("--frames", type=int, default=2000, help="frames to render")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args(argv)

    result: dict[str, Any] = {
        "machine": f"{platform.machine()}, {os.cpu_count()} cores",
        "envs": args.envs,
    }
    rates = throughput(args.envs, args.steps, args.rounds, args.threads)
    result["raw_env_steps_per_s"] = rates["raw"]
    result["vector_env_steps_per_s"] = rates["vector"]
    result["vector_over_raw"] = rates["vector"] / rates["raw"]
    if args.sync_steps > 0:
        result["sync_env_steps_per_s"] = sync_throughput(args.envs, args.sync_steps)
    result.update(render_rates(args.frames))

    if args.json:
        print(json.dumps(result, indent=2))
        return 0
    print(f"mazesim gymnasium bench: {result['machine']}, {args.envs} envs")
    print(f"  raw BatchSimulator      {result['raw_env_steps_per_s']:>12,.0f} env-steps/s")
    print(
        f"  native vector env       {result['vector_env_steps_per_s']:>12,.0f} env-steps/s"
        f"  ({100 * result['vector_over_raw']:.0f} % of raw)"
    )
    if "sync_env_steps_per_s" in result:
        print(f"  SyncVectorEnv           {result['sync_env_steps_per_s']:>12,.0f} env-steps/s")
    print(f"  env.render() 400x400    {result['render_fps']:>12,.0f} frames/s")
    print(f"  rasteriser alone        {result['rasteriser_fps']:>12,.0f} frames/s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
