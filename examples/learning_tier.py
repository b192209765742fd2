"""The learning tier: PPO, RecurrentPPO and PPO with a maze-size curriculum on unseen mazes whose
observation gives no plan, beside the hand-written baselines, on held-out mazes.

Needs the extra ``mazesim[sb3]`` (Stable-Baselines3 and sb3-contrib; ``make sb3-deps`` in a
checkout). Three commands::

    python examples/learning_tier.py train --agent ppo --seed 0 --out runs/tier-ppo-0
    python examples/learning_tier.py baselines --out runs/tier-baselines
    python examples/learning_tier.py table runs/tier-* --picture curves.png

The task is ``mazesim/UnseenMazeExplore-v0`` (the robot's readings, the map it has explored round
its cell, the goal's direction; 1000 steps of 128 ms) on mazes of ``--maze-size`` cells (7 x 7 by
default, where the hand rules no longer reach every goal within the step limit). ``train`` trains
one agent for ``--steps`` env-steps on 128 environments seeded ``seed``, ``seed + 1``, ...:

- ``ppo``: SB3's PPO, a feed-forward policy (two layers of 64), on mazes of the target size;
- ``recurrent``: sb3-contrib's RecurrentPPO, the same layers and an LSTM of 64, on the same;
- ``curriculum``: PPO on 3 x 3 mazes, then 5 x 5, then the target size, each stage once the
  last 200 training episodes reach 80 % (:class:`mazesim.envs.curriculum.MazeSizeCurriculum`).

Every ``--eval-every`` env-steps it runs the policy on 50 validation mazes of the target size
(environments seeded from ``3 * 10**6 + seed``): the learning curve. At the end it tests it on
100 held-out mazes of 5 x 5 and of the target size (environments seeded from ``10**6 + seed``,
never trained on), and writes ``results.json`` (success, mean steps of the successful episodes,
the curve, wall time, date, load average) into ``--out``. ``baselines`` runs the wall follower,
the frontier explorer and uniformly random actions on the same held-out mazes of seeds 0, 1 and
2. ``table`` prints the Markdown table of finished runs and draws their curves.
``MAZESIM_EXAMPLES_FAST=1`` runs a tiny version (a few hundred env-steps, 4 held-out mazes).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import time
from collections import defaultdict
from pathlib import Path
from typing import Any

import matplotlib

# First, as it says what to install when Stable-Baselines3 or torch is missing.
from mazesim.integrations.sb3 import make_vec_env

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import torch  # noqa: E402
from sb3_contrib import RecurrentPPO  # noqa: E402
from stable_baselines3 import PPO  # noqa: E402
from stable_baselines3.common.base_class import BaseAlgorithm  # noqa: E402
from stable_baselines3.common.callbacks import BaseCallback  # noqa: E402
from stable_baselines3.common.vec_env import VecEnv, VecNormalize  # noqa: E402

from mazesim.envs.baselines import FrontierExplorer, WallFollower, evaluate  # noqa: E402
from mazesim.envs.curriculum import MazeSizeCurriculum  # noqa: E402

TASK = "mazesim/UnseenMazeExplore-v0"
AGENTS = ("ppo", "recurrent", "curriculum")
#: The held-out mazes' environments are seeded from here on; the validation curve's from
#: ``VALIDATION_SEED``; training uses seed, seed + 1, ...
HELD_OUT_SEED = 10**6
VALIDATION_SEED = 3 * 10**6
#: The fast mode's time limit of the test episodes (None: the task's 1000 steps).
FAST_LIMIT = 100
#: PPO's settings (``examples/ppo_sb3.py``'s for ``UnseenMazeExplore-v0``), shared by every agent.
SETTINGS: dict[str, Any] = {
    "envs": 128,
    "n_steps": 128,
    "batch_size": 4096,
    "n_epochs": 4,
    "learning_rate": 3e-4,
    "gamma": 0.99,
    "net_arch": [64, 64],
    "lstm_hidden_size": 64,
    "curriculum": {"sizes": [[3, 3], [5, 5]], "promote_at": 0.8, "window": 200},
}


def run_policy(
    model: BaseAlgorithm, episodes: int, seed: int, maze_size: tuple[int, int]
) -> dict[str, float | None]:
    """One episode of ``model`` (sampled actions, its LSTM state carried) in each of ``episodes``
    environments seeded from ``seed``: the success rate and mean steps of the successes."""
    limit = {"max_episode_steps": FAST_LIMIT} if os.environ.get("MAZESIM_EXAMPLES_FAST") else {}
    envs = make_vec_env(TASK, episodes, seed=seed, monitor=False, maze_size=maze_size, **limit)
    observations = envs.reset()
    state = None
    starts = np.ones(episodes, dtype=bool)
    finished = np.zeros(episodes, dtype=bool)
    success = np.zeros(episodes, dtype=bool)
    steps = np.zeros(episodes, dtype=np.int64)
    while not finished.all():
        actions, state = model.predict(
            observations, state=state, episode_start=starts, deterministic=False
        )
        observations, _, dones, infos = envs.step(actions)
        steps += ~finished
        for i in np.flatnonzero(dones & ~finished):
            success[i] = infos[i]["is_success"]
        finished |= dones
        starts = dones
    envs.close()
    lengths = steps[success]
    return {
        "success": float(success.mean()),
        "success_steps": float(lengths.mean()) if lengths.size else None,
    }


class Progress(BaseCallback):
    """The validation curve every ``every`` env-steps; with a curriculum, its stages."""

    def __init__(
        self,
        every: int,
        episodes: int,
        seed: int,
        target: tuple[int, int],
        curriculum: MazeSizeCurriculum | None,
    ) -> None:
        super().__init__()
        self.every, self.episodes, self.seed_, self.target = every, episodes, seed, target
        self.curriculum = curriculum
        self.curve: list[tuple[int, float]] = []
        self.stages: list[tuple[int, list[int]]] = []
        self._next = every

    def _on_training_start(self) -> None:
        if self.curriculum is not None:
            self._apply_stage()

    def _on_step(self) -> bool:
        if self.curriculum is not None:
            dones = self.locals["dones"]
            successes = [info.get("is_success", False) for info in self.locals["infos"]]
            if self.curriculum.record(dones, successes):
                self._apply_stage()
        if self.num_timesteps >= self._next:
            self._next += self.every
            found = run_policy(self.model, self.episodes, self.seed_, self.target)
            self.curve.append((self.num_timesteps, found["success"]))
        return True

    def _apply_stage(self) -> None:
        assert self.curriculum is not None
        self.curriculum.apply(self.training_env.unwrapped.vector_env)  # type: ignore[attr-defined]
        self.stages.append((self.num_timesteps, list(self.curriculum.size)))


def machine() -> dict[str, Any]:
    """The date, the machine and its load average, for every figure."""
    return {
        "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
        "machine": f"{platform.machine()}, {os.cpu_count()} cores",
        "load_average": [round(load, 2) for load in os.getloadavg()],
    }


def train(args: argparse.Namespace, fast: bool) -> None:
    """Trains one agent, tests it on the held-out mazes and writes ``results.json``."""
    target = (args.maze_size, args.maze_size)
    envs_count = 8 if fast else SETTINGS["envs"]
    n_steps = 32 if fast else SETTINGS["n_steps"]
    batch = 128 if fast else SETTINGS["batch_size"]
    torch.set_num_threads(1)  # the batch engine has the other core
    curriculum = None
    if args.agent == "curriculum":
        stages = [tuple(size) for size in SETTINGS["curriculum"]["sizes"]] + [target]
        curriculum = MazeSizeCurriculum(
            stages,
            promote_at=SETTINGS["curriculum"]["promote_at"],
            window=4 if fast else SETTINGS["curriculum"]["window"],
        )
    envs: VecEnv = make_vec_env(TASK, envs_count, seed=args.seed, maze_size=target)
    envs = VecNormalize(envs, norm_obs=False, norm_reward=True, gamma=SETTINGS["gamma"])
    common = {
        "n_steps": n_steps,
        "batch_size": batch,
        "n_epochs": SETTINGS["n_epochs"],
        "learning_rate": SETTINGS["learning_rate"],
        "gamma": SETTINGS["gamma"],
        "ent_coef": 0.0,
        "seed": args.seed,
        "device": "cpu",
        "verbose": 0,
    }
    model: BaseAlgorithm
    if args.agent == "recurrent":
        policy = {
            "net_arch": SETTINGS["net_arch"],
            "lstm_hidden_size": SETTINGS["lstm_hidden_size"],
        }
        model = RecurrentPPO("MlpLstmPolicy", envs, policy_kwargs=policy, **common)
    else:
        model = PPO("MlpPolicy", envs, policy_kwargs={"net_arch": SETTINGS["net_arch"]}, **common)
    validation = 4 if fast else 50
    progress = Progress(
        args.eval_every, validation, VALIDATION_SEED + args.seed, target, curriculum
    )
    start = time.perf_counter()
    model.learn(total_timesteps=args.steps, callback=progress)
    seconds = time.perf_counter() - start
    envs.close()
    held_out = 4 if fast else 100
    tests = {
        f"{size}x{size}": run_policy(model, held_out, HELD_OUT_SEED + args.seed, (size, size))
        for size in sorted({5, args.maze_size})
    }
    results = {
        "agent": args.agent,
        "task": TASK,
        "maze_size": list(target),
        "seed": args.seed,
        "env_steps": model.num_timesteps,
        "settings": SETTINGS,
        "held_out_episodes": held_out,
        "held_out": tests,
        "curve": progress.curve,
        "stages": progress.stages,
        "wall_seconds": round(seconds, 1),
        **machine(),
    }
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "results.json").write_text(json.dumps(results, indent=1) + "\n")
    summary = ", ".join(f"{name} {100 * found['success']:.0f} %" for name, found in tests.items())
    print(
        f"{args.agent} seed {args.seed}: {model.num_timesteps} env-steps in {seconds:.0f} s; "
        f"success on {held_out} held-out mazes: {summary}"
    )


def baselines(args: argparse.Namespace, fast: bool) -> None:
    """The hand-written agents and random actions on the held-out mazes of seeds 0, 1, 2."""
    episodes = 4 if fast else 100
    for name, agent in (
        ("wall follower", WallFollower),
        ("frontier explorer", FrontierExplorer),
        ("random", None),
    ):
        for seed in range(3):
            start = time.perf_counter()
            tests = {}
            for size in sorted({5, args.maze_size}):
                found = evaluate(
                    TASK, agent, episodes, HELD_OUT_SEED + seed, maze_size=(size, size)
                )
                tests[f"{size}x{size}"] = {
                    "success": found.success,
                    "success_steps": (
                        None if np.isnan(found.mean_success_length) else found.mean_success_length
                    ),
                }
            results = {
                "agent": name,
                "seed": seed,
                "held_out_episodes": episodes,
                "held_out": tests,
                "curve": [],
                "wall_seconds": round(time.perf_counter() - start, 1),
                **machine(),
            }
            out = args.out / f"{name.replace(' ', '-')}-{seed}"
            out.mkdir(parents=True, exist_ok=True)
            (out / "results.json").write_text(json.dumps(results, indent=1) + "\n")
            summary = ", ".join(f"{k} {100 * v['success']:.0f} %" for k, v in tests.items())
            print(f"{name} seed {seed}: success on {episodes} held-out mazes: {summary}")


def table(runs: list[Path], picture: Path) -> None:
    """Prints the Markdown table of the runs' results (grouped by agent) and draws the curves."""
    grouped: dict[str, list[dict[str, Any]]] = defaultdict(list)
    for run in runs:
        for found in sorted(run.glob("**/results.json")):
            result = json.loads(found.read_text())
            grouped[result["agent"]].append(result)
    sizes = sorted({size for group in grouped.values() for r in group for size in r["held_out"]})
    header = ["agent", "seeds"]
    for size in sizes:
        header += [f"success {size}, mean (spread)", f"steps to goal {size}"]
    header += ["env-steps", "wall time per run", "date (UTC)", "load average"]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for agent, group in grouped.items():
        row = [agent, ", ".join(str(r["seed"]) for r in group)]
        for size in sizes:
            rates = [100 * r["held_out"][size]["success"] for r in group]
            steps = [r["held_out"][size]["success_steps"] for r in group]
            steps = [s for s in steps if s is not None]
            row.append(
                f"{np.mean(rates):.0f} % ({min(rates):.0f}-{max(rates):.0f}; "
                + " / ".join(f"{rate:.0f}" for rate in rates)
                + ")"
            )
            row.append(f"{np.mean(steps):.0f}" if steps else "-")
        walls = [r["wall_seconds"] for r in group]
        env_steps = {r.get("env_steps", 0) for r in group}
        loads = [load for r in group for load in r["load_average"][:1]]
        row += [
            "-" if env_steps == {0} else ", ".join(f"{s:,}" for s in sorted(env_steps)),
            f"{min(walls):.0f}-{max(walls):.0f} s",
            ", ".join(sorted({r["date"][:10] for r in group})),
            f"{min(loads):.1f}-{max(loads):.1f}",
        ]
        print("| " + " | ".join(row) + " |")
    figure, axes = plt.subplots(figsize=(6, 3.2), dpi=80)
    colours = dict(zip(AGENTS, ("tab:blue", "tab:orange", "tab:green")))
    for agent, group in grouped.items():
        for index, result in enumerate(group):
            if not result["curve"]:
                continue
            steps, rates = zip(*result["curve"])
            label = agent if index == 0 else None
            axes.plot(steps, [100 * r for r in rates], color=colours.get(agent), label=label)
    axes.set(xlabel="env-steps", ylabel="validation success %", ylim=(-2, 102))
    axes.legend(fontsize=7, loc="upper left")
    figure.suptitle(f"{TASK}: validation mazes of the target size, a line per run", fontsize=9)
    figure.tight_layout()
    figure.savefig(picture)
    plt.close(figure)


def main() -> int:
    fast = os.environ.get("MAZESIM_EXAMPLES_FAST") == "1"
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    commands = parser.add_subparsers(dest="command", required=True)
    training = commands.add_parser("train", help="train one agent, then test it")
    training.add_argument("--agent", choices=AGENTS, default="ppo")
    training.add_argument("--seed", type=int, default=0)
    training.add_argument("--steps", type=int, default=1_000_000, help="env-steps of training")
    training.add_argument("--eval-every", type=int, default=200_000)
    for command in (training, commands.add_parser("baselines", help="the hand rules, random")):
        command.add_argument("--maze-size", type=int, default=7, help="the target size's side")
        command.add_argument("--out", type=Path, default=Path("tier-run"))
    tabling = commands.add_parser("table", help="print the table of finished runs, draw curves")
    tabling.add_argument("runs", type=Path, nargs="+")
    tabling.add_argument("--picture", type=Path, default=Path("curves.png"))
    args = parser.parse_args()
    if args.command == "train":
        if fast:
            args.steps = min(args.steps, 512)
            args.eval_every = min(args.eval_every, 256)
        train(args, fast)
    elif args.command == "baselines":
        baselines(args, fast)
    else:
        table(args.runs, args.picture)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
