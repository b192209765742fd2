"""Training a navigator from scratch: the lower level on generated mazes, then the higher level on
the target world; checkpoints, ``--resume``, and a progress bar.

:func:`train` runs two stages:

1. **Lower level** (:mod:`mazesim.learn.lower`): the four sub-tasks on a pool of generated mazes,
   ``envs`` robots at a time, until ``steps`` env-steps are done, round by round. After every
   round whose end is at least :attr:`TrainSettings.checkpoint_seconds` after the last
   checkpoint (and after the last round) the tables, their update counts and the round reached
   are written to ``DIR/checkpoint.npz``, one file switched in with one atomic rename
   (:mod:`mazesim.learn.checkpoint`): a crash at any instant leaves the previous checkpoint or the
   new one, whole.
2. **Higher level** (:mod:`mazesim.learn.higher_training`): episodes on the target world with
   the lower level fixed, the sub-tasks chosen epsilon-greedily at checkpoint events.

The navigator is then saved into ``DIR`` (``tables.npz`` and ``policy.json``, see
:mod:`mazesim.learn.tables`) with the settings and what the run measured.

Everything random follows from the seed, round by round, and the simulator is deterministic
whatever the thread count, so a run stopped at any point and continued with ``resume=True``
ends with the same tables as a run never stopped (only the timings differ).
"""

from __future__ import annotations

import os
import sys
import time
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any, TextIO

from mazesim import load_world
from mazesim.episodes import shortest_path_steps
from mazesim.errors import InvalidArgumentError, PolicyFormatError
from mazesim.learn.checkpoint import (
    CHECKPOINT_FILE,
    CHECKPOINT_FORMAT,
    Checkpoint,
    checkpoint_exists,
    read_checkpoint,
    remove_checkpoint_leftovers,
    write_checkpoint,
)
from mazesim.learn.higher_training import HigherTraining, train_higher
from mazesim.learn.lower import LowerSettings, LowerTables, LowerTrainer, RoundStats
from mazesim.learn.tables import TrainedPolicy, save_policy
from mazesim.maze import checkpoint_ids, world_hash

__all__ = [
    "CHECKPOINT_FORMAT",
    "TrainSettings",
    "train",
    "train_flat_policy",
]


@dataclass(frozen=True)
class TrainSettings:
    """A training run's settings (saved with the navigator and checked on ``--resume``)."""

    world: str = "seed-maze"
    envs: int = 2048
    steps: int = 36_000_000
    seed: int = 0
    maze_pool: int = 200
    higher_episodes: int = 400
    higher_envs: int = 32
    higher_max_steps: int = 4000
    checkpoint_seconds: float = 30.0

    def lower(self) -> LowerSettings:
        """The lower-level stage's settings."""
        return LowerSettings(
            num_envs=self.envs, total_steps=self.steps, seed=self.seed, maze_pool=self.maze_pool
        )

    def higher(self) -> HigherTraining:
        """The higher-level stage's settings."""
        return HigherTraining(
            episodes_per_world=self.higher_episodes,
            envs_per_world=self.higher_envs,
            max_steps=self.higher_max_steps,
            seed=self.seed,
        )

    def identity(self) -> dict[str, Any]:
        """What must match for a checkpoint to be continued (not the checkpoint interval)."""
        values = asdict(self)
        values.pop("checkpoint_seconds")
        return values


class Progress:
    """A one-line progress bar with the live success rate, on a terminal only."""

    def __init__(self, stream: TextIO | None) -> None:
        self.stream = stream
        self.enabled = stream is not None and stream.isatty()
        self.started = time.perf_counter()
        self.shown = False

    def show(self, stage: str, done: int, total: int, detail: str) -> None:
        """Redraws the bar."""
        if not self.enabled or self.stream is None:
            return
        share = done / total if total else 1.0
        width = 24
        filled = int(round(width * share))
        elapsed = time.perf_counter() - self.started
        self.stream.write(
            f"\r\033[K{stage} [{'#' * filled}{'.' * (width - filled)}] {100 * share:3.0f}%  "
            f"{detail}  {elapsed:5.0f} s"
        )
        self.stream.flush()
        self.shown = True

    def close(self) -> None:
        """Clears the bar's line."""
        if self.shown and self.stream is not None:
            self.stream.write("\r\033[K")
            self.stream.flush()
            self.shown = False


