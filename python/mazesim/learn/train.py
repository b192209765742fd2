"""Training a navigator from scratch: the lower level on generated mazes, then the higher level on
the target world; checkpoints and ``--resume``.

:func:`run_training` is the one training pipeline (the sweep's ``hrl`` trainer runs it too); it
writes and prints nothing, and reports through ``progress(stage, done, total)`` and a
``checkpoint`` callback. :func:`train` runs it from settings, and writes only through the
:class:`RunWriter` it is handed (``mazesim train`` hands it a
:class:`~mazesim.learn.checkpoint.RunFolder`: checkpoints, ``--resume`` and the saved navigator);
without one it writes nothing. The two stages:

1. **Lower level** (:mod:`mazesim.learn.lower`): the four sub-tasks on a pool of generated mazes,
   ``envs`` robots at a time, until ``steps`` env-steps are done, round by round. After every
   round whose end is at least :attr:`TrainSettings.checkpoint_seconds` after the last
   checkpoint (and after the last round) the tables, their update counts and the round reached
   go to the writer; a :class:`~mazesim.learn.checkpoint.RunFolder` writes them to
   ``DIR/checkpoint.npz``, one file switched in with one atomic rename
   (:mod:`mazesim.learn.checkpoint`): a crash at any instant leaves the previous checkpoint or the
   new one, whole.
2. **Higher level** (:mod:`mazesim.learn.higher_training`): episodes on the target world with
   the lower level fixed, the sub-tasks chosen epsilon-greedily at checkpoint events.

The navigator, with the settings and what the run measured, then goes to the writer
(a :class:`~mazesim.learn.checkpoint.RunFolder` saves ``tables.npz`` and ``policy.json`` into
``DIR``, see :mod:`mazesim.learn.tables`).

Everything random follows from the seed, round by round, and the simulator is deterministic
whatever the thread count, so a run stopped at any point and continued with ``resume=True``
ends with the same tables as a run never stopped (only the timings differ).
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Sequence
from dataclasses import Field, asdict, dataclass, fields
from pathlib import Path
from typing import Any, Protocol, Union

from mazesim import load_world
from mazesim._core import World, builtin_world_names
from mazesim._paths import shell_command
from mazesim._settings import MAX_COUNT, MAX_SEED, bounded, check_settings, setting
from mazesim.batch import RobotChoice
from mazesim.episodes import EpisodeResult, learning_problems, shortest_path_steps
from mazesim.errors import InvalidArgumentError, _shown
from mazesim.learn.baseline import train_flat
from mazesim.learn.checkpoint import CHECKPOINT_FORMAT, Checkpoint
from mazesim.learn.fleet import Fleet
from mazesim.learn.higher import HigherLevel
from mazesim.learn.higher_training import HigherTraining, train_higher
from mazesim.learn.learning_curve import CURVE_VALUES, CurveFn, episode_progress, lower_point
from mazesim.learn.lower import (
    MAX_TRAINING_STEPS,
    LowerSettings,
    LowerTables,
    LowerTrainer,
    RoundStats,
    drive_on_when_blind,
)
from mazesim.learn.summary import summarise
from mazesim.learn.tables import TrainedPolicy
from mazesim.maze import checkpoint_ids, refuse_blocked_start, world_hash, world_source

__all__ = [
    "CHECKPOINT_FORMAT",
    "CURVE_VALUES",
    "CheckpointFn",
    "CurveFn",
    "ProgressFn",
    "RobotDraw",
    "RunWriter",
    "TrainSettings",
    "TrainingRun",
    "command_line_fields",
    "navigator_world",
    "refuse_unlearnable",
    "run_training",
    "train",
    "train_flat_policy",
    "world_file",
]


@dataclass(frozen=True)
class TrainSettings:
    """A training run's settings (saved with the navigator and checked on ``--resume``).

    The defaults are the only ones: the lower level's come from :class:`LowerSettings`, the step
    limit from :data:`mazesim.episodes.MAX_STEPS`, and ``mazesim train`` builds its options from
    the fields whose metadata has a ``help`` text (:func:`command_line_fields`).
    """

    world: str = setting(
        "seed-maze",
        "the world the higher level learns: a built-in name or a world file",
        "NAME|PATH",
    )
    envs: int = setting(
        LowerSettings.num_envs,
        "robots stepped at once while training the lower level",
        "N",
        least=1,
        most=MAX_COUNT,
    )
    steps: int = setting(
        LowerSettings.total_steps,
        "env-steps of lower-level training, e.g. 36M or 500k",
        "K",
        least=1,
        most=MAX_TRAINING_STEPS,
    )
    seed: int = setting(
        LowerSettings.seed, "seed of everything random in the run", "S", least=0, most=MAX_SEED
    )
    maze_pool: int = bounded(LowerSettings.maze_pool, least=1, most=MAX_COUNT)
    higher_episodes: int = bounded(HigherTraining.episodes_per_world, least=1, most=MAX_COUNT)
    higher_envs: int = bounded(HigherTraining.envs_per_world, least=1, most=MAX_COUNT)
    higher_max_steps: int = bounded(HigherTraining.max_steps, least=1, most=MAX_COUNT)
    checkpoint_seconds: float = bounded(30.0, least=0.0)
    #: The domain randomisation's ranges as ``axis=low:high,...`` (``mazesim train --randomise``;
    #: :func:`train` then draws the robots with a :data:`RobotDraw`), empty for the seed robot.
    randomise: str = ""
    #: The door sub-tasks' phases also count the distance driven (``mazesim train
    #: --door-distance``; :data:`mazesim.learn.subtasks.DISTANCE_PHASES`).
    door_distance: bool = False
    #: Corridors and Corners drives forward where no sensor sees a wall (``mazesim train
    #: --blind-forward``; :func:`mazesim.learn.lower.drive_on_when_blind`).
    blind_forward: bool = False
    #: There, it holds its heading on the maze's grid (``mazesim train --hold-heading``;
    #: the core's ``navigator::heading_hold``), in the lower level's training and the higher
    #: level's.
    hold_heading: bool = False

    def __post_init__(self) -> None:
        check_settings(self)

    def lower(self) -> LowerSettings:
        """The lower-level stage's settings."""
        return LowerSettings(
            num_envs=self.envs,
            total_steps=self.steps,
            seed=self.seed,
            maze_pool=self.maze_pool,
            door_distance=self.door_distance,
            blind_forward=self.blind_forward,
            hold_heading=self.hold_heading,
        )

    def higher(self) -> HigherTraining:
        """The higher-level stage's settings."""
        return HigherTraining(
            episodes_per_world=self.higher_episodes,
            envs_per_world=self.higher_envs,
            max_steps=self.higher_max_steps,
            seed=self.seed,
        )

    def as_dict(self) -> dict[str, Any]:
        """The settings as a navigator's metadata records them: a run without randomisation has
        no ``randomise`` key, and one without ``door_distance``, ``blind_forward`` or
        ``hold_heading`` not those, as before the fields existed."""
        values = asdict(self)
        for name in ("randomise", "door_distance", "blind_forward", "hold_heading"):
            if not values[name]:
                values.pop(name)
        return values

    def identity(self) -> dict[str, Any]:
        """What must match for a checkpoint to be continued (not the checkpoint interval)."""
        values = self.as_dict()
        values.pop("checkpoint_seconds")
        return values


