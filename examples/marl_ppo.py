"""Parameter-shared PPO on a multi-robot task of mazesim.marl, then held-out episodes.

Needs the extras ``mazesim[marl]`` and ``mazesim[sb3]`` (torch; ``make marl-deps sb3-deps`` in a
checkout)::

    python examples/marl_ppo.py --task maze_goals_v0 --seed 0 --steps 3000000 --out runs/goals-0

Every robot of every environment is one row of one policy (a CleanRL-style PPO written here: an
MLP actor with a state-independent Gaussian, an MLP critic), fed by the native batch
(``batch_env``: ``--envs`` environments x R robots, reset with seeds ``seed``, ``seed + 1``...).
A robot whose episode ended stands still until its environment restarts; its rows are left out
of the loss. Truncation at the step limit is treated as an end (no bootstrap).

It writes the learning curve (``progress.csv``: robot-steps, mean return of a robot over the
last 100 finished environments' episodes, and the task's measure: the share of robots at their
goal, or the final dispersion; ``curve.png``, its picture) and ``summary.json``, then runs the
trained policy (its mean action), a random policy and the task's hand rule for one episode on
each of ``--eval-envs`` held-out environments (seeded from ``10**6 + seed``: mazes, starts and
goals never trained on) with :func:`mazesim.marl.evaluate.evaluate`, and prints one line each.
``--plot runs/a runs/b --picture curve.png`` draws finished runs' curves together.
"""

from __future__ import annotations

import argparse
import csv
import dataclasses
import io
import json
import math
import time
from collections import deque
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import torch  # noqa: E402
from torch import nn  # noqa: E402

from mazesim._atomic import atomic_file  # noqa: E402
from mazesim.marl import aggregation_v0, maze_goals_v0  # noqa: E402
from mazesim.marl.evaluate import Evaluation, evaluate  # noqa: E402
from mazesim.marl.rules import HAND_RULES, random_policy  # noqa: E402

TASKS: dict[str, Any] = {"maze_goals_v0": maze_goals_v0, "aggregation_v0": aggregation_v0}


@dataclass
class Settings:
    """PPO's settings; each field is a command-line option of the same name."""

    task: str = "maze_goals_v0"  # the task module of mazesim.marl
    seed: int = 0  # the run's seed (environments, network, sampling)
    steps: int = 3_000_000  # robot-steps of training
    envs: int = 64  # environments of the native batch
    rollout: int = 64  # steps of every environment per update
    epochs: int = 4  # passes over a rollout
    minibatches: int = 4  # minibatches per pass
    learning_rate: float = 3e-4  # Adam's step size
    gamma: float = 0.99  # discount
    gae_lambda: float = 0.95  # GAE's lambda
    clip: float = 0.2  # PPO's ratio clip
    entropy: float = 0.0  # entropy bonus coefficient
    value_coef: float = 0.5  # weight of the value loss
    max_grad_norm: float = 0.5  # gradient clipping
    hidden: int = 64  # units of each of the two hidden layers
    eval_envs: int = 64  # held-out environments (one episode each)
    out: str = "runs/marl"  # folder of the curve, the summary and the model


class Agent(nn.Module):
    """The shared policy: actor mean and critic MLPs, and a learned log standard deviation."""

    def __init__(self, width: int, hidden: int) -> None:
        super().__init__()

        def mlp(outputs: int, scale: float) -> nn.Sequential:
            layers = [nn.Linear(width, hidden), nn.Tanh(), nn.Linear(hidden, hidden), nn.Tanh()]
            last = nn.Linear(hidden, outputs)
            for layer in [*layers[::2], last]:
                assert isinstance(layer, nn.Linear)
                nn.init.orthogonal_(layer.weight, math.sqrt(2) if layer is not last else scale)
                nn.init.zeros_(layer.bias)
            return nn.Sequential(*layers, last)

        self.actor = mlp(2, 0.01)
        self.critic = mlp(1, 1.0)
        self.log_std = nn.Parameter(torch.full((2,), -0.5))

    def value(self, observations: torch.Tensor) -> torch.Tensor:
        return self.critic(observations).squeeze(-1)

    def distribution(self, observations: torch.Tensor) -> torch.distributions.Normal:
        return torch.distributions.Normal(self.actor(observations), self.log_std.exp())


