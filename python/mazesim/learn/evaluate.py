"""Evaluating a navigator: success, collisions, steps against the shortest path, decisions, and
what the report's pictures (trajectories, Fig. 4.6 / 4.8) and terminal trace (Fig. 4.7) are
drawn from. It writes and prints nothing: :mod:`mazesim.learn.report` turns a summary and a
trace into text, :mod:`mazesim.learn.figures` draws the paths, and ``mazesim eval`` writes them.

An evaluation runs greedy episodes in a world with sensor noise and the start jitter of
:class:`mazesim.episodes.StartJitter` (2 cm, 10 degrees). In the world the navigator's
higher level learned, it uses that table; in any other world (a file, or the unseen generated
mazes of ``--world random``) the lower-level tables are kept and only the higher level is trained
there first, with at most :data:`ADAPT_EPISODES` episodes per maze: the transfer test.

Measures (:class:`Summary`): the share of episodes that reached the goal; bumps (wall contacts
the simulator counts) per episode, and the share of episodes without any; the control steps of
the episodes that arrived, and their ratio to the steps of the shortest path at cruise speed
(:func:`mazesim.episodes.shortest_path_steps`); and which sub-task the higher level chose
at each checkpoint event.

With ``spread``, :func:`evaluate_navigator` hands the episodes out in chunks
(:mod:`mazesim.learn.chunks`; ``mazesim eval --address`` passes Ray's
:func:`mazesim.distributed.evaluate_episodes`): the higher level of an unseen world is trained
once, here, and its tables shipped with the chunks; every episode ends as it would here, so the
summary is the same spread or not.

Recording the first episodes frame by frame (for the replay and videos) takes a ``recorder``
factory from the caller (:func:`mazesim.replay.navigator.recording`), so this module needs
nothing of the viewers.
"""

from __future__ import annotations

import dataclasses
import math
from collections import Counter
from collections.abc import Callable, Mapping, Sequence
from dataclasses import asdict, dataclass, field
from typing import Any, Protocol

import numpy as np
import numpy.typing as npt

from mazesim._core import World, generate_maze
from mazesim._seeding import stream_seeds
from mazesim.actions import ACTION_CODES, ACTIONS
from mazesim.batch import RobotChoice
from mazesim.episodes import (
    EVENT_SOURCES,
    MAX_STEPS,
    EpisodeBatch,
    EpisodeResult,
    StartJitter,
    run_episodes,
    shortest_path_steps,
)
from mazesim.errors import InvalidArgumentError
from mazesim.learn.chunks import NavigatorEpisodes
from mazesim.learn.discretise import format_levels
from mazesim.learn.higher import HigherLevel
from mazesim.learn.higher_training import HigherTraining, train_higher
from mazesim.learn.policy import HierarchicalPolicy, StepRecord
from mazesim.learn.stretches import run_navigator_episodes, stretches_apply
from mazesim.learn.subtasks import CONTROL_STEP_MS, SUBTASK_CODES, SUBTASK_NAMES
from mazesim.learn.tables import TrainedPolicy
from mazesim.maze import world_hash

__all__ = [
    "ADAPTATION",
    "ADAPT_EPISODES",
    "EvalSettings",
    "Evaluation",
    "Report",
    "Summary",
    "evaluate",
    "evaluate_navigator",
    "navigator_for",
    "summarise",
    "unseen_mazes",
]

#: How the higher level trains in worlds it has not seen: at most 200 episodes per maze, 8
#: robots per maze (the seed is the evaluation's).
ADAPTATION = HigherTraining(episodes_per_world=200, envs_per_world=8)
#: Episodes the higher level may train in a world it has not seen, per maze.
ADAPT_EPISODES = ADAPTATION.episodes_per_world
#: Robots stepped side by side in an evaluation (at most).
EVALUATION_ENVS = 500


@dataclass
class Summary:
    """What an evaluation measured."""

    episodes: int
    success_rate: float
    mean_collisions: float
    mean_steps: float | None
    mean_path_ratio: float | None
    collision_free_rate: float
    events: str
    decisions: dict[str, dict[str, int]] = field(default_factory=dict)
    world_success: list[float] = field(default_factory=list)
    #: Mean steps over every episode, a failed one counted at its limit (a sweep's ``mean_steps``).
    mean_steps_all: float = 0.0

    def as_json(self) -> dict[str, Any]:
        """The summary as the ``--json`` output's values."""
        values = asdict(self)
        for private in ("decisions", "events", "world_success", "mean_steps_all"):
            values.pop(private)
        return values