def command_line_fields() -> list[Field[Any]]:
    """The fields of :class:`TrainSettings` that ``mazesim train`` offers as options, in order."""
    return [f for f in fields(TrainSettings) if "help" in f.metadata]


def _round_summary(stats: RoundStats) -> dict[str, Any]:
    return {
        "round": stats.round_index,
        "epsilon": round(stats.epsilon, 6),
        "door_success": [round(stats.door_success_rate(k), 4) for k in (1, 2, 3)],
        "door_cut": stats.door_cut[1:],
        "corridor_speed": round(stats.corridor_speed, 4),
        "contact_share": round(stats.contact_share, 6),
    }


#: Reports progress as ``progress(stage, done, total)``: stage ``"lower"`` counts rounds,
#: ``"higher"`` and ``"flat"`` count episodes or steps.
ProgressFn = Callable[[str, int, int], None]
#: Called after each lower-level round with the tables, the next round and the history so far;
#: returns True to stop there (as if interrupted).
CheckpointFn = Callable[[LowerTables, int, list[dict[str, Any]]], bool]
#: Draws the robots of a randomised run as ``draw(round_index, count)``: the lower level's
#: robots for each round (``round_index`` from 0), and the higher level's once, with
#: ``round_index`` the lower level's number of rounds. The same arguments must give the same
#: robots (a resumed run draws its rounds again). A draw of several base profiles gives a
#: :class:`~mazesim.learn.fleet.Fleet`; the higher level then trains with its ``higher`` robots.
RobotDraw = Callable[[int, int], Union[RobotChoice, Fleet]]


