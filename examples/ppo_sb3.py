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
``--option goal_reward=20`` changes one of the task's options (any keyword of ``gymnasium.make``
for the task, such as the reward weights; repeat it for several) in training and in the held-out
episodes alike, and ``--video run.mp4`` (or ``.gif``) records the trained policy's first held-out
episode (needs ``mazesim[video]``).

Tiers 1 to 3 (``UnseenMazeExplore-v0``) scale PPO's rewards by a running estimate of the returns'
spread (SB3's ``VecNormalize`` with ``norm_obs=False``): the observations are already of order 1;
``UnseenMaze-v2`` takes tier 4's settings (no reward scaling), with 3M env-steps.
``UnseenMazeExplore-v0`` is evaluated with sampled actions: its memoryless policy, driven
deterministically, can loop for ever in a maze it cannot see; sampling gets it out, as it did in
training.
"""

from __future__ import annotations

import argparse
import ast
import csv
import os
import time
from pathlib import Path
from typing import Any

import matplotlib

# First, as it says what to install when Stable-Baselines3 or torch is missing.
from mazesim.integrations.sb3 import make_vec_env

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import torch  # noqa: E402
from stable_baselines3 import PPO  # noqa: E402
from stable_baselines3.common.logger import configure  # noqa: E402
from stable_baselines3.common.vec_env import VecEnv, VecNormalize  # noqa: E402

#: Settings of each tier: environments, env-steps, PPO's rollout length and minibatch size,
#: whether rewards are normalised, whether the held-out episodes use the policy's mean action.
SETTINGS: dict[str, dict[str, Any]] = {
    "mazesim/EPuckMaze-v0": {"envs": 64, "steps": 2_000_000, "n_steps": 128, "batch": 2048},
    "mazesim/MazeFixed-v1": {"envs": 64, "steps": 500_000, "n_steps": 128, "batch": 2048},
    "mazesim/MazeRandomGoal-v1": {"envs": 128, "steps": 2_000_000, "n_steps": 128, "batch": 4096},
    "mazesim/UnseenMazeExplore-v0": {
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


def evaluate(
    model: PPO, task: str, episodes: int, seed: int, deterministic: bool, options: dict[str, Any]
) -> float:
    """Success rate of ``model`` over one episode in each of ``episodes`` held-out envs."""
    envs = make_vec_env(task, episodes, seed=HELD_OUT_SEED + seed, monitor=False, **options)
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


def record_video(
    model: PPO, task: str, seed: int, deterministic: bool, options: dict[str, Any], path: Path
) -> int:
    """Writes the first held-out episode (seeded ``HELD_OUT_SEED + seed``, as in
    :func:`evaluate`) driven by ``model`` to ``path`` (.mp4 or .gif); returns its frames."""
    import gymnasium
    import imageio.v2 as imageio

    env = gymnasium.make(task, render_mode="rgb_array", **options)
    fps = float(env.metadata["render_fps"])
    # Frames are written as they are drawn: a 3000-step episode would not fit in memory.
    writer = imageio.get_writer(path, fps=min(fps, 50.0) if path.suffix == ".gif" else fps)
    observation, _ = env.reset(seed=HELD_OUT_SEED + seed)
    writer.append_data(env.render())
    frames, ended = 1, False
    while not ended:
        action, _ = model.predict(observation, deterministic=deterministic)
        observation, _, terminated, truncated, _ = env.step(action)
        writer.append_data(env.render())
        frames, ended = frames + 1, terminated or truncated
    writer.close()
    env.close()
    return frames


def parse_option(text: str) -> tuple[str, Any]:
    """``NAME=VALUE`` of ``--option``: VALUE is a Python literal (``20``, ``0.5``, ``(7, 7)``,
    ``True``) or else taken as a string (``world=seed-maze``)."""
    name, equals, value = text.partition("=")
    if not equals or not name.isidentifier():
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE (goal_reward=20), found {text!r}")
    try:
        return name, ast.literal_eval(value)
    except (ValueError, SyntaxError):
        return name, value


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
    parser.add_argument(
        "--option",
        type=parse_option,
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="a task option for training and the held-out episodes, e.g. goal_reward=20",
    )
    parser.add_argument(
        "--video", type=Path, help="record the first held-out episode (.mp4 or .gif)"
    )
    args = parser.parse_args()
    options = dict(args.option)
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
    envs: VecEnv = make_vec_env(args.task, envs_count, seed=args.seed, **options)
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
    deterministic = settings["deterministic"]
    success = evaluate(model, args.task, args.eval_episodes, args.seed, deterministic, options)
    if args.video is not None:
        frames = record_video(model, args.task, args.seed, deterministic, options, args.video)
        print(f"video of the first held-out episode ({frames} frames): {args.video}")
    print(
        f"{args.task} seed {args.seed}: {model.num_timesteps} env-steps in {seconds:.0f} s "
        f"({model.num_timesteps / seconds:,.0f} env-steps/s); success on {args.eval_episodes} "
        f"held-out episodes: {100 * success:.0f} %"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
