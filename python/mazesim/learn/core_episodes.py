"""The navigator's episodes in stretches: the lower level driven by the core's multi-step call.

Between two checkpoint events the navigator's lower level acts alone: a robot runs its sub-task
from the sub-task's table on the distance state and the phase, and a door sub-task that ends
hands over to "Corridors and Corners". The core's ``tabular`` controller does all of this
itself when handed the sub-task tracker's arrays (:meth:`mazesim.BatchSimulator.run` with
``subtasks``): it computes the distance state, follows each robot's odometry after every step
as :meth:`~mazesim.learn.subtasks.SubTaskTracker.update` does (the same f64 operations, the
distance bins of ``door_distance`` too), keeps a corridor robot's turn on the spot as
:func:`mazesim.learn.policy.hold_spins` does and, with ``hold_heading``, holds a blind corridor
robot's heading as :func:`mazesim.learn.heading_hold.hold_actions` does.
:func:`run_navigator_episodes` therefore lets the core drive each robot for up to
:data:`STRETCH_STEPS` control steps in one call, until it crosses a barcode, reaches the goal or
runs out of steps; the higher level then decides in Python, as
:meth:`~mazesim.learn.policy.HierarchicalPolicy.act` does at every step. Robots are independent
(each draws only from its own noise stream), so a robot may run ahead of another.

Every episode ends as it does through :func:`mazesim.episodes.run_episodes` one step at a time:
the same actions, steps, contacts, bumps and decisions, bit for bit (the tests compare both).
The per-step loop stays for what watches every step (traces, paths, recordings, higher-level
learning) and for events read by the barcode decoder, which needs each step's ground reading.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import numpy.typing as npt

from mazesim.actions import ACTION_CODES
from mazesim.episodes import EpisodeBatch, EpisodeResult, EpisodeSchedule
from mazesim.errors import InvalidArgumentError
from mazesim.learn.discretise import NUM_STATES
from mazesim.learn.policy import HierarchicalPolicy
from mazesim.learn.subtasks import NUM_SUBTASKS, SUBTASK_ACTIONS

__all__ = ["STRETCH_STEPS", "run_navigator_episodes", "stretches_apply"]

#: Control steps the core drives a robot in one call at most.
STRETCH_STEPS = 256


def stretches_apply(nav: EpisodeBatch, navigator: object) -> bool:
    """Whether :func:`run_navigator_episodes` can run ``navigator``'s episodes in ``nav``: a
    :class:`HierarchicalPolicy` (of heading phases or of heading and distance phases, holding
    its heading where blind or not) choosing greedily, with events from the ground truth, on
    robots of one motor limit (the per-step loop drives every robot at the first one's
    fractions)."""
    return (
        type(navigator) is HierarchicalPolicy
        and navigator.chooser is None
        and nav.events_from == "truth"
        and nav.batch.one_motor_limit
    )


def run_navigator_episodes(
    nav: EpisodeBatch,
    policy: HierarchicalPolicy,
    episodes_per_world: int,
    on_end: Callable[[npt.NDArray[np.int64], npt.NDArray[np.bool_]], None] | None = None,
    stretch_steps: int = STRETCH_STEPS,
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

    Returns:
        The results, in order of episode number, with the decisions of each episode.

    Raises:
        InvalidArgumentError: Events from the decoder, a navigator that explores, robots of
            different motor limits, or a stretch of fewer than one step.
    """
    if not stretches_apply(nav, policy):
        raise InvalidArgumentError(
            "expected a greedy HierarchicalPolicy, events from the ground "
            f"truth and robots of one motor limit, found a {type(policy).__name__} with events "
            f"from {nav.events_from!r} and one_motor_limit={nav.batch.one_motor_limit}"
        )
    if stretch_steps < 1:
        raise InvalidArgumentError(f"expected a stretch of at least 1 step, found {stretch_steps}")
    # One table per (sub-task, phase): the core reads the distance state, the sub-task and its
    # phase pick the table ("Corridors and Corners" has one phase).
    phases = policy.lower_q.shape[1] // NUM_STATES
    tables = np.ascontiguousarray(
        policy.lower_q.reshape(NUM_SUBTASKS * phases, NUM_STATES, len(ACTION_CODES))
    )
    allowed = np.ascontiguousarray(np.repeat(SUBTASK_ACTIONS, phases, axis=0))
    batch = nav.batch
    count = nav.num_envs
    schedule = EpisodeSchedule(nav, policy, episodes_per_world)
    active = schedule.active
    schedule.start(np.arange(count))
    events = np.zeros(count, dtype=np.int64)
    while np.any(active):
        # The higher level at the events, and the odometry of the last step of each robot.
        policy.act(nav.observations, nav.poses, events)
        chosen = np.flatnonzero(policy.record.chosen >= 0)
        schedule.decide(chosen, policy.record.chosen[chosen], events)
        counters = batch.simulator.run(
            stretch_steps,
            "tabular",
            batch.observations,
            batch.poses,
            batch.colliding,
            batch.crossings,
            max_episode_steps=nav.max_steps,
            end_at_goal=True,
            end_at_crossing=True,
            autoreset=False,
            table=tables,
            allowed_actions=allowed,
            active=active,
            hold_spins=True,
            hold_heading=policy.hold_heading,
            subtasks=policy.tracker.arrays(),
        )
        nav.episode_steps += counters["steps"].astype(np.int64)
        nav.contact_steps += counters["steps_in_contact"].astype(np.int64)
        nav.events[:] = batch.crossings
        arrived = active & (counters["goals_reached"] > 0)
        out_of_time = active & ~arrived & (nav.episode_steps >= nav.max_steps)
        events = np.where(active, nav.events, 0)
        schedule.close(arrived, out_of_time, events, on_end)
    return schedule.ordered_results()