def train(settings: Settings) -> dict[str, Any]:
    """Trains, writes the curve and the model into ``settings.out``; returns the summary."""
    torch.set_num_threads(1)  # the batch engine has the other core
    torch.manual_seed(settings.seed)
    module = TASKS[settings.task]
    batch = module.batch_env(settings.envs, threads=1)
    n, r = batch.num_envs, batch.num_robots
    rows, width, length = n * r, batch.observation_width, settings.rollout
    agent = Agent(width, settings.hidden)
    optimiser = torch.optim.Adam(agent.parameters(), lr=settings.learning_rate, eps=1e-5)
    observations = torch.from_numpy(batch.reset(settings.seed)[0].reshape(rows, width))
    buffers = {
        "obs": torch.zeros((length, rows, width)),
        "actions": torch.zeros((length, rows, 2)),
        "logp": torch.zeros((length, rows)),
        "values": torch.zeros((length, rows)),
        "rewards": torch.zeros((length, rows)),
        "dones": torch.zeros((length, rows)),
        "alive": torch.zeros((length, rows), dtype=torch.bool),
    }
    returns_so_far = np.zeros((n, r))
    success_so_far = np.zeros((n, r), bool)
    finished: deque[tuple[float, float]] = deque(maxlen=100)
    curve: list[dict[str, float]] = []
    done_steps, started = 0, time.perf_counter()
    while done_steps < settings.steps:
        for t in range(length):
            alive = batch.live.reshape(rows).copy()
            with torch.no_grad():
                policy = agent.distribution(observations)
                actions = policy.sample()
                buffers["logp"][t] = policy.log_prob(actions).sum(-1)
                buffers["values"][t] = agent.value(observations)
            buffers["obs"][t], buffers["actions"][t] = observations, actions
            buffers["alive"][t] = torch.from_numpy(alive)
            result = batch.step(actions.numpy().reshape(n, r, 2))
            next_obs, rewards, terminations, truncations, infos = result
            buffers["rewards"][t] = torch.from_numpy(rewards.reshape(rows))
            buffers["dones"][t] = torch.from_numpy((terminations | truncations).reshape(rows))
            returns_so_far += rewards
            if "is_success" in infos:
                success_so_far |= infos["is_success"]
            for e in np.flatnonzero(infos["reset"]):
                measure = (
                    float(success_so_far[e].mean())
                    if "is_success" in infos
                    else float(infos["dispersion"][e, 0])
                )
                finished.append((float(returns_so_far[e].mean()), measure))
                returns_so_far[e] = 0.0
                success_so_far[e] = False
            observations = torch.from_numpy(next_obs.reshape(rows, width))
        done_steps += length * rows
        update(agent, optimiser, buffers, observations, settings)
        if finished:
            mean_return, measure = (float(np.mean(column)) for column in zip(*finished))
            curve.append({"robot_steps": done_steps, "return": mean_return, "measure": measure})
    seconds = time.perf_counter() - started
    out = Path(settings.out)
    out.mkdir(parents=True, exist_ok=True)
    write_curve(out / "progress.csv", curve)
    with atomic_file(out / "model.pt") as stream:
        buffer = io.BytesIO()
        torch.save(agent.state_dict(), buffer)
        stream.write(buffer.getvalue())
    plot([out], out / "curve.png")
    summary = {"settings": dataclasses.asdict(settings), "seconds": seconds}
    summary["robot_steps"] = done_steps
    summary["evaluation"] = held_out(agent, settings)
    with atomic_file(out / "summary.json") as stream:
        stream.write(json.dumps(summary, indent=2).encode())
    return summary