def _robots_of(robot: RobotChoice | RobotDraw, round_index: int, count: int) -> RobotChoice | Fleet:
    if callable(robot):
        return robot(round_index, count)
    return robot


def _higher_robots(robot: RobotChoice | RobotDraw, round_index: int, count: int) -> RobotChoice:
    robots = _robots_of(robot, round_index, count)
    return robots.higher if isinstance(robots, Fleet) else robots


@dataclass
class TrainingRun:
    """What :func:`run_training` learned and measured."""

    tables: LowerTables
    level: HigherLevel
    history: list[dict[str, Any]]
    round_stats: list[RoundStats]
    higher_results: list[EpisodeResult]
    lower_seconds: float
    higher_seconds: float


def run_training(
    lower: LowerSettings,
    higher: HigherTraining,
    world: World,
    *,
    tables: LowerTables | None = None,
    next_round: int = 0,
    history: Sequence[dict[str, Any]] = (),
    threads: int = 0,
    progress: ProgressFn | None = None,
    checkpoint: CheckpointFn | None = None,
    robot: RobotChoice | RobotDraw = "seed",
    curve: CurveFn | None = None,
) -> TrainingRun | None:
    """The training pipeline: the lower level round by round, then the higher level on ``world``.

    It writes and prints nothing; ``checkpoint`` and ``progress`` are how callers see it go.

    Args:
        lower: The lower-level stage's settings.
        higher: The higher-level stage's settings.
        world: The world the higher level learns (a cell maze with a goal).
        tables: Tables to continue from (a resumed run), fresh ones by default.
        next_round: The first lower-level round to run.
        history: The round summaries of the rounds already run.
        threads: Worker threads of the simulator (0: one per core); results do not depend on it.
        progress: See :data:`ProgressFn`.
        checkpoint: See :data:`CheckpointFn`.
        robot: The robots of both stages (:data:`mazesim.batch.RobotChoice`: a profile's name,
            a :class:`~mazesim.RobotProfile`, or one per robot), handed to the batches as given;
            or a :data:`RobotDraw` giving fresh robots to each lower-level round and to the
            higher level (domain randomisation).
        curve: See :data:`CurveFn`.

    Returns:
        The run, or None when ``checkpoint`` stopped it.
    """
    tables = tables if tables is not None else LowerTables.zeros(lower.door_distance)
    summaries = list(history)
    stats_seen: list[RoundStats] = []
    started = time.perf_counter()
    rounds = lower.rounds
    if curve is not None:
        for summary in summaries:
            curve("lower", lower_point(summary, lower))
    if next_round < rounds:
        draws = callable(robot)
        first = _robots_of(robot, next_round, lower.num_envs)
        trainer = LowerTrainer(lower, tables, threads=threads, robot=first)
        for round_index in range(next_round, rounds):
            if draws and round_index > next_round:
                trainer.use_robots(_robots_of(robot, round_index, lower.num_envs))
            stats = trainer.run_round(round_index)
            stats_seen.append(stats)
            summaries.append(_round_summary(stats))
            if curve is not None:
                curve("lower", lower_point(summaries[-1], lower))
            if progress is not None:
                progress("lower", round_index + 1, rounds)
            stop = checkpoint is not None and checkpoint(trainer.tables, round_index + 1, summaries)
            if stop and round_index + 1 < rounds:
                return None
        tables = trainer.tables
    if lower.blind_forward or lower.hold_heading:
        drive_on_when_blind(tables.q)
    lower_seconds = time.perf_counter() - started
    started = time.perf_counter()

    level, results = train_higher(
        tables.q,
        [world],
        higher,
        threads=threads,
        progress=episode_progress("higher", progress, curve),
        robot=_higher_robots(robot, rounds, higher.envs_per_world),
        hold_heading=lower.hold_heading,
    )
    return TrainingRun(
        tables=tables,
        level=level,
        history=summaries,
        round_stats=stats_seen,
        higher_results=results,
        lower_seconds=lower_seconds,
        higher_seconds=time.perf_counter() - started,
    )


