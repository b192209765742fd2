"""SB3 PPO training speed: DummyVecEnv over 8 single envs against the batch engine's VecEnv.

Not a test: run it by hand (needs ``make sb3-deps``)::

    .venv/bin/python benches/bench_sb3.py [--task mazesim/UnseenMazeGuided-v0] [--envs 512]

Both train the same PPO (MLP policy, the same hyperparameters, chosen for throughput on a CPU:
rollouts of ``--n-steps`` steps per environment, minibatches of ``--batch`` samples or the whole
rollout if it is smaller, ``--epochs`` passes, one torch thread) on the same task, each for a fixed
number of env-steps; the rate is env-steps per second of ``model.learn``, training included, as
SB3 itself reports it. Only the vectorised env differs: ``DummyVecEnv`` of 8 ``gymnasium.make``
envs under ``Monitor``, or ``make_vec_env`` with ``--envs`` environments.
"""

from __future__ import annotations

import argparse
import statistics
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


def train_rate(envs: VecEnv, steps: int, n_steps: int, batch: int, epochs: int) -> float:
    """Env-steps per second of PPO learning ``steps`` env-steps on ``envs``."""
    batch = min(batch, n_steps * envs.num_envs)
    model = PPO(
        "MlpPolicy",
        envs,
        n_steps=n_steps,
        batch_size=batch,
        n_epochs=epochs,
        seed=0,
        device="cpu",
    )
    start = time.perf_counter()
    model.learn(total_timesteps=steps)
    rate = model.num_timesteps / (time.perf_counter() - start)
    envs.close()
    return rate


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--task", default="mazesim/UnseenMazeGuided-v0")
    parser.add_argument("--envs", type=int, default=512, help="envs of the batch engine's VecEnv")
    parser.add_argument("--n-steps", type=int, default=128, help="rollout steps per env")
    parser.add_argument("--batch", type=int, default=8192, help="PPO minibatch size")
    parser.add_argument("--epochs", type=int, default=1, help="PPO epochs per rollout")
    parser.add_argument("--dummy-steps", type=int, default=50_000)
    parser.add_argument("--fast-steps", type=int, default=1_000_000)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args(argv)
    torch.set_num_threads(1)
    settings = (args.n_steps, args.batch, args.epochs)

    def single() -> Any:
        return Monitor(gymnasium.make(args.task))

    dummies, fasts = [], []
    for _ in range(args.rounds):  # alternating, so that both meet the same machine load
        dummies.append(
            train_rate(DummyVecEnv([single for _ in range(8)]), args.dummy_steps, *settings)
        )
        fasts.append(
            train_rate(make_vec_env(args.task, args.envs, seed=0), args.fast_steps, *settings)
        )
    dummy, fast = statistics.median(dummies), statistics.median(fasts)
    print(
        f"PPO: n_steps {args.n_steps} per env, minibatches of {args.batch} (or the rollout), "
        f"{args.epochs} epoch(s), one torch thread; median of {args.rounds} alternating rounds"
    )
    print(f"SB3 PPO on {args.task}:")
    print(f"  DummyVecEnv x 8 single envs       {dummy:>10,.0f} env-steps/s")
    print(f"  make_vec_env, {args.envs} envs (batch)   {fast:>10,.0f} env-steps/s")
    print(f"  ratio                             {fast / dummy:>10.1f} x")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
