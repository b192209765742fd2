"""Evaluating a navigator: success, collisions, steps against the shortest path, decisions, and
what the report's pictures (trajectories, Fig. 4.6 / 4.8) and terminal trace (Fig. 4.7) are
drawn from. It writes and prints nothing: :mod:`mazesim.learn.evaluation_text` turns a summary and a
trace into text, :mod:`mazesim.learn.figures` draws the paths, and ``mazesim eval`` writes them.

An evaluation runs greedy episodes in a world with sensor noise and the start jitter of
:class:`mazesim.episodes.StartJitter` (2 cm, 10 degrees). In the world the navigator's
higher level learned, it uses that table; in any other world (a file, or the unseen generated
mazes of ``--world random``) the lower-level tables are kept and only the higher level is trained
there first, with at most :data:`ADAPT_EPISODES` episodes per maze: the transfer test.

Measures (:class:`~mazesim.learn.summary.Summary`, the one result type, made by
:func:`~mazesim.learn.summary.summarise`): the share of episodes that reached the goal; bumps
(wall contacts the simulator counts) per episode, and the share of episodes without any; the
control steps of the episodes that arrived, and their ratio to the steps of the shortest path at
cruise speed (:func:`mazesim.episodes.shortest_path_steps`); and which sub-task the higher level
chose at each checkpoint event. :func:`evaluate_navigator` returns one summary per source of
checkpoint events.

With ``spread``, :func:`evaluate_navigator` hands the episodes out in chunks
(:mod:`mazesim.learn.episode_ranges`; ``mazesim eval --address`` passes Ray's
:func:`mazesim.distributed.evaluate_episodes`): the higher level of an unseen world is trained
once, here, and its tables shipped with the chunks; every episode ends as it would here, so the
summary is the same spread or not.

What the first episodes looked like (their paths, the trace of episode 0, a recorded run for
the replay and videos) goes into an :class:`EvaluationRecord` the caller hands in; recording
frame by frame takes a ``recorder`` factory from the caller
(:class:`mazesim.replay.navigator.Recording`), so this module needs nothing of the viewers.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np
import numpy.typing as npt

from mazesim._core import RobotProfile, World, generate_maze
from mazesim._seeding import stream_seeds
from mazesim._settings import MAX_COUNT, MAX_SEED, check_settings, setting
from mazesim.actions import ACTION_CODES, ACTIONS
from mazesim.batch import RobotChoice, first_profile
from mazesim.episodes import (
    EVENT_SOURCES,
    MAX_STEPS,
    EpisodeBatch,
    EpisodeResult,
    StartJitter,
    run_episodes,
    shortest_path_steps,
)
from mazesim.errors import InvalidArgumentError, RegisteredName, _shown
from mazesim.learn.core_episodes import StretchReplay, run_navigator_episodes, stretches_apply
from mazesim.learn.discretise import format_levels
from mazesim.learn.episode_ranges import NavigatorEpisodes
from mazesim.learn.higher import HigherLevel
from mazesim.learn.higher_training import HigherTraining, train_higher
from mazesim.learn.policy import HierarchicalPolicy, StepRecord
from mazesim.learn.subtasks import CONTROL_STEP_MS, SUBTASK_CODES, SUBTASK_NAMES
from mazesim.learn.summary import Summary, summarise
from mazesim.learn.tables import TrainedPolicy
from mazesim.maze import world_hash

__all__ = [
    "ADAPTATION",
    "ADAPT_EPISODES",
    "EvalSettings",
    "EvaluationRecord",
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
class EvaluationRecord:
    """What an evaluation records of its first episodes beside the summary: the caller says what
    to record and hands the record to the evaluator, which fills in the rest.

    Attributes:
        paths: Record the trajectories of the first this many episodes of the first world.
        trace: Record the per-step trace of episode 0
            (:func:`mazesim.learn.evaluation_text.trace_text` makes it a file).
        recorder: Records the first episodes frame by frame (:attr:`run`, for the replay and
            videos); see :class:`RecorderFactory`.
        episode_paths: Filled in: each recorded episode's ``(x, y)`` points, by episode number
            (for :mod:`mazesim.learn.figures`).
        marks: Filled in: each recorded episode's decisions as ``(x, y, event, sub-task)``.
        trace_lines: Filled in: the trace of episode 0, one step or event a line.
        run: Filled in: the run the recorder recorded (``None`` without a recorder).
        outcomes: Filled in: the results of the recorded episodes, by episode number.
    """

    paths: int = 0
    trace: bool = False
    recorder: RecorderFactory | None = None
    episode_paths: dict[int, npt.NDArray[np.float64]] = field(default_factory=dict)
    marks: dict[int, list[tuple[float, float, int, int]]] = field(default_factory=dict)
    trace_lines: list[str] = field(default_factory=list)
    run: Any = None
    outcomes: dict[int, EpisodeResult] = field(default_factory=dict)

    @property
    def episodes(self) -> int:
        """Episodes of the first world this record asks for (0: none)."""
        wanted = max(self.paths, 1 if self.trace else 0)
        return wanted if self.recorder is None else max(wanted, self.recorder.episodes)

    def fill_from(self, other: EvaluationRecord) -> None:
        """Takes what ``other`` recorded (the same episodes, run elsewhere)."""
        self.episode_paths, self.marks = other.episode_paths, other.marks
        self.trace_lines, self.run, self.outcomes = other.trace_lines, other.run, other.outcomes


#: The most unseen mazes one evaluation generates (each takes about 16 kB and an episode or more).
MAX_UNSEEN_MAZES = 10_000


@dataclass(frozen=True)
class EvalSettings:
    """What ``mazesim eval`` measures: its options are these fields (the defaults are the only
    ones, the help texts are the metadata's)."""

    policy: str | None = setting(
        None,
        "folder of a saved navigator, or 'randomised': the one shipped trained with "
        "domain randomisation",
        "DIR",
        default_text="the one shipped for seed-maze",
    )
    world: str | None = setting(
        None,
        "a built-in world, a world file, or 'random' for unseen generated mazes",
        "NAME|PATH|random",
        default_text="the navigator's world",
    )
    episodes: int = setting(
        200,
        "evaluation episodes (with 'random': spread over --mazes mazes)",
        "N",
        least=1,
        most=MAX_COUNT,
    )
    mazes: int = setting(100, "unseen mazes of --world random", "M", least=1, most=MAX_UNSEEN_MAZES)
    seed: int = setting(
        0,
        "seed of the episodes' start jitter and sensor noise, and of the random mazes",
        "S",
        least=0,
        most=MAX_SEED,
    )
    events: RegisteredName = setting(
        "both",
        "checkpoint events from the simulator's ground truth, from the robust barcode "
        "decoder, or both, reported side by side",
        choices=(*EVENT_SOURCES, "both"),
    )
    max_steps: int = setting(
        MAX_STEPS,
        "control steps (64 ms) after which an episode fails",
        "N",
        least=1,
        most=MAX_COUNT,
    )
    robot: str = setting(
        "seed",
        "the robot profile the navigator drives: a built-in name or a profile file "
        "(docs/robots.md); the report's seed robot unless told",
        "NAME|PATH",
    )

    def __post_init__(self) -> None:
        check_settings(self)

    @property
    def sources(self) -> list[str]:
        """The event sources to evaluate with, in order."""
        return list(EVENT_SOURCES) if self.events == "both" else [self.events]


def unseen_mazes(count: int, seed: int) -> list[World]:
    """``count`` generated 5 x 5 perfect mazes for testing; their seeds derive from ``seed`` on a
    stream no training run uses. Single-corridor draws are kept (``junction=False``), as when the
    documented figures were measured.

    Raises:
        InvalidArgumentError: ``count`` is not in 1 to :data:`MAX_UNSEEN_MAZES`.
    """
    if not 1 <= count <= MAX_UNSEEN_MAZES:
        raise InvalidArgumentError(f"expected 1 to {MAX_UNSEEN_MAZES} unseen mazes, found {count}")
    maze_seeds = stream_seeds(seed, "evaluate/mazes", count)
    return [generate_maze(5, 5, seed=int(maze_seed), junction=False) for maze_seed in maze_seeds]


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
        policy.lower_q,
        worlds,
        settings,
        threads=threads,
        progress=adapting,
        robot=robot,
        hold_heading=policy.hold_heading,
    )
    return level, True


