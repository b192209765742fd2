"""SB3 PPO training speed: DummyVecEnv over 8 single envs against the batch engine's VecEnv.

Not a test: run it by hand (needs ``make sb3-deps``)::

    .venv/bin/python benches/bench_sb3.py [--task mazesim/UnseenMazeGuided-v0] [--envs 128]

Both train the same PPO (MLP policy, rollouts of 128 steps per env, 4 epochs, one torch thread,
minibatches of ``--batch`` samples or the whole rollout if it is smaller: examples/ppo_sb3.py's
settings) on the same task, each for a fixed number of env-steps; the rate is env-steps per second
of wall time, training included, as SB3 itself reports it.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Sequence
from typing import Any

import gymnasium
import torch
from stable_baselines3 import PPO
from stable_baselines3.common.monitor import Monitor
from stable_baselines3.common.vec_env import DummyVecEnv, VecEnv

import mazesim  # noqa: F401  (registers the tasks)
from mazesim.integrations.sb3 import make_vec_env

#: Rollout steps per environment.
N_STEPS = 128


def train_rate(envs: VecEnv, steps: int, batch: int) -> float:
    """Env-steps per second of PPO learning ``steps`` env-steps on ``envs``."""
    batch = min(batch, N_STEPS * envs.num_envs)
    model = PPO(
        "MlpPolicy", envs, n_steps=N_STEPS, batch_size=batch, n_epochs=4, seed=0, device="cpu"
    )
    start = time.perf_counter()
    model.learn(total_timesteps=steps)
    rate = model.num_timesteps / (time.perf_counter() - start)
    envs.close()
    return rate


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--task", default="mazesim/UnseenMazeGuided-v0")
    parser.add_argument("--envs", type=int, default=128, help="envs of the batch engine's VecEnv")
    parser.add_argument("--batch", type=int, default=4096, help="PPO minibatch size")
    parser.add_argument("--dummy-steps", type=int, default=40_000)
    parser.add_argument("--fast-steps", type=int, default=400_000)
    args = parser.parse_args(argv)
    torch.set_num_threads(1)

    def single() -> Any:
        return Monitor(gymnasium.make(args.task))

    dummy = train_rate(DummyVecEnv([single for _ in range(8)]), args.dummy_steps, args.batch)
    fast = train_rate(make_vec_env(args.task, args.envs, seed=0), args.fast_steps, args.batch)
    print(f"SB3 PPO on {args.task}:")
    print(f"  DummyVecEnv x 8 single envs       {dummy:>10,.0f} env-steps/s")
    print(f"  make_vec_env, {args.envs} envs (batch)   {fast:>10,.0f} env-steps/s")
    print(f"  ratio                             {fast / dummy:>10.1f} x")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