def update(
    agent: Agent,
    optimiser: torch.optim.Optimizer,
    buffers: dict[str, torch.Tensor],
    last_observations: torch.Tensor,
    settings: Settings,
) -> None:
    """GAE over the rollout, then PPO's clipped updates on the rows of live robots."""
    rewards, dones, values = buffers["rewards"], buffers["dones"], buffers["values"]
    with torch.no_grad():
        following = agent.value(last_observations)
    advantages = torch.zeros_like(rewards)
    running = torch.zeros_like(following)
    for t in reversed(range(len(rewards))):
        going = 1.0 - dones[t]
        following = following if t == len(rewards) - 1 else values[t + 1]
        delta = rewards[t] + settings.gamma * following * going - values[t]
        running = delta + settings.gamma * settings.gae_lambda * going * running
        advantages[t] = running
    alive = buffers["alive"].reshape(-1)
    obs = buffers["obs"].reshape(-1, buffers["obs"].shape[-1])[alive]
    actions = buffers["actions"].reshape(-1, 2)[alive]
    old_logp = buffers["logp"].reshape(-1)[alive]
    adv = advantages.reshape(-1)[alive]
    targets = adv + values.reshape(-1)[alive]
    count = len(adv)
    size = max(count // settings.minibatches, 1)
    for _ in range(settings.epochs):
        order = torch.randperm(count)
        for start in range(0, count, size):
            pick = order[start : start + size]
            policy = agent.distribution(obs[pick])
            ratio = (policy.log_prob(actions[pick]).sum(-1) - old_logp[pick]).exp()
            a = adv[pick]
            a = (a - a.mean()) / (a.std() + 1e-8) if len(a) > 1 else a
            clipped = torch.clamp(ratio, 1 - settings.clip, 1 + settings.clip)
            policy_loss = -torch.min(ratio * a, clipped * a).mean()
            value_loss = 0.5 * (agent.value(obs[pick]) - targets[pick]).pow(2).mean()
            entropy = policy.entropy().sum(-1).mean()
            loss = policy_loss + settings.value_coef * value_loss - settings.entropy * entropy
            optimiser.zero_grad()
            loss.backward()
            nn.utils.clip_grad_norm_(agent.parameters(), settings.max_grad_norm)
            optimiser.step()


def held_out(agent: Agent, settings: Settings) -> dict[str, dict[str, float]]:
    """The trained policy, a random policy and the hand rule on the same held-out episodes."""
    module = TASKS[settings.task]
    seed = 10**6 + settings.seed

    def trained(observations: np.ndarray) -> np.ndarray:
        with torch.no_grad():
            mean = agent.actor(torch.from_numpy(observations))
        return mean.clamp(-1.0, 1.0).numpy()

    policies = {
        "ppo": trained,
        "random": random_policy(seed),
        "hand rule": HAND_RULES[settings.task],
    }
    results = {}
    for name, policy in policies.items():
        found: Evaluation = evaluate(module.batch_env(settings.eval_envs, threads=1), policy, seed)
        results[name] = dataclasses.asdict(found)
    return results


def write_curve(path: Path, curve: list[dict[str, float]]) -> None:
    text = io.StringIO()
    writer = csv.DictWriter(text, ["robot_steps", "return", "measure"])
    writer.writeheader()
    writer.writerows(curve)
    with atomic_file(path) as stream:
        stream.write(text.getvalue().encode())


def plot(runs: list[Path], picture: Path) -> None:
    """Draws the curves of finished runs (their ``progress.csv``) into ``picture``."""
    figure, (returns, measures) = plt.subplots(1, 2, figsize=(10, 4))
    task = ""
    for run in runs:
        with open(run / "progress.csv", newline="") as stream:
            rows = list(csv.DictReader(stream))
        summary = run / "summary.json"
        if summary.exists():
            task = json.loads(summary.read_text())["settings"]["task"]
        steps = [float(row["robot_steps"]) for row in rows]
        returns.plot(steps, [float(row["return"]) for row in rows], label=run.name)
        measures.plot(steps, [float(row["measure"]) for row in rows], label=run.name)
    returns.set(xlabel="robot-steps", ylabel="mean return of a robot", title=task)
    measure = "final dispersion (lower: tighter)" if "aggregation" in task else "robots at goal"
    measures.set(xlabel="robot-steps", ylabel=measure)
    for axes in (returns, measures):
        axes.grid(alpha=0.3)
        axes.legend(fontsize="small")
    figure.tight_layout()
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=100)
    plt.close(figure)
    with atomic_file(picture) as stream:
        stream.write(buffer.getvalue())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    for field in dataclasses.fields(Settings):
        option = "--" + field.name.replace("_", "-")
        kind = {"int": int, "float": float, "str": str}[str(field.type)]
        parser.add_argument(option, type=kind, default=field.default, dest=field.name)
    parser.add_argument("--plot", nargs="+", type=Path, help="finished runs to draw together")
    parser.add_argument("--picture", type=Path, default=Path("marl-curves.png"))
    args = parser.parse_args()
    if args.plot:
        plot(args.plot, args.picture)
        return
    settings = Settings(**{f.name: getattr(args, f.name) for f in dataclasses.fields(Settings)})
    summary = train(settings)
    print(
        f"{settings.task} seed {settings.seed}: {summary['robot_steps']} robot-steps in "
        f"{summary['seconds']:.0f} s ({summary['robot_steps'] / summary['seconds']:,.0f} "
        "robot-steps/s)"
    )
    for name, found in summary["evaluation"].items():
        print(
            f"  {name}: mean return {found['mean_return']:.2f}, at goal {found['success']:.2f}, "
            f"collided {found['collided']:.2f}, dispersion {found['dispersion']:.1f} "
            f"({found['episodes']} held-out episodes)"
        )


if __name__ == "__main__":
    main()