def _round_summary(stats: RoundStats) -> dict[str, Any]:
    return {
        "round": stats.round_index,
        "epsilon": round(stats.epsilon, 6),
        "door_success": [round(stats.door_success_rate(k), 4) for k in (1, 2, 3)],
        "door_cut": stats.door_cut[1:],
        "corridor_speed": round(stats.corridor_speed, 4),
        "contact_share": round(stats.contact_share, 6),
    }


def train(
    settings: TrainSettings,
    out: str | os.PathLike[str],
    resume: bool = False,
    progress: TextIO | None = sys.stderr,
    threads: int = 0,
    stop_after_rounds: int | None = None,
) -> TrainedPolicy | None:
    """Trains a navigator and saves it into ``out``.

    Args:
        settings: The run's settings.
        out: The folder for the checkpoint and the navigator (created if missing).
        resume: Continue the run whose checkpoint is in ``out``.
        progress: Where the progress bar goes (shown only on a terminal); None for none.
        threads: Worker threads of the simulator (0: one per core); results do not depend on it.
        stop_after_rounds: Stop (as if interrupted) after this many lower-level rounds in this
            call, leaving the checkpoint; for tests.

    Returns:
        The trained navigator, or None when stopped early by ``stop_after_rounds``.

    Raises:
        PolicyFormatError: ``resume`` without a usable checkpoint of the same settings, or a
            checkpoint already in ``out`` without ``resume``.
        UnknownNameError, WorldFormatError: The world cannot be loaded.
    """
    folder = Path(out)
    world = load_world(settings.world)
    if world.goal is None or world.cell_maze() is None:
        raise InvalidArgumentError(
            f"world {world.name!r} needs a [grid] maze and a goal to train a navigator for"
        )
    lower_settings = settings.lower()
    if folder.exists() and not folder.is_dir():
        raise InvalidArgumentError(f"expected a folder for the navigator, found a file: {folder}")
    if resume:
        if not checkpoint_exists(folder):
            raise PolicyFormatError(f"{folder / CHECKPOINT_FILE}: no checkpoint to resume from")
        saved = read_checkpoint(folder, settings.identity())
        tables, next_round = saved.tables, saved.next_round
        history, lower_seconds = saved.history, saved.lower_seconds
    else:
        if checkpoint_exists(folder):
            raise PolicyFormatError(
                f"{folder} holds the checkpoint of another run; pass --resume to continue it, "
                "or choose another --out"
            )
        tables, next_round, history, lower_seconds = LowerTables.zeros(), 0, [], 0.0
    folder.mkdir(parents=True, exist_ok=True)
    remove_checkpoint_leftovers(folder)

    bar = Progress(progress)
    rounds = lower_settings.rounds
    try:
        if next_round < rounds:
            trainer = LowerTrainer(lower_settings, tables, threads=threads)
            started = time.perf_counter()
            last_saved = started
            done_here = 0
            for round_index in range(next_round, rounds):
                stats = trainer.run_round(round_index)
                history.append(_round_summary(stats))
                done_here += 1
                now = time.perf_counter()
                last_round = round_index + 1 == rounds
                stopping = stop_after_rounds is not None and done_here >= stop_after_rounds
                if last_round or stopping or now - last_saved >= settings.checkpoint_seconds:
                    write_checkpoint(
                        folder,
                        settings.identity(),
                        Checkpoint(
                            trainer.tables, round_index + 1, history, lower_seconds + now - started
                        ),
                    )
                    last_saved = now
                success = stats.door_success_rate()
                bar.show(
                    "lower level",
                    round_index + 1,
                    rounds,
                    f"round {round_index + 1}/{rounds}  door sub-tasks {100 * success:.1f}% "
                    f"success  corridor speed {stats.corridor_speed:.2f}",
                )
                if stopping and not last_round:
                    return None
            lower_seconds += time.perf_counter() - started
            tables = trainer.tables
        higher_started = time.perf_counter()

        def higher_progress(done: int, total: int, recent: float) -> None:
            bar.show(
                "higher level",
                done,
                total,
                f"episode {done}/{total} on {world.name}  {100 * recent:.1f}% reached the goal",
            )

        level, results = train_higher(
            tables.q,
            [world],
            settings.higher(),
            threads=threads,
            progress=higher_progress,
        )
        higher_seconds = time.perf_counter() - higher_started
    finally:
        bar.close()

    last = results[-100:]
    training: dict[str, Any] = {
        "settings": asdict(settings),
        "lower": lower_settings.as_dict(),
        "higher": asdict(settings.higher()),
        "lower_env_steps": rounds * lower_settings.num_envs * lower_settings.round_steps,
        "higher_env_steps": int(sum(r.steps for r in results)),
        "lower_seconds": round(lower_seconds, 1),
        "higher_seconds": round(higher_seconds, 1),
        "higher_success_last_100": sum(r.arrived for r in last) / max(1, len(last)),
        "shortest_path_steps": shortest_path_steps(world),
        "history": history,
        "cpu_count": os.cpu_count(),
        "load_average": list(os.getloadavg()) if hasattr(os, "getloadavg") else None,
    }
    policy = TrainedPolicy(
        kind="hierarchical",
        world_name=world.name,
        world_sha256=world_hash(world),
        checkpoint_ids=level.checkpoint_ids[0],
        lower_q=tables.q,
        higher_q=level.q[0],
        training=training,
    )
    save_policy(policy, folder)
    policy.source = str(folder)
    return policy