def navigator_world(name: str) -> World:
    """Loads the world a navigator is to learn (a built-in name or a world file).

    Raises:
        InvalidArgumentError: The navigator cannot learn it (no cell maze, no goal, a goal out of
            reach, no checkpoints: :func:`mazesim.episodes.learning_problems`); the message says
            what to change.
        UnknownNameError, WorldFormatError: The world cannot be loaded.
    """
    world = load_world(name)
    refuse_unlearnable(world, name)
    return world


def refuse_unlearnable(world: World, name: str, verb: str = "learn") -> None:
    """Refuses a world the navigator cannot learn or drive, loaded from ``name`` (a built-in
    name or a world file): one message for ``mazesim train``, ``eval --world`` and ``demo
    --controller hrl``, naming the world, its file and what to change. A start pose in a wall is
    refused first, as every command refuses it (:func:`mazesim.maze.refuse_blocked_start`).

    Raises:
        InvalidArgumentError: :func:`mazesim.episodes.learning_problems` finds a problem.
    """
    refuse_blocked_start(world, name)
    problems = learning_problems(world, show_command=shell_command("mazesim", "show", name))
    if problems:
        raise InvalidArgumentError(
            f"the navigator cannot {verb} world {world_source(world, name)}: " + "; ".join(problems)
        )


def world_file(name: str) -> str | None:
    """The absolute path of the world file ``name`` names, or None for a built-in world (a
    saved navigator keeps it, so that ``mazesim eval --policy`` finds the world again)."""
    if name in builtin_world_names():
        return None
    return str(Path(name).resolve())


def _machine() -> dict[str, Any]:
    return {
        "cpu_count": os.cpu_count(),
        "load_average": list(os.getloadavg()) if hasattr(os, "getloadavg") else None,
    }


class RunWriter(Protocol):
    """Where :func:`train` writes a run (:class:`mazesim.learn.checkpoint.RunFolder` writes a
    folder); ``settings`` are the run's :meth:`TrainSettings.identity`."""

    def start(self, settings: dict[str, Any]) -> Checkpoint | None:
        """Prepares for the run; returns the checkpoint to continue from (None: start afresh)."""
        ...

    def save(self, settings: dict[str, Any], checkpoint: Checkpoint) -> None:
        """Keeps a checkpoint of the run."""
        ...

    def finish(self, policy: TrainedPolicy) -> None:
        """Keeps the trained navigator."""
        ...