NavigatorFactory = Callable[[npt.NDArray[np.int64]], Any]


class RecorderFactory(Protocol):
    """Builds a recording navigator from the batch and the navigator it watches.

    What it builds is a navigator itself, with ``after_step(arrived, out_of_time)`` and
    ``run(controller, seed)`` (the recorded run); it records the first :attr:`episodes` episodes.
    """

    episodes: int

    def __call__(self, nav: EpisodeBatch, navigator: Any) -> Any: ...


#: Runs an evaluation's chunks (``chunk(first, count)`` -> the results of episodes ``first`` to
#: ``first + count - 1``) for ``episodes`` episodes and joins them in episode order.
Spreader = Callable[[Callable[[int, int], list[EpisodeResult]], int], list[EpisodeResult]]


def evaluate(
    make_navigator: NavigatorFactory,
    worlds: Sequence[World],
    episodes_per_world: int,
    seed: int = 0,
    events: str = "truth",
    jitter: StartJitter | None = None,
    max_steps: int = MAX_STEPS,
    record: EvaluationRecord | None = None,
    threads: int = 0,
    controller: str = "hrl",
    progress: Callable[[str, int, int], None] | None = None,
    multi_step: bool = True,
    robot: RobotChoice = "seed",
) -> Summary:
    """Runs greedy episodes of a navigator and measures them.

    With ``multi_step`` (the default), a greedy
    :class:`~mazesim.learn.policy.HierarchicalPolicy` with events from the ground truth runs in
    the core's multi-step call from one checkpoint event to the next, door sub-tasks included
    (:func:`mazesim.learn.core_episodes.run_navigator_episodes`); the episodes to record (paths,
    trace, replay) are recorded from the core's per-step trace of the same run
    (:class:`~mazesim.learn.core_episodes.StretchReplay`), so every episode runs once. Any
    other navigator (a flat one, one that wraps ``act``) and decoder events run one step at a
    time. The results are the same either way; the multi-step
    call is the faster (see ``docs/performance.md``).

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
        record: What to record of the first episodes (filled in here); ``None``: nothing.
        threads: Worker threads of the batch.
        controller: The controller's name in the recorded run.
        progress: Called as ``progress("evaluate", episodes_done, episodes_total)``.
        multi_step: Use the multi-step call where it applies (the default); ``False``: one step
            at a time.
        robot: The robots (:data:`mazesim.batch.RobotChoice`), handed to the batch as given.

    Returns:
        What the episodes measured.
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
    record = record if record is not None else EvaluationRecord()
    replay = None
    if multi_step and stretches_apply(nav, navigator):
        replay = StretchReplay(nav, navigator, record.episodes)
    # What the watcher and the recorder read: the batch and the navigator, step by step, or
    # their replay from the core's trace.
    stepper: Any = navigator if replay is None else replay.navigator
    shown: Any = nav if replay is None else replay.view
    recording = None if record.recorder is None else record.recorder(shown, stepper)
    paths: dict[int, list[tuple[float, float]]] = {}
    ended: set[int] = set()
    marks = record.marks
    lines = record.trace_lines

    def watch(
        batch: EpisodeBatch,
        actions: npt.NDArray[np.int64],
        arrived: npt.NDArray[np.bool_],
        out_of_time: npt.NDArray[np.bool_],
    ) -> None:
        if recording is not None:
            recording.after_step(arrived, out_of_time)
        if not record.paths and not record.trace:
            return
        steps = stepper.record
        # A robot left without an episode is still stepped: record its episode's steps only.
        running = ~np.isin(batch.episode, list(ended))
        for env in np.flatnonzero(running & (batch.episode < record.paths)):
            episode = int(batch.episode[env])
            x, y, _ = (float(v) for v in batch.poses[env])
            paths.setdefault(episode, []).append((x, y))
            if steps.chosen[env] >= 0:
                marks.setdefault(episode, []).append(
                    (x, y, int(steps.event[env]), int(steps.chosen[env]))
                )
        if record.trace:
            for env in np.flatnonzero(running & (batch.episode == 0)):
                lines.append(_trace_line(batch, steps, int(env)))
                if arrived[env]:
                    lines.append(f"# goal reached after {int(batch.episode_steps[env])} steps")
                elif out_of_time[env]:
                    lines.append(f"# out of time after {int(batch.episode_steps[env])} steps")
        ended.update(int(episode) for episode in batch.episode[running & (arrived | out_of_time)])

    driver = stepper if recording is None else recording
    if replay is not None:
        replay.driver, replay.watch = driver, watch
        results = run_navigator_episodes(nav, navigator, episodes_per_world, on_end, replay=replay)
    else:
        decisions = navigator.record.decisions
        results = run_episodes(nav, driver, episodes_per_world, watch, on_end, decisions)
    record.episode_paths = {k: np.array(v) for k, v in paths.items()}
    recorded = [r for r in results if r.world == 0 and r.episode < record.episodes]
    record.outcomes = {r.episode: r for r in recorded}
    if recording is not None:
        record.run = recording.run(controller, seed)
    return summarise(results, shortest, events)


def evaluate_navigator(
    policy: TrainedPolicy,
    worlds: Sequence[World],
    episodes_per_world: int,
    seed: int = 0,
    sources: Sequence[str] = ("truth",),
    max_steps: int = MAX_STEPS,
    record: EvaluationRecord | None = None,
    threads: int = 0,
    spread: Spreader | None = None,
    progress: Callable[[str, int, int], None] | None = None,
    multi_step: bool = True,
    robot: RobotChoice = "seed",
) -> dict[str, Summary]:
    """Evaluates a saved navigator with checkpoint events from each source (it writes nothing).

    Args:
        record: What to record of the first source's first episodes in the first world (the
            paths, the trace of episode 0, a run for the replay), filled in here.
        spread: ``None``: run every episode in this process; else the function that runs the
            evaluation's chunks (:data:`Spreader`, e.g. Ray's
            :func:`mazesim.distributed.evaluate_episodes`). The recorded episodes are run here
            as well.
        progress: Called as ``progress(stage, done, total)``: ``"adapt"`` while the higher level
            learns unseen worlds, then ``"evaluate"`` (``"evaluate robust"`` for the second
            source) over the episodes.
        multi_step: Run the episodes in the core's multi-step call where it applies (the
            default; see :func:`evaluate`); ``False``: every episode one step at a time. The
            results are the same.
        robot: The robots of the evaluation and of the higher level's adaptation
            (:data:`mazesim.batch.RobotChoice`), handed to the batches as given; with
            ``spread``, one profile for every robot, sent to the chunks as itself (a profile
            file's as its TOML text), so the machines that run them need no copy of its file.

    Returns:
        Each source's summary, in the order of ``sources``; their
        :attr:`~mazesim.learn.summary.Summary.adapted` says whether the higher level was
        trained in ``worlds`` first.

    Raises:
        PolicyFormatError: A flat navigator asked to drive a world it did not learn.
        MissingDependencyError: ``spread`` needs a package that is not installed.
        InvalidArgumentError: ``episodes_per_world`` is below 1, or ``worlds`` is empty.
    """
    if episodes_per_world < 1 or len(worlds) < 1:
        raise InvalidArgumentError(
            "expected at least one world and one episode per world, found"
            f" {len(worlds)} worlds and {episodes_per_world} episodes per world"
        )
    if spread is not None and not isinstance(robot, (str, RobotProfile)):
        raise InvalidArgumentError(
            "expected one robot profile (a name, a profile file or a RobotProfile) for every "
            f"episode of an evaluation spread in chunks, found a sequence of {len(robot)}"
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
        hold_heading = policy.hold_heading

        def make_navigator(world_of_env: npt.NDArray[np.int64]) -> Any:
            return HierarchicalPolicy(lower_q, level, world_of_env, hold_heading=hold_heading)

    summaries: dict[str, Summary] = {}
    level_shipped = None if policy.kind == "flat" else level

    def run(*args: Any, **options: Any) -> Summary:
        if spread is None:
            return evaluate(*args, **options)
        return _evaluate_spread(spread, policy, level_shipped, *args, **options)

    for place, source in enumerate(sources):
        first = place == 0
        summary = run(
            make_navigator,
            worlds,
            episodes_per_world,
            seed=seed,
            events=source,
            max_steps=max_steps,
            record=record if first else None,
            threads=threads,
            controller=policy.kind,
            progress=_staged(progress, "evaluate" if first else f"evaluate {source}"),
            multi_step=multi_step,
            robot=robot,
        )
        summaries[source] = dataclasses.replace(summary, adapted=adapted)
    return summaries


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
) -> Summary:
    """:func:`evaluate` with its episodes spread in chunks by ``spread``; the episodes to record
    run here as well."""

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
        hold_heading=policy.hold_heading,
        robot=first_profile(options["robot"]),
    )
    progress = options.pop("progress")
    results = chunks.check_joined(spread(chunks, chunks.episodes))
    if progress is not None:
        progress("evaluate", chunks.episodes, chunks.episodes)
    shortest = [shortest_path_steps(world) for world in worlds]
    _record_here(options.pop("record"), make_navigator, worlds, episodes_per_world, options)
    return summarise(results, shortest, options["events"])


def _record_here(
    record: EvaluationRecord | None,
    make_navigator: NavigatorFactory,
    worlds: Sequence[World],
    episodes_per_world: int,
    options: dict[str, Any],
) -> None:
    """Runs the first episodes of the first world again, one step at a time, for what ``record``
    asks for (an episode ends the same way whatever runs it), and fills it in."""
    if record is None or not record.episodes:
        return
    here = EvaluationRecord(record.paths, record.trace, record.recorder)
    options = {**options, "multi_step": False, "record": here}
    evaluate(make_navigator, worlds[:1], min(episodes_per_world, record.episodes), **options)
    record.fill_from(here)


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
            note += f" -> higher level: {_shown(SUBTASK_NAMES[chosen])}"
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
