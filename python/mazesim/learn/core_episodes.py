"""The navigator's episodes in stretches: the lower level driven by the core's multi-step call.

Between two checkpoint events the navigator's lower level acts alone: a robot runs its sub-task
from the sub-task's table on the distance state and the phase, and a door sub-task that ends
hands over to "Corridors and Corners". The core's ``tabular`` controller does all of this
itself when handed the navigator's sub-task arrays (:meth:`mazesim.BatchSimulator.run` with
``subtasks``): it computes the distance state, follows each robot's odometry after every step
as the core's navigator (:class:`mazesim._core.Navigator`) does at every step (the same
sub-task code, the distance bins of ``door_distance`` too), keeps a corridor robot's turn on the
spot and, with ``hold_heading``, holds a blind corridor robot's heading.
:func:`run_navigator_episodes` therefore lets the core drive each robot for up to
:data:`STRETCH_STEPS` control steps in one call, until it crosses a barcode, reaches the goal or
runs out of steps; the higher level then decides in Python, as
:meth:`~mazesim.learn.policy.HierarchicalPolicy.act` does at every step. Robots are independent
(each draws only from its own noise stream), so a robot may run ahead of another.

Every episode ends as it does through :func:`mazesim.episodes.run_episodes` one step at a time:
the same actions, steps, contacts, bumps and decisions, bit for bit (the tests compare both).
What watches every step of the first episodes (the paths, trace and recording of an evaluation)
is handed a :class:`StretchReplay`: the core then writes each step of the robots running them
(``BatchSimulator.run``'s ``trace``, with the sub-task, phase and sub-task ends of each step), and
the replay shows those steps one at a time, as the per-step loop would have shown them, so no
episode runs twice. The per-step loop stays for higher-level learning and for events read by
the barcode decoder, which needs each step's ground reading.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._core import EpisodeLimits, RunSettings, TabularSettings
from mazesim.actions import ACTION_CODES
from mazesim.episodes import EpisodeBatch, EpisodeResult, EpisodeSchedule, Watcher
from mazesim.errors import InvalidArgumentError, _shown
from mazesim.learn.discretise import NUM_SENSORS, NUM_STATES, distances_and_levels, encode_state
from mazesim.learn.policy import HierarchicalPolicy, StepRecord
from mazesim.learn.subtasks import NUM_SUBTASKS, SUBTASK_ACTIONS

__all__ = ["STRETCH_STEPS", "StretchReplay", "run_navigator_episodes", "stretches_apply"]

#: Control steps the core drives a robot in one call at most.
STRETCH_STEPS = 256
#: The episode number a :class:`StretchReplay` shows for robots that do not step.
_NOT_SHOWN = np.iinfo(np.int64).max


class TracedNavigator:
    """The navigator's steps read back from a stretch's trace: a navigator (``act``,
    ``record``, ``higher``, ``world_of_env``) whose ``act`` returns the actions the core took."""

    def __init__(self, policy: HierarchicalPolicy) -> None:
        self.higher = policy.higher
        self.world_of_env = policy.world_of_env
        self.record = StepRecord(policy.num_envs)
        self.actions = np.zeros(policy.num_envs, dtype=np.int64)

    def reset(self, envs: npt.ArrayLike, poses: npt.ArrayLike) -> None:
        """Nothing to do: the policy it reads back starts the robots."""

    def act(
        self, observations: npt.ArrayLike, poses: npt.ArrayLike, events: npt.ArrayLike
    ) -> npt.NDArray[np.int64]:
        """The actions of the step being shown."""
        return self.actions


class StepView:
    """An :class:`~mazesim.episodes.EpisodeBatch` as the per-step loop shows it before or
    after one step of a stretch (what a :data:`~mazesim.episodes.Watcher` and a recorder read):
    robots that do not take that step show the episode number ``_NOT_SHOWN``."""

    def __init__(self, nav: EpisodeBatch) -> None:
        self.worlds, self.world_of_env, self.robot = nav.worlds, nav.world_of_env, nav.robot
        self.control_step_ms, self.num_envs = nav.control_step_ms, nav.num_envs
        self.observations = nav.observations.copy()
        self.poses = nav.poses.copy()
        self.colliding = nav.colliding.copy()
        self.events = nav.events.copy()
        self.episode = nav.episode.copy()
        self.episode_steps = nav.episode_steps.copy()


class StretchReplay:
    """What watches every step of the first ``episodes`` episodes of
    :func:`run_navigator_episodes`, shown them one step at a time from the core's trace.

    Build it, then set :attr:`driver` (the navigator ``act`` is called on each step: the
    :attr:`navigator` or a recorder wrapping it and reading :attr:`view`) and :attr:`watch`.

    Args:
        nav: The robots and their worlds.
        policy: Their navigator.
        episodes: Episodes ``0 .. episodes - 1`` are shown (0: none).
    """

    def __init__(self, nav: EpisodeBatch, policy: HierarchicalPolicy, episodes: int) -> None:
        self.nav = nav
        self.episodes = episodes
        self.view = StepView(nav)
        self.navigator = TracedNavigator(policy)
        self.driver: Any = self.navigator
        self.watch: Watcher | None = None
        self.stretch_steps = STRETCH_STEPS
        self._watched = np.zeros(nav.num_envs, dtype=bool)
        self._before = (nav.observations, nav.poses, nav.colliding)
        self._first = StepRecord(nav.num_envs)
        self._events = np.zeros(nav.num_envs, dtype=np.int64)

    def begin(
        self, active: npt.NDArray[np.bool_], first: StepRecord, events: npt.NDArray[np.int64]
    ) -> dict[str, npt.NDArray[Any]] | None:
        """Before a call: notes the robots to show (active, running an episode to show), their
        state, the policy's record of the call's first step (it acted in Python) and the
        checkpoint events that step acted on; returns the call's ``trace`` arrays (empty, for
        :attr:`stretch_steps` steps), or ``None`` when no robot is to be shown."""
        episode = self.nav.episode
        self._watched = active & (episode >= 0) & (episode < self.episodes)
        if not self._watched.any():
            return None
        nav = self.nav
        self._before = (nav.observations.copy(), nav.poses.copy(), nav.colliding.copy())
        self._first, self._events = _copied(first), events.copy()
        steps, n, width = self.stretch_steps, nav.num_envs, nav.observations.shape[1]
        return {
            "observations": np.zeros((steps, n, width), dtype=np.float32),
            "poses": np.zeros((steps, n, 3), dtype=np.float32),
            "colliding": np.zeros((steps, n), dtype=bool),
            "crossings": np.zeros((steps, n), dtype=np.int32),
            "actions": np.zeros((steps, n), dtype=np.int32),
            "subtasks": np.zeros((steps, n), dtype=np.int32),
            "phases": np.zeros((steps, n), dtype=np.int32),
            "subtask_ends": np.zeros((steps, n), dtype=bool),
        }

    def show(self, steps: npt.NDArray[np.int64], trace: dict[str, npt.NDArray[Any]]) -> None:
        """After a call (before the batch's counters move on): shows its steps of the robots
        noted by :meth:`begin` (``steps``: (N,) steps each robot took, ``trace``: the arrays
        :meth:`begin` gave, filled) to the driver and the watcher."""
        nav, view, navigator = self.nav, self.view, self.navigator
        watched, before = self._watched, self._before
        base = nav.episode_steps.copy()
        for step in range(int(steps[watched].max(initial=0))):
            stepping = watched & (steps > step)
            view.observations[:], view.poses[:], view.colliding[:] = before
            view.episode = np.where(stepping, nav.episode, _NOT_SHOWN)
            view.episode_steps = base + step
            navigator.record = self._first if step == 0 else _record_of(trace, step, before[0])
            navigator.actions = trace["actions"][step].astype(np.int64)
            shown = self._events if step == 0 else np.zeros_like(self._events)
            actions = self.driver.act(view.observations, view.poses, shown)
            before = (trace["observations"][step], trace["poses"][step], trace["colliding"][step])
            view.observations[:], view.poses[:], view.colliding[:] = before
            view.events[:] = trace["crossings"][step]
            view.episode_steps = base + step + 1
            arrived = stepping & nav.at_goal(view.poses)
            out_of_time = stepping & ~arrived & (view.episode_steps >= nav.max_steps)
            if self.watch is not None:
                self.watch(view, actions, arrived, out_of_time)  # type: ignore[arg-type]


def _record_of(
    trace: dict[str, npt.NDArray[Any]], step: int, observations: npt.NDArray[np.float32]
) -> StepRecord:
    """The navigator's record of step ``step`` (> 0) of a call, from its trace and the
    observations it acted on."""
    record = StepRecord(observations.shape[0])
    record.distances_cm, record.levels = distances_and_levels(observations[:, :NUM_SENSORS])
    record.state = np.asarray(encode_state(record.levels))
    record.subtask = trace["subtasks"][step].astype(np.int64)
    record.phase = trace["phases"][step].astype(np.int64)
    record.action = trace["actions"][step].astype(np.int64)
    record.ended = trace["subtask_ends"][step].copy()
    return record


def stretches_apply(nav: EpisodeBatch, navigator: object) -> bool:
    """Whether :func:`run_navigator_episodes` can run ``navigator``'s episodes in ``nav``: a
    :class:`HierarchicalPolicy` (of heading phases or of heading and distance phases, holding
    its heading where blind or not) choosing greedily, with events from the ground truth.
    Robots of several motor limits drive, as in the per-step loop, at the fractions of the
    first one's (``BatchSimulator.run``'s ``wheel_speed_limit``)."""
    return (
        type(navigator) is HierarchicalPolicy
        and navigator.chooser is None
        and nav.events_from == "truth"
    )


def run_navigator_episodes(
    nav: EpisodeBatch,
    policy: HierarchicalPolicy,
    episodes_per_world: int,
    on_end: Callable[[npt.NDArray[np.int64], npt.NDArray[np.bool_]], None] | None = None,
    stretch_steps: int = STRETCH_STEPS,
    replay: StretchReplay | None = None,
) -> list[EpisodeResult]:
    """Runs ``episodes_per_world`` greedy episodes of ``policy`` in each world of ``nav``, each
    robot in the core from one checkpoint event to the next; the results equal
    :func:`mazesim.episodes.run_episodes`'s.

    Args:
        nav: The robots and their worlds (events from the ground truth).
        policy: The navigator of all robots (greedy: no ``chooser``).
        episodes_per_world: Episodes to run in each world.
        on_end: Called with the robots whose episode ended and whether each arrived, before new
            episodes start on them.
        stretch_steps: Control steps of a robot in one call at most.
        replay: Shown every step of the first episodes (see :class:`StretchReplay`).

    Returns:
        The results, in order of episode number, with the decisions of each episode.

    Raises:
        InvalidArgumentError: Events from the decoder, a navigator that explores, or a stretch
            of fewer than one step.
    """
    if not stretches_apply(nav, policy):
        raise InvalidArgumentError(
            "expected a greedy HierarchicalPolicy and events from the ground truth, found a "
            f"{type(policy).__name__} with events from {_shown(nav.events_from)}"
        )
    if stretch_steps < 1:
        raise InvalidArgumentError(f"expected a stretch of at least 1 step, found {stretch_steps}")
    if replay is not None:
        replay.stretch_steps = stretch_steps
    # One table per (sub-task, phase): the core reads the distance state, the sub-task and its
    # phase pick the table ("Corridors and Corners" has one phase).
    phases = policy.lower_q.shape[1] // NUM_STATES
    tables = np.ascontiguousarray(
        policy.lower_q.reshape(NUM_SUBTASKS * phases, NUM_STATES, len(ACTION_CODES))
    )
    allowed = np.ascontiguousarray(np.repeat(SUBTASK_ACTIONS, phases, axis=0))
    batch = nav.batch
    controller = TabularSettings(
        tables,
        allowed_actions=allowed,
        hold_spins=True,
        hold_heading=policy.hold_heading,
        wheel_speed_limit=batch.profile.max_wheel_speed,
    )
    limits = EpisodeLimits(
        max_steps=nav.max_steps, end_at_goal=True, end_at_crossing=True, autoreset=False
    )
    count = nav.num_envs
    schedule = EpisodeSchedule(nav, policy, episodes_per_world)
    active = schedule.active
    schedule.start(np.arange(count))
    events = np.zeros(count, dtype=np.int64)
    while np.any(active):
        # The higher level at the events, and the odometry of the last step of each robot.
        policy.act(nav.observations, nav.poses, events)
        schedule.decide(*policy.record.decisions(), events)
        trace = None if replay is None else replay.begin(active, policy.record, events)
        subtasks = policy.subtask_arrays()
        counters = batch.simulator.run(
            stretch_steps,
            controller,
            batch.observations,
            batch.poses,
            batch.colliding,
            batch.crossings,
            settings=RunSettings(limits, active=active, subtasks=subtasks, trace=trace),
        )
        policy.set_subtask_arrays(subtasks)
        if trace is not None and replay is not None:
            replay.show(counters["steps"].astype(np.int64), trace)
        nav.episode_steps += counters["steps"].astype(np.int64)
        nav.contact_steps += counters["steps_in_contact"].astype(np.int64)
        nav.events[:] = batch.crossings
        arrived = active & (counters["goals_reached"] > 0)
        out_of_time = active & ~arrived & (nav.episode_steps >= nav.max_steps)
        events = np.where(active, nav.events, 0)
        schedule.close(arrived, out_of_time, events, on_end)
    return schedule.ordered_results()


def _copied(record: StepRecord) -> StepRecord:
    """A copy of ``record``'s arrays."""
    copy = StepRecord(record.state.size)
    for name, value in vars(record).items():
        setattr(copy, name, np.array(value, copy=True))
    return copy
