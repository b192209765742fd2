"""The settings objects of ``BatchSimulator.run`` (``EpisodeLimits``, ``AvoidCollisionSettings``,
``TabularSettings``, ``RunSettings``) and of ``Simulator.step_task`` (``StepBounds``): checked
when made, frozen, shown and pickled as values; ``run``'s former keywords still run the same
call, with a ``DeprecationWarning``, for one release."""

from __future__ import annotations

import copy
import pickle
from typing import Any

import numpy as np
import pytest

import mazesim
from batch_buffers import buffers
from mazesim import AvoidCollisionSettings, EpisodeLimits, RunSettings, TabularSettings
from mazesim._core import StepBounds


def seed_batch(n: int = 6) -> mazesim.BatchSimulator:
    worlds = [mazesim.generate_maze(5, 5, seed=90 + i, loops=0.1) for i in range(n)]
    return mazesim.BatchSimulator(worlds, robot="seed", seeds=0, threads=1)


def traced(n: int, steps: int) -> dict[str, np.ndarray]:
    return {
        "poses": np.zeros((steps, n, 3), np.float32),
        "actions": np.zeros((steps, n), np.int32),
        "episode_ends": np.zeros((steps, n), bool),
    }


def test_former_keywords_warn_and_run_as_the_settings_do() -> None:
    n, steps = 6, 70
    tables = np.random.default_rng(3).random((2, 4096, 12))
    allowed = np.ones((2, 12), bool)
    allowed[1, 4] = False
    index = np.arange(n, dtype=np.int64) % 2
    limits = {"end_at_crossing": True, "autoreset": False}
    runs = []
    for former in (False, True):
        batch = seed_batch(n)
        out = buffers(batch)
        batch.reset(*out)
        trace = traced(n, steps)
        if former:
            with pytest.warns(DeprecationWarning, match="run's keyword .* is deprecated"):
                counters = batch.run(
                    steps,
                    "tabular",
                    *out,
                    table=tables,
                    allowed_actions=allowed,
                    table_index=index,
                    epsilon=0.2,
                    seeds=11,
                    trace=trace,
                    max_episode_steps=50,
                    **limits,
                )
        else:
            controller = TabularSettings(
                tables, allowed_actions=allowed, table_index=index, epsilon=0.2
            )
            settings = RunSettings(EpisodeLimits(max_steps=50, **limits), seeds=11, trace=trace)
            counters = batch.run(steps, controller, *out, settings=settings)
        runs.append((trace, out, counters))
    (trace, out, counters), (old_trace, old_out, old_counters) = runs
    for key in trace:
        np.testing.assert_array_equal(trace[key], old_trace[key], err_msg=key)
    for mine, theirs in zip(out, old_out):
        np.testing.assert_array_equal(mine, theirs)
    assert counters.keys() == old_counters.keys()
    for key in counters:
        np.testing.assert_array_equal(counters[key], old_counters[key], err_msg=key)
    assert counters["episodes_finished"].sum() > 0 and (trace["actions"] >= 0).any()


def test_former_avoid_collision_keywords_warn_and_still_check_their_values() -> None:
    batch = mazesim.BatchSimulator(mazesim.load_world("seed-maze"), num_envs=2)
    out = buffers(batch)
    with pytest.warns(DeprecationWarning, match="'threshold'"):
        batch.run(5, "avoid-collision", *out, threshold=70.0)
    with pytest.warns(DeprecationWarning, match="'seeds'"):
        counters = batch.run(5, AvoidCollisionSettings(), *out, seeds=[4, 5])
    assert counters["steps"].tolist() == [5, 5]
    with (
        pytest.warns(DeprecationWarning),
        pytest.raises(mazesim.InvalidArgumentError, match="threshold"),
    ):
        batch.run(5, "braitenberg", *out, threshold=float("nan"))


def test_settings_and_former_keywords_together_are_refused() -> None:
    batch = mazesim.BatchSimulator(mazesim.load_world("seed-maze"), num_envs=2)
    out = buffers(batch)
    with pytest.raises(mazesim.InvalidArgumentError, match="either settings or"):
        batch.run(5, "braitenberg", *out, settings=RunSettings(), seeds=3)
    with pytest.raises(mazesim.InvalidArgumentError, match="expected settings to be a RunSettings"):
        batch.run(5, "braitenberg", *out, settings=EpisodeLimits())
    with pytest.raises(mazesim.InvalidArgumentError, match="not_a_keyword"):
        batch.run(5, "braitenberg", *out, not_a_keyword=1)
    with pytest.raises(mazesim.InvalidArgumentError, match="as a TabularSettings"):
        batch.run(5, "tabular", *out)
    assert (batch.steps() == 0).all()