@dataclass
class Evaluation:
    """An evaluation's summary, its episodes, and what was recorded for pictures and traces."""

    summary: Summary
    results: list[EpisodeResult]
    paths: dict[int, npt.NDArray[np.float64]] = field(default_factory=dict)
    marks: dict[int, list[tuple[float, float, int, int]]] = field(default_factory=dict)
    trace: list[str] = field(default_factory=list)
    run: Any = None


@dataclass(frozen=True)
class EvalSettings:
    """What ``mazesim eval`` measures: its options are these fields (the defaults are the only
    ones, the help texts are the metadata's)."""

    policy: str | None = field(
        default=None,
        metadata={
            "help": "folder of a saved navigator, or 'randomised': the one shipped trained with "
            "domain randomisation",
            "metavar": "DIR",
            "default_text": "the one shipped for seed-maze",
        },
    )
    world: str | None = field(
        default=None,
        metadata={
            "help": "a built-in world, a world file, or 'random' for unseen generated mazes",
            "metavar": "NAME|PATH|random",
            "default_text": "the navigator's world",
        },
    )
    episodes: int = field(
        default=200,
        metadata={
            "help": "evaluation episodes (with 'random': spread over --mazes mazes)",
            "metavar": "N",
        },
    )
    mazes: int = field(
        default=100, metadata={"help": "unseen mazes of --world random", "metavar": "M"}
    )
    seed: int = field(
        default=0,
        metadata={
            "help": "seed of the episodes' start jitter and sensor noise, and of the random mazes",
            "metavar": "S",
        },
    )
    events: str = field(
        default="both",
        metadata={
            "help": "checkpoint events from the simulator's ground truth, from the robust barcode "
            "decoder, or both, reported side by side",
            "choices": (*EVENT_SOURCES, "both"),
        },
    )
    max_steps: int = field(
        default=MAX_STEPS,
        metadata={
            "help": "control steps (64 ms) after which an episode fails",
            "metavar": "N",
        },
    )

    @property
    def sources(self) -> list[str]:
        """The event sources to evaluate with, in order."""
        return list(EVENT_SOURCES) if self.events == "both" else [self.events]


def unseen_mazes(count: int, seed: int) -> list[World]:
    """``count`` generated 5 x 5 perfect mazes for testing; their seeds derive from ``seed`` on a
    stream no training run uses."""
    maze_seeds = stream_seeds(seed, "evaluate/mazes", count)
    return [generate_maze(5, 5, seed=int(maze_seed)) for maze_seed in maze_seeds]


def navigator_for(
    policy: TrainedPolicy,
    worlds: Sequence[World],
    seed: int = 0,
    threads: int = 0,
    progress: Callable[[str, int, int], None] | None = None,
    robot: RobotChoice = "seed",
) -> tuple[HigherLevel, bool]:
    """The higher level to drive ``worlds`` with: the policy's own when it is the world it
    learned, else one trained there for :data:`ADAPT_EPISODES` episodes per world.

    Args:
        policy: The navigator.
        worlds: The worlds to drive.
        seed: Seed of the adaptation's episodes and exploration.
        threads: Worker threads of the batch.
        progress: Called as ``progress("adapt", episodes_done, episodes_total)``.
        robot: The robots of the adaptation (:data:`mazesim.batch.RobotChoice`).

    Returns:
        The higher level (one table per world) and whether it was trained here.
    """
    if policy.kind != "hierarchical" or policy.lower_q is None or policy.higher_q is None:
        raise InvalidArgumentError("expected a hierarchical navigator")
    if len(worlds) == 1 and world_hash(worlds[0]) == policy.world_sha256:
        level = HigherLevel([policy.checkpoint_ids], q=policy.higher_q[None])
        return level, False
    settings = dataclasses.replace(ADAPTATION, seed=seed)

    def adapting(done: int, total: int, recent: float) -> None:
        if progress is not None:
            progress("adapt", done, total)

    level, _ = train_higher(
        policy.lower_q, worlds, settings, threads=threads, progress=adapting, robot=robot
    )
    return level, True


