"""PPO (Stable-Baselines3) on a mazesim task, through the batch engine, then held-out episodes.

Needs the extra ``mazesim[sb3]`` (``make sb3-deps`` in a checkout). One script for every tier of
the task suite; each tier has its settings below (``--task`` picks one)::

    python examples/ppo_sb3.py --task mazesim/MazeFixed-v1 --seed 0 --out runs/fixed-0

It trains PPO (an MLP policy) for ``--total-timesteps`` env-steps on ``--envs`` environments of
the task (seeded ``seed``, ``seed + 1``, ...), writes the learning curve (``progress.csv``: SB3's
logger, with the success rate and mean length of the last 100 episodes; ``curve.png``, their
picture) and the model, then runs the trained policy for one episode on each of
``--eval-episodes`` held-out episodes:
environments seeded from ``10**6 + seed``, so their mazes, starts and goals were never trained on.
It prints the success rate. ``MAZESIM_EXAMPLES_FAST=1`` runs a tiny version (a few seconds).
``--plot runs/fixed-0 runs/fixed-1 --picture fixed.png`` draws finished runs' curves together.

Tiers 1 to 3 (``UnseenMaze-v1``) scale PPO's rewards by a running estimate of the returns' spread
(SB3's ``VecNormalize`` with ``norm_obs=False``): the observations are already of order 1;
``UnseenMaze-v2`` takes tier 4's settings (no reward scaling), with 3M env-steps. ``UnseenMaze-v1``
is evaluated with sampled actions: its memoryless policy, driven deterministically, can loop for
ever in a maze it cannot see; sampling gets it out, as it did in training.
"""

from __future__ import annotations

import argparse
import csv
import os
import time
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import torch  # noqa: E402
from stable_baselines3 import PPO  # noqa: E402
from stable_baselines3.common.logger import configure  # noqa: E402
from stable_baselines3.common.vec_env import VecEnv, VecNormalize  # noqa: E402

from mazesim.integrations.sb3 import make_vec_env  # noqa: E402

#: Settings of each tier: environments, env-steps, PPO's rollout length and minibatch size,
#: whether rewards are normalised, whether the held-out episodes use the policy's mean action.
SETTINGS: dict[str, dict[str, Any]] = {
    "mazesim/EPuckMaze-v0": {"envs": 64, "steps": 2_000_000, "n_steps": 128, "batch": 2048},
    "mazesim/MazeFixed-v1": {"envs": 64, "steps": 500_000, "n_steps": 128, "batch": 2048},
    "mazesim/MazeRandomGoal-v1": {"envs": 128, "steps": 2_000_000, "n_steps": 128, "batch": 4096},
    "mazesim/UnseenMaze-v1": {
        "envs": 128,
        "steps": 3_000_000,
        "n_steps": 128,
        "batch": 4096,
        "deterministic": False,
    },
    "mazesim/UnseenMaze-v2": {
        "envs": 128,
        "steps": 3_000_000,
        "n_steps": 128,
        "batch": 4096,
        "normalize_reward": False,
    },
    "mazesim/UnseenMazeGuided-v0": {
        "envs": 128,
        "steps": 1_000_000,
        "n_steps": 128,
        "batch": 4096,
        "normalize_reward": False,
    },
}
#: The held-out environments are seeded from here on (training uses seed, seed + 1, ...).
HELD_OUT_SEED = 10**6


def evaluate(model: PPO, task: str, episodes: int, seed: int, deterministic: bool) -> float:
    """Success rate of ``model`` over one episode in each of ``episodes`` held-out envs."""
    envs = make_vec_env(task, episodes, seed=HELD_OUT_SEED + seed, monitor=False)
    observations = envs.reset()
    finished = np.zeros(episodes, dtype=bool)
    success = np.zeros(episodes, dtype=bool)
    while not finished.all():
        actions, _ = model.predict(observations, deterministic=deterministic)
        observations, _, dones, infos = envs.step(actions)
        for i in np.flatnonzero(dones & ~finished):
            success[i] = infos[i]["is_success"]
        finished |= dones
    envs.close()
    return float(success.mean())