def test_the_tables_are_copied_when_the_settings_are_made() -> None:
    table = np.zeros((4096, 12))
    table[:, 0] = 1.0
    forward = TabularSettings(table)
    table[:, 0], table[:, 9] = 0.0, 1.0  # now spin right everywhere
    batch = seed_batch(2)
    out = buffers(batch)
    trace = traced(2, 5)
    batch.run(5, forward, *out, settings=RunSettings(trace=trace))
    assert (trace["actions"] == 0).all()
    batch.run(5, TabularSettings(table), *out, settings=RunSettings(trace=trace))
    assert (trace["actions"] == 9).all()


def test_the_settings_show_and_keep_their_values() -> None:
    limits = EpisodeLimits(max_steps=30, end_at_goal=True)
    assert repr(limits) == (
        "EpisodeLimits(max_steps=30, end_at_goal=True, end_at_crossing=False, autoreset=True)"
    )
    assert (limits.max_steps, limits.end_at_goal, limits.end_at_crossing, limits.autoreset) == (
        30,
        True,
        False,
        True,
    )
    assert limits == EpisodeLimits(30, True) and limits != EpisodeLimits(31, True)
    assert hash(limits) == hash(EpisodeLimits(30, True)) and limits != "EpisodeLimits"
    assert RunSettings().limits == EpisodeLimits()
    rule = AvoidCollisionSettings(threshold=70.0)
    assert (rule.threshold, rule.max_speed) == (70.0, 6.28)
    assert repr(rule) == "AvoidCollisionSettings(threshold=70.0, max_speed=6.28)"
    tabular = TabularSettings(np.zeros((12, 4096, 12)), hold_spins=True, wheel_speed_limit=6.0)
    assert repr(tabular) == (
        "TabularSettings(tables=12, epsilon=0.0, hold_spins=True, hold_heading=False, "
        "wheel_speed_limit=6.0)"
    )
    active = np.ones(3, bool)
    settings = RunSettings(limits, seeds=[1, 2, 3], active=active)
    assert settings.active is active and settings.seeds == [1, 2, 3] and settings.trace is None
    assert repr(settings).startswith("RunSettings(limits=EpisodeLimits(max_steps=30")
    assert "active=<ndarray>" in repr(settings)
    bounds = StepBounds(np.zeros(11, np.float32), np.ones(11, np.float32), 6.28)
    for value in (limits, rule, bounds):
        for again in (pickle.loads(pickle.dumps(value)), copy.deepcopy(value)):
            assert repr(again) == repr(value)
    np.testing.assert_array_equal(pickle.loads(pickle.dumps(bounds)).high, bounds.high)
    with pytest.raises(AttributeError):
        limits.max_steps = 3  # type: ignore[misc]


@pytest.mark.parametrize(
    ("make", "says"),
    [
        (lambda: EpisodeLimits(max_steps=-1), "max_steps"),
        (lambda: EpisodeLimits(autoreset="yes"), "autoreset"),
        (lambda: AvoidCollisionSettings(max_speed=float("inf")), "max_speed"),
        (lambda: TabularSettings(np.zeros((4096, 12)), hold_heading=1.5), "hold_heading"),
        (lambda: RunSettings(limits={"max_steps": 3}), "expected limits to be an EpisodeLimits"),
        (lambda: RunSettings(seeds=[1, -2]), r"seeds\[1\]"),
        (lambda: RunSettings(seeds="12"), "seeds"),
        (lambda: RunSettings(active=np.ones(3)), "active"),
        (lambda: RunSettings(subtasks=[1, 2]), "expected subtasks to be a dict"),
        (lambda: StepBounds(np.zeros(11, np.float32), np.ones(10, np.float32), 6.28), "high"),
        (lambda: StepBounds(np.zeros(11), np.ones(11, np.float32), 6.28), "float32"),
        (lambda: StepBounds(np.zeros(11, np.float32), np.ones(11, np.float32), 0.0), "above 0"),
    ],
)
def test_bad_settings_are_refused_when_made(make: Any, says: str) -> None:
    with pytest.raises(mazesim.InvalidArgumentError, match=says):
        make()


def test_a_step_of_bounds_of_another_width_is_refused_before_it_moves() -> None:
    world = mazesim.load_world("seed-maze")
    simulator = mazesim.Simulator(world)
    env = mazesim.envs.EPuckMazeEnv(world="seed-maze", observation="goal")
    assert env._task is not None
    narrow = StepBounds(np.zeros(3, np.float32), np.ones(3, np.float32), 6.28)
    with pytest.raises(mazesim.InvalidArgumentError, match="expected bounds of 11 readings"):
        simulator.step_task(env._task.core, narrow, 1.0, 1.0)
    assert simulator.steps == 0
    with pytest.raises(mazesim.InvalidArgumentError, match="expected bounds to be a StepBounds"):
        simulator.step_task(env._task.core, (narrow.low, narrow.high), 1.0, 1.0)
