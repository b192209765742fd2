"""The navigator's corridor stretches in the core's multi-step call give, episode for episode,
what one step at a time gives (:mod:`mazesim.learn.core_episodes`)."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

import mazesim
from mazesim.actions import ACTION_CODES
from mazesim.episodes import EpisodeBatch, run_episodes
from mazesim.errors import InvalidArgumentError
from mazesim.learn.core_episodes import run_navigator_episodes, stretches_apply
from mazesim.learn.discretise import NUM_STATES
from mazesim.learn.evaluate import EvaluationRecord, evaluate_navigator
from mazesim.learn.higher import HigherLevel
from mazesim.learn.policy import HierarchicalPolicy
from mazesim.learn.qlearning import best_allowed
from mazesim.learn.subtasks import SUBTASK_ACTIONS
from mazesim.learn.tables import load_policy
from mazesim.maze import checkpoint_ids
from mazesim.replay.navigator import Recording
from navigator_oracle import hold_spins

RIGHT, LEFT, FORWARD = (ACTION_CODES.index(code) for code in ("aa", "bb", "00"))


def test_a_corridor_robot_keeps_its_turn_on_the_spot() -> None:
    spins = np.array([RIGHT, LEFT, RIGHT, LEFT, FORWARD, LEFT])
    previous = np.array([LEFT, RIGHT, RIGHT, -1, RIGHT, RIGHT])
    corridor = np.array([True, True, True, True, True, False])
    np.testing.assert_array_equal(
        hold_spins(spins, previous, corridor), [LEFT, RIGHT, RIGHT, LEFT, FORWARD, LEFT]
    )


@pytest.mark.parametrize(
    ("stretch_steps", "seed", "threads", "robots_per_world"),
    [(1, 9, 1, 2), (256, 9, 2, 2), (256, 4, 1, 5), (37, 4, 2, 5)],
)
def test_stretches_equal_single_steps_in_unseen_mazes(
    stretch_steps: int,
    seed: int,
    threads: int,
    robots_per_world: int,
) -> None:
    """Random higher-level values (so every sub-task runs), a checkpoint the higher level does
    not know (its events are ignored), a short step limit (so some episodes fail), fewer
    robots than episodes (robots wait with none left), and turns on the spot held; two seeds,
    one and two threads, two batch sizes."""
    held = [0]
    shipped = load_policy(None)
    assert shipped.lower_q is not None
    worlds = [mazesim.generate_maze(5, 5, seed=300 + i) for i in range(3)]
    ids = [checkpoint_ids(world)[1:] for world in worlds]
    values = np.random.default_rng(6).normal(size=HigherLevel(ids).q.shape)
    level = HigherLevel(ids, q=values)
    world_of_env = np.repeat(np.arange(3), robots_per_world)
    results = []
    calls = []
    for multi in (True, False):
        nav = EpisodeBatch(worlds, world_of_env, seed=seed, max_steps=2500, threads=threads)
        policy = HierarchicalPolicy(shipped.lower_q, level, world_of_env)
        acts = [0]
        act = policy.act

        def counted(
            *args: Any, act: Any = act, acts: list[int] = acts, policy: Any = policy
        ) -> Any:
            acts[0] += 1
            actions = act(*args)
            # A corridor action other than the table's best is a turn on the spot kept.
            r = policy.record
            best = best_allowed(
                shipped.lower_q[r.subtask, r.state + NUM_STATES * r.phase],
                SUBTASK_ACTIONS[r.subtask],
            )
            held[0] += int(np.count_nonzero((best != r.action) & (r.subtask == 0)))
            return actions

        policy.act = counted  # type: ignore[method-assign]
        ends: list[bool] = []

        def on_end(robots: np.ndarray, arrived: np.ndarray, ends: list[bool] = ends) -> None:
            ends.extend(arrived.tolist())

        if multi:
            got = run_navigator_episodes(nav, policy, 5, on_end, stretch_steps=stretch_steps)
        else:
            got = run_episodes(nav, policy, 5, None, on_end, policy.record.decisions)
        results.append((got, sorted(ends)))
        calls.append(acts[0])
    (fast, fast_ends), (slow, slow_ends) = results
    assert [r.episode for r in fast] == list(range(15))
    assert fast == slow
    # Robots run ahead of one another, so which robot runs which episode may differ.
    assert len(fast_ends) == 15 and sorted(fast_ends) == sorted(slow_ends)
    arrived = [r.arrived for r in fast]
    assert any(arrived) and not all(arrived), "expected both ends of an episode to be covered"
    assert {option for r in fast for _, option in r.decisions} == {0, 1, 2, 3}
    assert held[0] > 0, "expected turns on the spot kept in the per-step loop"
    if stretch_steps > 1:
        # Door sub-tasks and corridors alike go many steps a call: one call a checkpoint event
        # or so, where a door step used to cost a call of its own.
        assert calls[0] * 8 < calls[1], calls


@pytest.mark.parametrize(
    ("navigator", "episodes", "seed", "recorded", "least_success"),
    [(None, 12, 3, 3, 0.0), ("randomised", 6, 2, 2, 0.5)],
)
def test_evaluation_is_the_same_either_way_with_trace_and_paths(
    navigator: str | None, episodes: int, seed: int, recorded: int, least_success: float
) -> None:
    """The shipped navigator, and the randomised one (door distance, heading held where blind)."""
    policy = load_policy(navigator)
    assert policy.hold_heading == (navigator == "randomised")
    world = mazesim.load_world("seed-maze")
    fast, slow = (EvaluationRecord(paths=2, trace=True, recorder=Recording(recorded)) for _ in "ab")
    summaries = [
        evaluate_navigator(policy, [world], episodes, seed=seed, record=record, multi_step=multi)
        for record, multi in ((fast, True), (slow, False))
    ]
    assert summaries[0] == summaries[1]
    assert fast.outcomes == slow.outcomes and sorted(fast.outcomes) == list(range(recorded))
    assert fast.trace_lines == slow.trace_lines and len(fast.trace_lines) > 100
    assert fast.episode_paths.keys() == slow.episode_paths.keys() == {0, 1}
    for episode in fast.episode_paths:
        np.testing.assert_array_equal(fast.episode_paths[episode], slow.episode_paths[episode])
    assert fast.marks == slow.marks
    assert fast.run is not None and slow.run is not None
    assert fast.run.as_json() == slow.run.as_json()
    assert summaries[0]["truth"].success_rate >= least_success
    assert fast.marks == slow.marks
    assert fast.run is not None and slow.run is not None
    assert fast.run.as_json() == slow.run.as_json()


def robots_of_two_motor_limits() -> list[mazesim.RobotProfile]:
    seed = mazesim.RobotProfile.builtin("seed")
    slower = mazesim.RobotProfile.from_toml(
        seed.to_toml().replace(f"max_wheel_speed = {seed.max_wheel_speed}", "max_wheel_speed = 5.5")
    )
    assert slower.max_wheel_speed == 5.5
    return [seed, slower]


@pytest.mark.parametrize("first", [0, 1])
def test_robots_of_two_motor_limits_drive_at_the_first_ones_fractions_either_way(
    first: int,
) -> None:
    policy = load_policy(None)
    assert policy.lower_q is not None and policy.higher_q is not None
    world = mazesim.load_world("seed-maze")
    level = HigherLevel([policy.checkpoint_ids], q=policy.higher_q[None])
    robots = robots_of_two_motor_limits()
    robots = robots[first:] + robots[:first]
    results = []
    for multi in (True, False):
        nav = EpisodeBatch([world], num_envs=4, robot=robots * 2, seed=4, max_steps=1500)
        greedy = HierarchicalPolicy(policy.lower_q, level, np.zeros(4, dtype=np.int64))
        if multi:
            results.append(run_navigator_episodes(nav, greedy, 6))
        else:
            results.append(run_episodes(nav, greedy, 6, None, None, greedy.record.decisions))
    assert results[0] == results[1]
    assert any(r.arrived for r in results[0])


def test_what_stretches_cannot_run_is_refused() -> None:
    policy = load_policy(None)
    assert policy.lower_q is not None and policy.higher_q is not None
    world = mazesim.load_world("seed-maze")
    level = HigherLevel([policy.checkpoint_ids], q=policy.higher_q[None])
    greedy = HierarchicalPolicy(policy.lower_q, level, [0])
    exploring = HierarchicalPolicy(
        policy.lower_q, level, [0], chooser=lambda robots, states: states * 0
    )
    truth = EpisodeBatch([world], num_envs=1)
    robust = EpisodeBatch([world], num_envs=1, events="robust")
    mixed = EpisodeBatch([world], num_envs=2, robot=robots_of_two_motor_limits())
    assert stretches_apply(truth, greedy)
    assert stretches_apply(mixed, greedy)
    assert not stretches_apply(robust, greedy)
    assert not stretches_apply(truth, exploring)
    with pytest.raises(InvalidArgumentError, match="ground truth"):
        run_navigator_episodes(robust, greedy, 1)
    with pytest.raises(InvalidArgumentError, match="at least 1 step"):
        run_navigator_episodes(truth, greedy, 1, stretch_steps=0)


@pytest.mark.parametrize(("worlds", "episodes"), [(1, -1), (1, 0), (0, 3)])
def test_an_evaluation_of_no_episode_is_refused(worlds: int, episodes: int) -> None:
    # It returned a summary of 0 episodes, 0 % success, as if the navigator had been tried.
    policy = load_policy(None)
    maze = [mazesim.load_world("seed-maze")] * worlds
    with pytest.raises(mazesim.InvalidArgumentError, match="at least one world and one episode"):
        evaluate_navigator(policy, maze, episodes)
