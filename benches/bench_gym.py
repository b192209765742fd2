"""The gymnasium front against the raw batch engine, and the frame rate of rendering.

Not a test: run it by hand (gymnasium must be installed)::

    .venv/bin/python benches/bench_gym.py [--envs 1024] [--steps 1000] [--json]

Throughput: ``--envs`` environments, each in its own 5 x 5 maze of 0.25 m cells, the e-puck with
all 11 sensors read with noise every 32 ms control step, and uniformly random actions (a pool
drawn beforehand, so the policy costs nothing). One env-step is one control step of one robot.

- raw: :class:`mazesim.BatchSimulator` stepping the wheel speeds into preallocated buffers;
- vector env: ``gymnasium.make_vec("mazesim/EPuckMaze-v0", vectorization_mode=
  "vector_entry_point", world="random")``, stepped through the gymnasium API: action checks,
  observations, rewards (shortest-path progress), time limits, autoreset and info arrays included;
- sync (reference): ``SyncVectorEnv`` over the same number of single envs, for a few steps.

Raw and vector env step in turns, one step each, so that other load on the machine falls on both
alike; the rate is from the median step time (the sustained rate, from the mean, is printed too).

One env: ``gymnasium.make("mazesim/EPuckMaze-v0")`` against ``gymnasium.make("CartPole-v1")``,
both stepped through gymnasium's wrappers with random actions (episodes restart when they end),
in alternating rounds of ``ROUND`` steps so that other load on the machine falls on both alike,
with the raw :class:`mazesim.Simulator` beside them; the ratio is the figure to read.

Rendering: frames per second of ``env.render()`` of a single env made with
``render_mode="rgb_array"`` (400 x 400, through gymnasium's wrappers) and of the numpy rasteriser
alone, in seed-maze.
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
from gymnasium.utils import seeding

import mazesim
from mazesim.envs import ENV_ID
from mazesim.envs.options import draw_seed

POOL = 16
#: Steps of one env between switches from one contender to the next.
ROUND = 2000


def _rate(run: Callable[[], None], count: int) -> float:
    """Calls ``run`` and returns ``count`` per second of wall time."""
    start = time.perf_counter()
    run()
    return count / (time.perf_counter() - start)


def throughput(num_envs: int, steps: int, threads: int) -> dict[str, float]:
    """Env-steps per second of the raw engine and of the vector env (median and mean step)."""
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

    # The raw engine runs the very episodes of the vector env: env i is seeded with 0 + i and
    # draws its maze, then its simulator seed, from that RNG. So both step the same robots into
    # the same walls (contacts cost more than free driving) and the comparison is like for like.
    worlds, seeds = [], []
    for i in range(num_envs):
        rng = seeding.np_random(i)[0]
        worlds.append(mazesim.generate_maze(5, 5, seed=draw_seed(rng)))
        seeds.append(draw_seed(rng))
    batch = mazesim.BatchSimulator(worlds, robot="e-puck", seeds=seeds, threads=threads)
    max_speed = np.float32(mazesim.RobotProfile.builtin("e-puck").max_wheel_speed)
    speeds = [a * max_speed for a in actions]
    observations = np.zeros((num_envs, batch.observation_width), dtype=np.float32)
    poses = np.zeros((num_envs, 3), dtype=np.float32)
    colliding = np.zeros(num_envs, dtype=bool)
    crossings = np.zeros(num_envs, dtype=np.int32)
    batch.reset(observations, poses, colliding, crossings)

    def raw(k: int) -> None:
        batch.step(speeds[k % POOL], observations, poses, colliding, crossings)

    def vector(k: int) -> None:
        envs.step(actions[k % POOL])

    space = envs.single_observation_space
    for k in range(20):  # warm up, and check that both run the same episodes
        raw(k)
        vector_observations = envs.step(actions[k % POOL])[0]
    if not np.array_equal(vector_observations, np.clip(observations, space.low, space.high)):
        raise RuntimeError("the raw engine and the vector env ran different episodes")
    # Step by step in turns, so that other load on the machine falls on both alike; the median
    # step time of each gives its rate, the mean the sustained rate.
    times: dict[str, list[float]] = {"raw": [], "vector": []}
    for k in range(steps):
        for name, run in (("raw", raw), ("vector", vector)):
            start = time.perf_counter()
            run(k)
            times[name].append(time.perf_counter() - start)
    envs.close()
    rates = {name: num_envs / float(np.median(ts)) for name, ts in times.items()}
    rates.update({f"{name}_mean": num_envs / float(np.mean(ts)) for name, ts in times.items()})
    return rates


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


def single_env_rates(steps: int) -> dict[str, float]:
    """Steps per second of one mazesim env and one CartPole env (both through gymnasium.make),
    and of the raw Simulator, from the median of alternating rounds."""
    contenders: dict[str, Callable[[int], None]] = {}
    for name, env_id in (("mazesim_env", ENV_ID), ("cartpole_env", "CartPole-v1")):
        env: Any = gymnasium.make(env_id)
        env.reset(seed=0)
        env.action_space.seed(0)
        pool = [env.action_space.sample() for _ in range(POOL)]

        def run(count: int, env: Any = env, pool: list[Any] = pool) -> None:
            for k in range(count):
                _, _, terminated, truncated, _ = env.step(pool[k % POOL])
                if terminated or truncated:
                    env.reset()

        contenders[name] = run
    simulator = mazesim.Simulator(mazesim.load_world("seed-maze"), seed=0)
    wheels = [(float(a), float(b)) for a, b in np.random.default_rng(0).uniform(-6, 6, (POOL, 2))]

    def raw(count: int) -> None:
        for k in range(count):
            simulator.step(*wheels[k % POOL])
            simulator.distance_sensors()
            simulator.ground_sensors()

    contenders["raw_simulator"] = raw
    times: dict[str, list[float]] = {name: [] for name in contenders}
    for _ in range(max(1, steps // ROUND)):
        for name, run in contenders.items():
            start = time.perf_counter()
            run(ROUND)
            times[name].append(time.perf_counter() - start)
    return {f"{name}_steps_per_s": ROUND / float(np.median(ts)) for name, ts in times.items()}


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
    parser.add_argument("--steps", type=int, default=1000, help="control steps of each")
    parser.add_argument("--threads", type=int, default=0, help="engine threads (0: all cores)")
    parser.add_argument("--sync-steps", type=int, default=10, help="SyncVectorEnv steps (0: skip)")
    parser.add_argument("--frames", type=int, default=2000, help="frames to render")
    parser.add_argument(
        "--single-steps", type=int, default=100_000, help="steps of one env (0: skip)"
    )
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args(argv)

    result: dict[str, Any] = {
        "machine": f"{platform.machine()}, {os.cpu_count()} cores",
        "envs": args.envs,
    }
    rates = throughput(args.envs, args.steps, args.threads)
    result["raw_env_steps_per_s"] = rates["raw"]
    result["vector_env_steps_per_s"] = rates["vector"]
    result["vector_over_raw"] = rates["vector"] / rates["raw"]
    result["raw_mean_env_steps_per_s"] = rates["raw_mean"]
    result["vector_mean_env_steps_per_s"] = rates["vector_mean"]
    if args.sync_steps > 0:
        result["sync_env_steps_per_s"] = sync_throughput(args.envs, args.sync_steps)
    if args.single_steps > 0:
        result.update(single_env_rates(args.single_steps))
        result["mazesim_over_cartpole"] = (
            result["mazesim_env_steps_per_s"] / result["cartpole_env_steps_per_s"]
        )
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
    mean_ratio = result["vector_mean_env_steps_per_s"] / result["raw_mean_env_steps_per_s"]
    print(
        f"  (sustained: raw {result['raw_mean_env_steps_per_s']:,.0f}, vector env "
        f"{result['vector_mean_env_steps_per_s']:,.0f}, {100 * mean_ratio:.0f} %)"
    )
    if "sync_env_steps_per_s" in result:
        print(f"  SyncVectorEnv           {result['sync_env_steps_per_s']:>12,.0f} env-steps/s")
    if "mazesim_env_steps_per_s" in result:
        print(
            f"  one env, gymnasium.make {result['mazesim_env_steps_per_s']:>12,.0f} steps/s"
            f"  ({result['mazesim_over_cartpole']:.2f} x CartPole-v1's "
            f"{result['cartpole_env_steps_per_s']:,.0f}; raw Simulator "
            f"{result['raw_simulator_steps_per_s']:,.0f})"
        )
    print(f"  env.render() 400x400    {result['render_fps']:>12,.0f} frames/s")
    print(f"  rasteriser alone        {result['rasteriser_fps']:>12,.0f} frames/s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
