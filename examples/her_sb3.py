"""SAC with hindsight relabelling (Stable-Baselines3's ``HerReplayBuffer``) on a goal-conditioned
mazesim task, then held-out goals.

Needs the extra ``mazesim[sb3]`` (``make sb3-deps`` in a checkout)::

    python examples/her_sb3.py --task mazesim/EPuckGoal-v0 --seed 0 --steps 10000 --out runs/her-0

It trains SAC (``MultiInputPolicy``) with a ``HerReplayBuffer`` (4 relabelled goals per real one,
the ``future`` strategy; one gradient step every 4 env-steps) for ``--steps`` env-steps on one env
of the task seeded ``seed``, with a time limit of ``--episode-steps`` control steps (shorter than
the task's own: HER learns from finished episodes, and short ones give it more of them). Every
``--eval-every`` env-steps it runs the deterministic policy on ``--eval-episodes`` held-out
episodes (an env seeded ``10**6 + seed``, so their starts and goals, and with unseen mazes their
mazes, were never trained on). It writes ``curve.png`` (held-out success against env-steps) and
``results.json`` (the task, seed, settings, the curve, the final held-out success rate, mean
episode length of the successes, wall time and the machine's load) into ``--out``, and prints
the final figures. ``MAZESIM_EXAMPLES_FAST=1`` runs a tiny version (300 env-steps).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import time
from pathlib import Path
from typing import Any

import gymnasium
import matplotlib

# First, as it says what to install when Stable-Baselines3 or torch is missing.
import mazesim.integrations.sb3  # noqa: F401

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import torch  # noqa: E402
from stable_baselines3 import SAC, TD3, HerReplayBuffer  # noqa: E402
from stable_baselines3.common.base_class import BaseAlgorithm  # noqa: E402
from stable_baselines3.common.callbacks import BaseCallback  # noqa: E402

import mazesim  # noqa: E402, F401  (registers the tasks)

#: The goal-conditioned tasks this script trains on.
TASKS = (
    "mazesim/EPuckGoal-v0",
    "mazesim/EPuckGoalDense-v0",
    "mazesim/UnseenMazeGoal-v0",
    "mazesim/UnseenMazeGoalDense-v0",
)
#: The held-out episodes' env is seeded from here on (training uses ``seed``).
HELD_OUT_SEED = 10**6
#: The observation's values that point at the episode's own goal, which a relabelled
#: ``desired_goal`` contradicts: ``--observation pose`` leaves them out.
GOAL_DIRECTION = ("goal_forward", "goal_left")


class PoseObservation(gymnasium.ObservationWrapper):  # type: ignore[type-arg]
    """The task made with ``include_pose=True``, without the goal's direction in ``observation``:
    the readings, the pose (x, y, heading) and the previous action, so that the policy learns where
    a goal lies from ``desired_goal`` and the pose alone, the same for a relabelled goal as for the
    episode's own."""

    def __init__(self, env: gymnasium.Env) -> None:  # type: ignore[type-arg]
        super().__init__(env)
        names = list(env.unwrapped.maze.observation_names)  # type: ignore[attr-defined]
        self.keep = np.array([i for i, name in enumerate(names) if name not in GOAL_DIRECTION])
        inner = env.observation_space["observation"]  # type: ignore[index]
        spaces = dict(env.observation_space.spaces)  # type: ignore[attr-defined]
        spaces["observation"] = gymnasium.spaces.Box(
            inner.low[self.keep], inner.high[self.keep], dtype=np.float32
        )
        self.observation_space = gymnasium.spaces.Dict(spaces)

    def observation(self, observation: dict[str, Any]) -> dict[str, Any]:
        return {**observation, "observation": observation["observation"][self.keep]}


def make_env(task: str, limit: int, observation: str) -> gymnasium.Env:  # type: ignore[type-arg]
    """One env of ``task`` with a time limit of ``limit`` steps, its observation as chosen."""
    if observation == "pose":
        return PoseObservation(gymnasium.make(task, max_episode_steps=limit, include_pose=True))
    return gymnasium.make(task, max_episode_steps=limit)


def evaluate(
    model: BaseAlgorithm, task: str, episodes: int, seed: int, limit: int, observation: str
) -> tuple[float, float]:
    """Success rate of ``model``'s deterministic policy over ``episodes`` held-out episodes, and
    the mean length (control steps) of the successful ones (NaN without any)."""
    env = make_env(task, limit, observation)
    observation, _ = env.reset(seed=HELD_OUT_SEED + seed)
    successes, lengths = 0, []
    for _ in range(episodes):
        length, done, success = 0, False, False
        while not done:
            action, _ = model.predict(observation, deterministic=True)
            observation, _, terminated, truncated, info = env.step(action)
            length += 1
            success = bool(info["is_success"])
            done = terminated or truncated
        successes += success
        if success:
            lengths.append(length)
        observation, _ = env.reset()
    env.close()
    return successes / episodes, float(np.mean(lengths)) if lengths else float("nan")