def summarise(results: list[EpisodeResult], shortest: Sequence[float], events: str) -> Summary:
    """The one result type of an evaluation: what ``results`` measured.

    Args:
        results: The episodes.
        shortest: The shortest path's steps of each world, for the path ratio.
        events: Where the checkpoint events came from.
    """
    arrived = [r for r in results if r.arrived]
    count = len(results)
    decisions: dict[str, Counter[str]] = {}
    for result in results:
        for event, option in result.decisions:
            key = f"{'+' if event > 0 else '-'}{abs(event)}"
            decisions.setdefault(key, Counter())[SUBTASK_CODES[option]] += 1
    worlds = max((r.world for r in results), default=-1) + 1
    world_success = [
        float(np.mean([r.arrived for r in results if r.world == world])) for world in range(worlds)
    ]
    return Summary(
        world_success=world_success,
        episodes=count,
        success_rate=len(arrived) / count if count else 0.0,
        mean_collisions=float(np.mean([r.bumps for r in results])) if count else 0.0,
        mean_steps=float(np.mean([r.steps for r in arrived])) if arrived else None,
        mean_steps_all=float(np.mean([r.steps for r in results])) if count else 0.0,
        mean_path_ratio=(
            float(np.mean([r.steps / shortest[r.world] for r in arrived])) if arrived else None
        ),
        collision_free_rate=(sum(1 for r in results if r.bumps == 0) / count if count else 0.0),
        events=events,
        decisions={
            key: dict(sorted(counts.items()))
            for key, counts in sorted(
                decisions.items(), key=lambda item: (abs(int(item[0])), item[0][0] == "-")
            )
        },
    )


NavigatorFactory = Callable[[npt.NDArray[np.int64]], Any]


class RecorderFactory(Protocol):
    """Builds a recording navigator from the batch and the navigator it watches.

    What it builds is a navigator itself, with ``after_step(arrived, out_of_time)`` and
    ``run(controller, seed)`` (the recorded run); it records the first :attr:`episodes` episodes.
    """

    episodes: int

    def __call__(self, nav: EpisodeBatch, navigator: Any) -> Any: ...


#: Runs an evaluation's chunks (``chunk(first, count)`` -> per-episode arrays) for ``episodes``
#: episodes and joins their arrays in episode order.
Spreader = Callable[[Callable[[int, int], Mapping[str, Any]], int], Mapping[str, Any]]