def train_flat_policy(
    settings: TrainSettings,
    out: str | os.PathLike[str],
    progress: TextIO | None = sys.stderr,
    threads: int = 0,
) -> TrainedPolicy:
    """Trains the flat baseline on ``settings.world`` for ``settings.steps`` env-steps and saves
    it into ``out`` (:mod:`mazesim.learn.baseline`)."""
    from mazesim.learn.baseline import train_flat

    world = load_world(settings.world)
    if world.goal is None or world.cell_maze() is None:
        raise InvalidArgumentError(
            f"world {world.name!r} needs a [grid] maze and a goal to train a navigator for"
        )
    bar = Progress(progress)
    started = time.perf_counter()

    def flat_progress(done: int, total: int, recent: float) -> None:
        bar.show(
            "flat baseline",
            done,
            total,
            f"step {done}/{total}  {100 * recent:.1f}% of recent episodes reached the goal",
        )

    try:
        q, outcomes = train_flat(
            world,
            settings.steps,
            num_envs=settings.envs,
            seed=settings.seed,
            threads=threads,
            progress=flat_progress,
        )
    finally:
        bar.close()
    last = outcomes[-100:]
    policy = TrainedPolicy(
        kind="flat",
        world_name=world.name,
        world_sha256=world_hash(world),
        checkpoint_ids=checkpoint_ids(world),
        flat_q=q,
        training={
            "settings": asdict(settings),
            "env_steps": settings.steps,
            "seconds": round(time.perf_counter() - started, 1),
            "episodes": len(outcomes),
            "success_last_100": sum(last) / max(1, len(last)),
            "cpu_count": os.cpu_count(),
            "load_average": list(os.getloadavg()) if hasattr(os, "getloadavg") else None,
        },
    )
    Path(out).mkdir(parents=True, exist_ok=True)
    save_policy(policy, out)
    policy.source = str(out)
    return policy