class HeldOutCurve(BaseCallback):
    """Evaluates the policy on the held-out episodes every ``every`` env-steps."""

    def __init__(
        self, task: str, every: int, episodes: int, seed: int, limit: int, observation: str
    ) -> None:
        super().__init__()
        self.task, self.every, self.episodes = task, every, episodes
        self.seed_, self.limit, self.observation = seed, limit, observation
        self.points: list[tuple[int, float]] = []

    def _on_step(self) -> bool:
        if self.num_timesteps % self.every == 0:
            rate, _ = evaluate(
                self.model, self.task, self.episodes, self.seed_, self.limit, self.observation
            )
            self.points.append((self.num_timesteps, rate))
        return True


def plot_curve(points: list[tuple[int, float]], picture: Path, title: str) -> None:
    """Draws held-out success against env-steps into a small PNG."""
    figure, axes = plt.subplots(figsize=(4, 2.6), dpi=80)
    axes.plot([p[0] for p in points], [100 * p[1] for p in points], marker=".")
    axes.set(xlabel="env-steps", ylabel="held-out success %", ylim=(-2, 102))
    figure.suptitle(title, fontsize=9)
    figure.tight_layout()
    figure.savefig(picture)
    plt.close(figure)


def main() -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--task", default="mazesim/EPuckGoal-v0", choices=TASKS)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--algo", choices=("sac", "td3"), default="sac")
    parser.add_argument("--steps", type=int, default=10_000, help="env-steps of training")
    parser.add_argument("--episode-steps", type=int, default=100, help="training time limit")
    parser.add_argument(
        "--eval-steps", type=int, default=None, help="held-out time limit (default: training's)"
    )
    parser.add_argument("--observation", choices=("task", "pose"), default="task")
    parser.add_argument("--gamma", type=float, default=0.95)
    parser.add_argument("--train-freq", type=int, default=4, help="env-steps per gradient step")
    parser.add_argument("--net", type=int, default=64, help="width of the two hidden layers")
    parser.add_argument("--batch", type=int, default=128)
    parser.add_argument("--n-sampled-goal", type=int, default=4)
    parser.add_argument("--learning-starts", type=int, default=1_000)
    parser.add_argument("--eval-every", type=int, default=2_500)
    parser.add_argument("--eval-episodes", type=int, default=50)
    parser.add_argument("--out", type=Path, default=Path("her-run"))
    args = parser.parse_args()
    if os.environ.get("MAZESIM_EXAMPLES_FAST") == "1":
        args.steps = min(args.steps, 300)
        args.eval_every = min(args.eval_every, 150)
        args.eval_episodes = min(args.eval_episodes, 2)
        args.episode_steps = min(args.episode_steps, 50)
        args.eval_steps = min(args.eval_steps or 50, 50)
    eval_steps = args.eval_steps or args.episode_steps

    # One torch thread: a shared machine's cores fought over by torch's threads slow SAC down.
    torch.set_num_threads(1)
    env = make_env(args.task, args.episode_steps, args.observation)
    settings: dict[str, Any] = {
        "algo": args.algo,
        "observation": args.observation,
        "buffer_size": 200_000,
        "batch_size": args.batch,
        "learning_starts": min(args.learning_starts, args.steps // 2),
        "gamma": args.gamma,
        "train_freq": args.train_freq,
        "n_sampled_goal": args.n_sampled_goal,
        "goal_selection_strategy": "future",
        "net_arch": [args.net, args.net],
    }
    algorithm = SAC if args.algo == "sac" else TD3
    model = algorithm(
        "MultiInputPolicy",
        env,
        replay_buffer_class=HerReplayBuffer,
        replay_buffer_kwargs={
            "n_sampled_goal": settings["n_sampled_goal"],
            "goal_selection_strategy": settings["goal_selection_strategy"],
        },
        buffer_size=settings["buffer_size"],
        batch_size=settings["batch_size"],
        learning_starts=settings["learning_starts"],
        gamma=settings["gamma"],
        train_freq=settings["train_freq"],
        policy_kwargs={"net_arch": settings["net_arch"]},
        seed=args.seed,
        device="cpu",
        verbose=0,
    )
    curve = HeldOutCurve(
        args.task, args.eval_every, args.eval_episodes, args.seed, eval_steps, args.observation
    )
    start = time.perf_counter()
    model.learn(total_timesteps=args.steps, callback=curve)
    seconds = time.perf_counter() - start
    env.close()
    success, length = evaluate(
        model, args.task, args.eval_episodes, args.seed, eval_steps, args.observation
    )
    args.out.mkdir(parents=True, exist_ok=True)
    points = [point for point in curve.points if point[0] < args.steps] + [(args.steps, success)]
    plot_curve(points, args.out / "curve.png", f"{args.task} seed {args.seed}")
    results = {
        "task": args.task,
        "seed": args.seed,
        "steps": args.steps,
        "episode_steps": args.episode_steps,
        "eval_steps": eval_steps,
        "eval_episodes": args.eval_episodes,
        "settings": settings,
        "curve": points,
        "success": success,
        "mean_success_length": None if np.isnan(length) else length,
        "wall_seconds": round(seconds, 1),
        "load_average": list(os.getloadavg()),
        "machine": f"{platform.machine()}, {os.cpu_count()} cores",
        "date": time.strftime("%Y-%m-%d", time.gmtime()),
    }
    (args.out / "results.json").write_text(json.dumps(results, indent=1) + "\n")
    print(
        f"{args.task} seed {args.seed}: {args.steps} env-steps in {seconds:.0f} s; success on "
        f"{args.eval_episodes} held-out episodes: {100 * success:.0f} %"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