def plot_curves(runs: list[Path], picture: Path, title: str) -> None:
    """Draws, one line per run directory (its ``progress.csv``), the success rate and the mean
    length of the last 100 training episodes against env-steps, side by side, into a small PNG."""
    figure, (rate, length) = plt.subplots(1, 2, figsize=(7, 2.6), dpi=80)
    for run in runs:
        steps, success, lengths = [], [], []
        with (run / "progress.csv").open() as rows:
            for row in csv.DictReader(rows):
                if row.get("rollout/success_rate"):
                    steps.append(float(row["time/total_timesteps"]))
                    success.append(100 * float(row["rollout/success_rate"]))
                    lengths.append(float(row["rollout/ep_len_mean"]))
        rate.plot(steps, success, label=run.name)
        length.plot(steps, lengths, label=run.name)
    rate.set(xlabel="env-steps", ylabel="success %", ylim=(-2, 102))
    length.set(xlabel="env-steps", ylabel="episode length (steps)", ylim=(0, None))
    figure.suptitle(title, fontsize=9)
    if len(runs) > 1:
        rate.legend(fontsize=7, loc="lower right")
    figure.tight_layout()
    figure.savefig(picture)
    plt.close(figure)


def main() -> int:
    fast = os.environ.get("MAZESIM_EXAMPLES_FAST") == "1"
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--task", default="mazesim/UnseenMazeGuided-v0", choices=sorted(SETTINGS))
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--total-timesteps", type=int, default=None, help="default: the tier's")
    parser.add_argument("--envs", type=int, default=None, help="default: the tier's")
    parser.add_argument("--eval-episodes", type=int, default=100)
    parser.add_argument("--out", type=Path, default=Path("ppo-run"))
    parser.add_argument(
        "--plot",
        type=Path,
        nargs="+",
        metavar="RUN",
        help="no training: draw these runs' learning curves into --picture",
    )
    parser.add_argument("--picture", type=Path, default=Path("curves.png"))
    args = parser.parse_args()
    if args.plot:
        plot_curves(args.plot, args.picture, args.task)
        return 0
    settings = {"normalize_reward": True, "deterministic": True, **SETTINGS[args.task]}
    if fast:
        settings.update(envs=8, steps=2048, n_steps=64, batch=256)
        args.eval_episodes = min(args.eval_episodes, 4)
    envs_count = args.envs or settings["envs"]
    total = args.total_timesteps or settings["steps"]

    # One torch thread: the batch engine has the other core, and threads fighting over two cores
    # (or a machine shared with other jobs) slow PPO down many times over.
    torch.set_num_threads(1)
    envs: VecEnv = make_vec_env(args.task, envs_count, seed=args.seed)
    if settings["normalize_reward"]:
        envs = VecNormalize(envs, norm_obs=False, norm_reward=True, gamma=0.99)
    model = PPO(
        "MlpPolicy",
        envs,
        n_steps=settings["n_steps"],
        batch_size=settings["batch"],
        n_epochs=4,
        learning_rate=3e-4,
        gamma=0.99,
        ent_coef=0.0,
        seed=args.seed,
        device="cpu",
        verbose=0,
    )
    args.out.mkdir(parents=True, exist_ok=True)
    model.set_logger(configure(str(args.out), ["csv"]))
    start = time.perf_counter()
    model.learn(total_timesteps=total)
    seconds = time.perf_counter() - start
    model.save(args.out / "model.zip")
    envs.close()
    plot_curves([args.out], args.out / "curve.png", f"{args.task} seed {args.seed}")
    success = evaluate(model, args.task, args.eval_episodes, args.seed, settings["deterministic"])
    print(
        f"{args.task} seed {args.seed}: {model.num_timesteps} env-steps in {seconds:.0f} s "
        f"({model.num_timesteps / seconds:,.0f} env-steps/s); success on {args.eval_episodes} "
        f"held-out episodes: {100 * success:.0f} %"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