def evaluate(
    make_navigator: NavigatorFactory,
    worlds: Sequence[World],
    episodes_per_world: int,
    seed: int = 0,
    events: str = "truth",
    jitter: StartJitter | None = None,
    max_steps: int = MAX_STEPS,
    record_paths: int = 0,
    trace: bool = False,
    threads: int = 0,
    recorder: RecorderFactory | None = None,
    controller: str = "hrl",
    progress: Callable[[str, int, int], None] | None = None,
    multi_step: bool = True,
    robot: RobotChoice = "seed",
) -> Evaluation:
    """Runs greedy episodes of a navigator and measures them.

    With ``multi_step`` (the default), a greedy
    :class:`~mazesim.learn.policy.HierarchicalPolicy` with events from the ground truth runs in
    the core's multi-step call from one checkpoint event to the next, door sub-tasks included
    (:func:`mazesim.learn.stretches.run_navigator_episodes`); the episodes to record (paths,
    trace, replay) then run once more, one step at a time. Any other navigator (a flat one, one
    that wraps ``act``), robots of different motor limits and decoder events run one step at a
    time. The results are the same either way; the multi-step call is the faster (see
    ``docs/performance.md``).

    Args:
        make_navigator: Builds the navigator of the robots from their world numbers (a
            :class:`~mazesim.learn.policy.HierarchicalPolicy` or a
            :class:`~mazesim.learn.baseline.FlatNavigator`).
        worlds: The worlds.
        episodes_per_world: Episodes in each world.
        seed: Seed of the episodes' start jitter and sensor noise.
        events: ``"truth"`` or ``"robust"`` (checkpoint events from the decoder).
        jitter: Start jitter; the default :class:`StartJitter`.
        max_steps: Control steps after which an episode fails.
        record_paths: Record the trajectories of the first this many episodes of world 0.
        trace: Record the per-step trace of episode 0.
        threads: Worker threads of the batch.
        recorder: Records the first episodes frame by frame (:attr:`Evaluation.run`, for the
            replay and videos); see :data:`RecorderFactory`.
        controller: The controller's name in the recorded run.
        progress: Called as ``progress("evaluate", episodes_done, episodes_total)``.
        multi_step: Use the multi-step call where it applies (the default); ``False``: one step
            at a time.
        robot: The robots (:data:`mazesim.batch.RobotChoice`), handed to the batch as given.
    """
    per_world = max(1, min(episodes_per_world, EVALUATION_ENVS // max(1, len(worlds))))
    world_of_env = np.repeat(np.arange(len(worlds)), per_world)
    nav = EpisodeBatch(
        worlds,
        world_of_env,
        seed=seed,
        jitter=jitter,
        max_steps=max_steps,
        events=events,
        threads=threads,
        robot=robot,
    )
    navigator = make_navigator(world_of_env)
    total = episodes_per_world * len(worlds)
    finished = [0]
    if progress is not None:
        progress("evaluate", 0, total)

    def on_end(robots: npt.NDArray[np.int64], arrived: npt.NDArray[np.bool_]) -> None:
        finished[0] += robots.size
        if progress is not None:
            progress("evaluate", min(finished[0], total), total)

    shortest = [shortest_path_steps(world) for world in worlds]
    if multi_step and stretches_apply(nav, navigator):
        results = run_navigator_episodes(nav, navigator, episodes_per_world, on_end)
        evaluation = Evaluation(summarise(results, shortest, events), results)
        options = dict(
            seed=seed,
            events=events,
            jitter=jitter,
            max_steps=max_steps,
            record_paths=record_paths,
            trace=trace,
            threads=threads,
            recorder=recorder,
            controller=controller,
            robot=robot,
        )
        _record_here(evaluation, make_navigator, worlds, episodes_per_world, options)
        return evaluation
    recording = None if recorder is None else recorder(nav, navigator)
    evaluation = Evaluation(summary=summarise([], [1.0], events), results=[])
    paths: dict[int, list[tuple[float, float]]] = {}
    ended: set[int] = set()
    marks = evaluation.marks
    lines = evaluation.trace

    def watch(
        batch: EpisodeBatch,
        actions: npt.NDArray[np.int64],
        arrived: npt.NDArray[np.bool_],
        out_of_time: npt.NDArray[np.bool_],
    ) -> None:
        if recording is not None:
            recording.after_step(arrived, out_of_time)
        if not record_paths and not trace:
            return
        record = navigator.record
        # A robot left without an episode is still stepped: record its episode's steps only.
        running = ~np.isin(batch.episode, list(ended))
        for env in np.flatnonzero(running & (batch.episode < record_paths)):
            episode = int(batch.episode[env])
            x, y, _ = (float(v) for v in batch.poses[env])
            paths.setdefault(episode, []).append((x, y))
            if record.chosen[env] >= 0:
                marks.setdefault(episode, []).append(
                    (x, y, int(record.event[env]), int(record.chosen[env]))
                )
        if trace:
            for env in np.flatnonzero(running & (batch.episode == 0)):
                lines.append(_trace_line(batch, record, int(env)))
                if arrived[env]:
                    lines.append(f"# goal reached after {int(batch.episode_steps[env])} steps")
                elif out_of_time[env]:
                    lines.append(f"# out of time after {int(batch.episode_steps[env])} steps")
        ended.update(int(episode) for episode in batch.episode[running & (arrived | out_of_time)])

    def decisions_of() -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]]:
        robots = np.flatnonzero(navigator.record.chosen >= 0)
        return robots, navigator.record.chosen[robots]

    results = run_episodes(
        nav,
        navigator if recording is None else recording,
        episodes_per_world,
        watch,
        on_end,
        decisions_of,
    )
    evaluation.summary = summarise(results, shortest, events)
    evaluation.results = results
    evaluation.paths = {k: np.array(v) for k, v in paths.items()}
    if recording is not None:
        evaluation.run = recording.run(controller, seed)
    return evaluation