def train(
    settings: TrainSettings,
    checkpoint: RunWriter | None = None,
    progress: ProgressFn | None = None,
    threads: int = 0,
    stop_after_rounds: int | None = None,
    robot: RobotChoice | RobotDraw = "seed",
    curve: CurveFn | None = None,
) -> TrainedPolicy | None:
    """Trains a navigator (:func:`run_training`) from ``settings``.

    It writes and prints nothing itself: checkpoints, the run to continue and the trained
    navigator go through ``checkpoint``.

    Args:
        settings: The run's settings.
        checkpoint: Where the run is written (``mazesim train``:
            :class:`mazesim.learn.checkpoint.RunFolder`, which also says whether to resume);
            ``None``: nowhere.
        progress: See :data:`ProgressFn`.
        threads: Worker threads of the simulator (0: one per core); results do not depend on it.
        stop_after_rounds: Stop (as if interrupted) after this many lower-level rounds in this
            call, after a checkpoint; for tests.
        robot: The robots (see :func:`run_training`); a :data:`RobotDraw` exactly when
            ``settings.randomise`` names its ranges.
        curve: Receives the learning curve (:data:`CurveFn`).

    Returns:
        The trained navigator, or None when stopped early by ``stop_after_rounds``.

    Raises:
        InvalidArgumentError: ``settings.randomise`` without a :data:`RobotDraw` or the other
            way round.
        PolicyFormatError: The writer has no usable checkpoint to resume, or one it should not
            continue (see :meth:`mazesim.learn.checkpoint.RunFolder.start`).
        UnknownNameError, WorldFormatError: The world cannot be loaded.
    """
    if bool(settings.randomise) != callable(robot):
        raise InvalidArgumentError(
            "expected a robot draw exactly with randomisation ranges in the settings, found "
            f"randomise={_shown(settings.randomise)} and robot={_shown(robot)}"
        )
    world = navigator_world(settings.world)
    lower_settings = settings.lower()
    saved = None if checkpoint is None else checkpoint.start(settings.identity())
    if saved is not None:
        tables, next_round = saved.tables, saved.next_round
        history, lower_seconds = saved.history, saved.lower_seconds
    else:
        tables, next_round = LowerTables.zeros(settings.door_distance), 0
        history, lower_seconds = [], 0.0

    rounds = lower_settings.rounds
    started = time.perf_counter()
    clock = {"saved": started, "done": 0}

    def save(tables: LowerTables, reached: int, summaries: list[dict[str, Any]]) -> bool:
        clock["done"] += 1
        now = time.perf_counter()
        stopping = stop_after_rounds is not None and clock["done"] >= stop_after_rounds
        due = reached == rounds or stopping or now - clock["saved"] >= settings.checkpoint_seconds
        if due and checkpoint is not None:
            elapsed = lower_seconds + now - started
            checkpoint.save(settings.identity(), Checkpoint(tables, reached, summaries, elapsed))
            clock["saved"] = now
        return stopping

    run = run_training(
        lower_settings,
        settings.higher(),
        world,
        tables=tables,
        next_round=next_round,
        history=history,
        threads=threads,
        progress=progress,
        checkpoint=save,
        robot=robot,
        curve=curve,
    )
    if run is None:
        return None
    results = run.higher_results
    shortest = shortest_path_steps(world)
    training: dict[str, Any] = {
        "settings": settings.as_dict(),
        "lower": lower_settings.as_dict(),
        "higher": asdict(settings.higher()),
        "lower_env_steps": rounds * lower_settings.num_envs * lower_settings.round_steps,
        "higher_env_steps": summarise(results, [shortest]).env_steps,
        "lower_seconds": round(lower_seconds + run.lower_seconds, 1),
        "higher_seconds": round(run.higher_seconds, 1),
        "higher_success_last_100": summarise(results[-100:], [shortest]).success_rate,
        "shortest_path_steps": shortest,
        "history": run.history,
        **_machine(),
    }
    policy = TrainedPolicy(
        kind="hierarchical",
        world_name=world.name,
        world_sha256=world_hash(world),
        world_file=world_file(settings.world),
        checkpoint_ids=run.level.checkpoint_ids[0],
        lower_q=run.tables.q,
        higher_q=run.level.q[0],
        training=training,
    )
    if checkpoint is not None:
        checkpoint.finish(policy)
    return policy


def train_flat_policy(
    settings: TrainSettings,
    checkpoint: RunWriter | None = None,
    progress: ProgressFn | None = None,
    threads: int = 0,
    curve: CurveFn | None = None,
) -> TrainedPolicy:
    """Trains the flat baseline on ``settings.world`` for ``settings.steps`` env-steps
    (:mod:`mazesim.learn.baseline`) and hands it to ``checkpoint``'s
    :meth:`~RunWriter.finish` (``None``: it is only returned); ``curve`` receives ``("flat",
    {"index": env-steps done, "goal_rate": share of the last episodes that reached the
    goal})``."""
    world = navigator_world(settings.world)
    started = time.perf_counter()

    q, outcomes = train_flat(
        world,
        settings.steps,
        num_envs=settings.envs,
        seed=settings.seed,
        threads=threads,
        progress=episode_progress("flat", progress, curve),
    )
    last = outcomes[-100:]
    policy = TrainedPolicy(
        kind="flat",
        world_name=world.name,
        world_sha256=world_hash(world),
        world_file=world_file(settings.world),
        checkpoint_ids=checkpoint_ids(world),
        flat_q=q,
        training={
            "settings": settings.as_dict(),
            "env_steps": settings.steps,
            "seconds": round(time.perf_counter() - started, 1),
            "episodes": len(outcomes),
            "success_last_100": sum(last) / max(1, len(last)),
            **_machine(),
        },
    )
    if checkpoint is not None:
        checkpoint.finish(policy)
    return policy