@dataclass
class Report:
    """What :func:`evaluate_navigator` measured."""

    summaries: dict[str, Summary]
    evaluations: dict[str, Evaluation]
    adapted: bool
    run: Any = None


def evaluate_navigator(
    policy: TrainedPolicy,
    worlds: Sequence[World],
    episodes_per_world: int,
    seed: int = 0,
    sources: Sequence[str] = ("truth",),
    max_steps: int = MAX_STEPS,
    trace: bool = False,
    plot_episodes: int = 0,
    threads: int = 0,
    spread: Spreader | None = None,
    recorder: RecorderFactory | None = None,
    progress: Callable[[str, int, int], None] | None = None,
    multi_step: bool = True,
    robot: RobotChoice = "seed",
) -> Report:
    """Evaluates a saved navigator with checkpoint events from each source (it writes nothing).

    Args:
        trace: Record the per-step trace of the first source's episode 0
            (:attr:`Evaluation.trace`; :func:`mazesim.learn.report.trace_text` makes it a file).
        plot_episodes: Record the paths of the first source's first this many episodes of the
            first world (:attr:`Evaluation.paths`, for :mod:`mazesim.learn.figures`).
        spread: ``None``: run every episode in this process; else the function that runs the
            evaluation's chunks (:data:`Spreader`, e.g. Ray's
            :func:`mazesim.distributed.evaluate_episodes`). The trace, the picture's and the
            recorded episodes are run here as well.
        recorder: Records the first episodes of the first source frame by frame
            (:attr:`Report.run`; see :data:`RecorderFactory`).
        progress: Called as ``progress(stage, done, total)``: ``"adapt"`` while the higher level
            learns unseen worlds, then ``"evaluate"`` (``"evaluate robust"`` for the second
            source) over the episodes.
        multi_step: Run the episodes in the core's multi-step call where it applies (the
            default; see :func:`evaluate`); ``False``: every episode one step at a time. The
            results are the same.
        robot: The robots of the evaluation and of the higher level's adaptation
            (:data:`mazesim.batch.RobotChoice`), handed to the batches as given; the seed
            robot's only with ``spread``.

    Raises:
        PolicyFormatError: A flat navigator asked to drive a world it did not learn.
        MissingDependencyError: ``spread`` needs a package that is not installed.
    """
    if spread is not None and not (isinstance(robot, str) and robot == "seed"):
        raise InvalidArgumentError(
            f"expected the seed robot for an evaluation spread in chunks, found {robot!r}"
        )
    adapted = False
    make_navigator: NavigatorFactory
    if policy.kind == "flat":
        from mazesim.learn.baseline import FlatNavigator

        if len(worlds) != 1 or policy.flat_q is None:
            raise InvalidArgumentError("the flat baseline drives the one world it learned")
        policy.check_world(worlds[0])
        flat_q = policy.flat_q

        def make_navigator(world_of_env: npt.NDArray[np.int64]) -> Any:
            return FlatNavigator(flat_q, policy.checkpoint_ids, world_of_env.size)

    else:
        level, adapted = navigator_for(
            policy, worlds, seed=seed, threads=threads, progress=progress, robot=robot
        )
        lower_q = policy.lower_q
        assert lower_q is not None

        def make_navigator(world_of_env: npt.NDArray[np.int64]) -> Any:
            return HierarchicalPolicy(lower_q, level, world_of_env)

    summaries: dict[str, Summary] = {}
    evaluations: dict[str, Evaluation] = {}
    level_shipped = None if policy.kind == "flat" else level

    def run(*args: Any, **options: Any) -> Evaluation:
        if spread is None:
            return evaluate(*args, **options)
        return _evaluate_spread(spread, policy, level_shipped, *args, **options)

    for place, source in enumerate(sources):
        first = place == 0
        evaluation = run(
            make_navigator,
            worlds,
            episodes_per_world,
            seed=seed,
            events=source,
            max_steps=max_steps,
            record_paths=plot_episodes if first else 0,
            trace=first and trace,
            threads=threads,
            recorder=recorder if first else None,
            controller=policy.kind,
            progress=_staged(progress, "evaluate" if first else f"evaluate {source}"),
            multi_step=multi_step,
            robot=robot,
        )
        summaries[source] = evaluation.summary
        evaluations[source] = evaluation
    return Report(summaries, evaluations, adapted, evaluations[sources[0]].run)


def _staged(
    progress: Callable[[str, int, int], None] | None, stage: str
) -> Callable[[str, int, int], None] | None:
    """``progress`` reporting under the name ``stage``."""
    if progress is None:
        return None
    report = progress
    return lambda _, done, total: report(stage, done, total)


def _evaluate_spread(
    spread: Spreader,
    policy: TrainedPolicy,
    level: HigherLevel | None,
    make_navigator: NavigatorFactory,
    worlds: Sequence[World],
    episodes_per_world: int,
    **options: Any,
) -> Evaluation:
    """:func:`evaluate` with its episodes spread in chunks by ``spread``; the episodes to record
    for the trace, the picture and the replay run here as well."""

    if level is None:
        ids: list[list[int]] = [list(policy.checkpoint_ids)]
    else:
        ids = level.checkpoint_ids
    chunks = NavigatorEpisodes(
        kind=policy.kind,
        world_tomls=tuple(world.to_toml() for world in worlds),
        episodes_per_world=episodes_per_world,
        seed=options["seed"],
        events=options["events"],
        max_steps=options["max_steps"],
        checkpoint_ids=tuple(tuple(world_ids) for world_ids in ids),
        lower_q=policy.lower_q if level is not None else None,
        higher_q=level.q if level is not None else None,
        flat_q=policy.flat_q if level is None else None,
    )
    progress = options.pop("progress")
    results = chunks.results(spread(chunks, chunks.episodes))
    if progress is not None:
        progress("evaluate", chunks.episodes, chunks.episodes)
    shortest = [shortest_path_steps(world) for world in worlds]
    evaluation = Evaluation(summarise(results, shortest, options["events"]), results)
    _record_here(evaluation, make_navigator, worlds, episodes_per_world, options)
    return evaluation


def _record_here(
    evaluation: Evaluation,
    make_navigator: NavigatorFactory,
    worlds: Sequence[World],
    episodes_per_world: int,
    options: dict[str, Any],
) -> None:
    """Runs the first episodes of the first world again, one step at a time, for the paths,
    the trace and the recorded run that ``options`` ask for (an episode ends the same way
    whatever runs it), and puts them into ``evaluation``."""
    recorded = max(options["record_paths"], 1 if options["trace"] else 0)
    if options["recorder"] is not None:
        recorded = max(recorded, options["recorder"].episodes)
    if not recorded:
        return
    options = {**options, "multi_step": False}
    local = evaluate(make_navigator, worlds[:1], min(episodes_per_world, recorded), **options)
    evaluation.paths, evaluation.marks, evaluation.trace = local.paths, local.marks, local.trace
    evaluation.run = local.run


def _trace_line(batch: EpisodeBatch, record: StepRecord, env: int) -> str:
    """One step of the trace, in the report's style (Fig. 4.7): what the robot sensed and did,
    after a line for the checkpoint event and decision that came first, if any."""
    step = int(batch.episode_steps[env])
    x, y, yaw = (float(v) for v in batch.poses[env])
    action = ACTION_CODES[int(record.action[env])]
    subtask = int(record.subtask[env])
    before = []
    if record.ended[env]:
        before.append("      door sub-task ended -> 'Corridors and Corners'")
    event = int(record.event[env])
    if event:
        direction = "arrival" if event > 0 else "departure"
        note = f"      checkpoint {event:+d} ({direction})"
        chosen = int(record.chosen[env])
        if chosen >= 0:
            note += f" -> higher level: {SUBTASK_NAMES[chosen]!r}"
        before.append(note)
    line = (
        f"{step:5d} {step * CONTROL_STEP_MS / 1000.0:7.2f}  {x:6.3f} {y:6.3f} "
        f"{math.degrees(yaw):6.1f}  {format_levels(record.levels[env])}  "
        f"{int(record.state[env]):4d}  {SUBTASK_CODES[subtask]:<2} {int(record.phase[env])}  "
        f"{action}  {ACTIONS[action].description}"
    )
    if batch.colliding[env]:
        line += "  [contact]"
    return "\n".join([*before, line])
