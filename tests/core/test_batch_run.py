"""``BatchSimulator.run``: many control steps in one call with a controller in the core.

Each run is checked against the same batch stepped from Python one step at a time with the
Python version of its controller (or, for controllers that draw random numbers, with the wheel
speeds the run recorded), bit for bit, over thread counts and batch sizes.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from typing import Any, Union

import numpy as np
import numpy.typing as npt
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mazesim
from batch_buffers import Buffers, buffers
from hostile import run_hostile
from mazesim.actions import WHEEL_SPEED_FRACTIONS
from mazesim.benchmark import braitenberg
from mazesim.controllers import AvoidCollision
from mazesim.learn.discretise import (
    NUM_SENSORS,
    SHARP_TABLE,
    distance_levels,
    encode_state,
    observation_states,
    volts_to_cm,
)
from mazesim.learn.qlearning import best_allowed

LIMIT = 40
#: What ``run`` takes as its controller.
Controller = Union[str, mazesim.AvoidCollisionSettings, mazesim.TabularSettings]
#: Episodes that end at the goal, or at a crossing, and stand still then.
AT_GOAL = mazesim.RunSettings(mazesim.EpisodeLimits(end_at_goal=True, autoreset=False))
AT_CROSSING = mazesim.RunSettings(mazesim.EpisodeLimits(end_at_crossing=True, autoreset=False))
MASK64 = (1 << 64) - 1


def next_seed(seed: int) -> int:
    """The seed an ended episode is reset with: the first SplitMix64 output from ``seed``."""
    z = (seed + 0x9E3779B97F4A7C15) & MASK64
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK64
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK64
    return z ^ (z >> 31)


def make_batch(
    n: int, robot: str = "e-puck", threads: int = 1, first: int = 0
) -> mazesim.BatchSimulator:
    """Envs ``first .. first + n`` of a family of distinct mazes, env i seeded with i."""
    worlds = [mazesim.generate_maze(5, 5, seed=50 + i, loops=0.1) for i in range(first, first + n)]
    return mazesim.BatchSimulator(worlds, robot=robot, seeds=first, threads=threads)


def trace_buffers(batch: mazesim.BatchSimulator, steps: int) -> dict[str, npt.NDArray[Any]]:
    n = batch.num_envs
    return {
        "observations": np.zeros((steps, n, batch.observation_width), np.float32),
        "poses": np.zeros((steps, n, 3), np.float32),
        "colliding": np.zeros((steps, n), bool),
        "crossings": np.zeros((steps, n), np.int32),
        "wheel_speeds": np.zeros((steps, n, 2), np.float32),
        "actions": np.zeros((steps, n), np.int32),
        "episode_ends": np.zeros((steps, n), bool),
    }


def run(
    batch: mazesim.BatchSimulator, steps: int, controller: Controller, seeds: int | None = None
) -> tuple[dict[str, npt.NDArray[Any]], Buffers, dict[str, npt.NDArray[np.uint64]]]:
    out = buffers(batch)
    batch.observe(*out)
    trace = trace_buffers(batch, steps)
    limits = mazesim.EpisodeLimits(max_steps=LIMIT)
    settings = mazesim.RunSettings(limits, seeds=seeds, trace=trace)
    counters = batch.run(steps, controller, *out, settings=settings)
    return trace, out, counters


def step_from_python(
    batch: mazesim.BatchSimulator,
    steps: int,
    choose: Callable[[int, npt.NDArray[np.float32]], npt.NDArray[np.float32]],
    first_seed: int = 0,
) -> npt.NDArray[np.float32]:
    """Steps ``batch`` with wheel speeds ``choose(step, observations)``, resetting each env whose
    episode reached ``LIMIT`` steps with the seed after its last; the observations of each step."""
    out = buffers(batch)
    batch.observe(*out)
    seeds = np.arange(first_seed, first_seed + batch.num_envs, dtype=np.uint64)
    trace = []
    for t in range(steps):
        batch.step(choose(t, out[0]), *out)
        trace.append(out[0].copy())
        ended = batch.steps() >= LIMIT
        following = np.array([next_seed(int(s)) for s in seeds], dtype=np.uint64)
        seeds = np.where(ended, following, seeds)
        batch.reset(*out, mask=ended, seeds=seeds)
    return np.stack(trace)


@pytest.mark.parametrize(("n", "threads"), [(5, 1), (33, 2), (40, 0)])
def test_braitenberg_run_equals_python_steps(n: int, threads: int) -> None:
    trace, out, counters = run(make_batch(n, threads=threads), 100, "braitenberg")
    actions = np.zeros((n, 2), np.float32)
    stepped = step_from_python(make_batch(n), 100, lambda _, obs: braitenberg(obs[:, :8], actions))
    np.testing.assert_array_equal(trace["observations"], stepped)
    assert trace["episode_ends"].sum() == counters["episodes_finished"].sum() > 0
    assert counters["steps_in_contact"].sum() == trace["colliding"].sum()
    assert (counters["steps"] == 100).all()


def test_avoid_collision_run_equals_python_steps() -> None:
    # A low threshold: sensor noise alone turns the robots both ways.
    controller = AvoidCollision(threshold=70.0)
    rule = mazesim.AvoidCollisionSettings(threshold=70.0)
    trace, _, _ = run(make_batch(24, threads=2), 90, rule)
    stepped = step_from_python(make_batch(24), 90, lambda _, obs: controller.batch(obs[:, :8]))
    np.testing.assert_array_equal(trace["observations"], stepped)
    wheels = trace["wheel_speeds"]
    assert (wheels[..., 0] == 0).any() and (wheels[..., 1] == 0).any()


@pytest.mark.parametrize("table_seed", range(8))
def test_tabular_run_acts_as_numpy_argmax_over_table_4_1(table_seed: int) -> None:
    rng = np.random.default_rng(table_seed)
    n, steps = 12, 60
    # Few distinct values, so that ties (the first maximum wins) are common.
    tables = rng.integers(0, 3, size=(3, 4096, 12)).astype(np.float64)
    allowed = rng.random((3, 12)) < 0.6
    allowed[:, rng.integers(0, 12)] = True
    roles = rng.integers(0, 3, size=n).astype(np.int64)
    batch = make_batch(n, robot="seed", threads=2)
    start = buffers(batch)
    batch.observe(*start)
    tabular = mazesim.TabularSettings(tables, allowed_actions=allowed, table_index=roles)
    trace, _, _ = run(batch, steps, tabular)
    ends = trace["episode_ends"]
    assert not ends[: LIMIT - 1].any() and ends[LIMIT - 1].all()
    before = np.concatenate([start[0][None], trace["observations"][:-1]])
    for t in range(min(steps, LIMIT)):
        states = observation_states(before[t])
        expected = best_allowed(tables[roles, states], allowed[roles])
        np.testing.assert_array_equal(trace["actions"][t], expected)
        np.testing.assert_array_equal(
            trace["wheel_speeds"][t],
            (WHEEL_SPEED_FRACTIONS[expected] * 6.28).astype(np.float32),
        )
    wheels = trace["wheel_speeds"]
    stepped = step_from_python(make_batch(n, robot="seed"), steps, lambda t, _: wheels[t])
    np.testing.assert_array_equal(trace["observations"], stepped)


@pytest.mark.parametrize("controller", ["random", "tabular"])
def test_random_draws_replay_from_python_and_ignore_threads_and_batch_size(
    controller: str,
) -> None:
    robot = "seed" if controller == "tabular" else "e-puck"
    table = np.random.default_rng(0).random((4096, 12))
    allowed = np.ones(12, bool)
    allowed[[3, 11]] = False
    rule: Controller = controller
    if controller == "tabular":
        rule = mazesim.TabularSettings(table, epsilon=0.5, allowed_actions=allowed)
    one, _, _ = run(make_batch(30, robot, threads=1), 80, rule, seeds=77)
    two, _, _ = run(make_batch(30, robot, threads=2), 80, rule, seeds=77)
    for key in one:
        np.testing.assert_array_equal(one[key], two[key])
    # Env 17 alone, in a batch of one, with the seeds env 17 had in the batch of 30.
    alone, _, _ = run(make_batch(1, robot, first=17), 80, rule, seeds=94)
    for key in one:
        np.testing.assert_array_equal(alone[key][:, 0], one[key][:, 17])
    wheels = one["wheel_speeds"]
    stepped = step_from_python(make_batch(30, robot), 80, lambda t, _: wheels[t])
    np.testing.assert_array_equal(one["observations"], stepped)
    if controller == "tabular":
        assert not np.isin(one["actions"], [3, 11]).any()
        assert len(np.unique(one["actions"])) == 10
    else:
        assert (np.abs(wheels) <= 6.28).all() and wheels.std() > 2.0


def test_goal_ends_episodes_and_without_autoreset_envs_stand_still() -> None:
    world = mazesim.load_world("seed-maze")
    gx, gy, radius = world.goal
    batch = mazesim.BatchSimulator(world, num_envs=3, threads=1)
    # Just outside the goal disc, facing its centre.
    batch.set_starts(np.array([[gx + radius + 0.01, gy, np.pi]] * 3))
    out = buffers(batch)
    batch.reset(*out)
    trace = trace_buffers(batch, 30)
    limits = AT_GOAL.limits
    settings = mazesim.RunSettings(limits, trace=trace)
    counters = batch.run(30, "braitenberg", *out, settings=settings)
    assert counters["goals_reached"].tolist() == [1, 1, 1]
    ended = int(np.argmax(trace["episode_ends"][:, 0]))
    assert 0 < ended < 29 and counters["steps"].tolist() == [ended + 1] * 3
    assert trace["episode_ends"].sum() == 3
    inside = np.hypot(trace["poses"][ended, :, 0] - gx, trace["poses"][ended, :, 1] - gy)
    assert (inside <= radius).all()
    np.testing.assert_array_equal(trace["poses"][-1], trace["poses"][ended])
    assert (trace["actions"] == -1).all() and (trace["wheel_speeds"][ended + 1 :] == 0).all()
    again = batch.run(5, "braitenberg", *out, settings=AT_GOAL)
    assert again["steps"].tolist() == [0, 0, 0]
    standing = mazesim.RunSettings(mazesim.EpisodeLimits(autoreset=False))
    moving = batch.run(5, "braitenberg", *out, settings=standing)
    assert moving["steps"].tolist() == [5, 5, 5]


def test_each_env_ends_at_its_own_goal_from_set_goals_at() -> None:
    world = mazesim.load_world("seed-maze")
    gx, gy, radius = world.goal
    batch = mazesim.BatchSimulator(world, num_envs=3, threads=1)
    starts = np.array([[gx + radius + 0.01, gy, np.pi]] * 3)
    batch.set_starts(starts)
    # Env 1's goal moves to the start cell's west neighbour; env 2's to a far corner.
    batch.set_goals_at(np.array([1, 2]), np.array([[gx - 0.25, gy, 0.08], [0.125, 0.125, 0.08]]))
    goals = batch.goals()
    assert goals[0].tolist() == list(world.goal)
    assert goals[1].tolist() == [gx - 0.25, gy, 0.08] and goals[2].tolist() == [0.125, 0.125, 0.08]
    out = buffers(batch)
    batch.reset(*out)
    counters = batch.run(30, "braitenberg", *out, settings=AT_GOAL)
    assert counters["goals_reached"].tolist() == [1, 0, 0]
    # A bad row changes nothing and names its environment.
    with pytest.raises(mazesim.InvalidArgumentError, match="environment 2: .*radius"):
        batch.set_goals_at(np.array([0, 2]), np.array([[0.1, 0.1, 0.1], [0.1, 0.1, 0.0]]))
    assert batch.goals()[0].tolist() == list(world.goal)
    # A snapshot carries an env's own goal; set_world goes back to the world's.
    snapshot = batch.snapshot_env(2)
    batch.restore_env(0, snapshot)
    assert batch.goals()[0].tolist() == [0.125, 0.125, 0.08]
    batch.set_world(2, world, 0)
    assert batch.goals()[2].tolist() == list(world.goal)
    single = mazesim.Simulator(world)
    single.set_goal(0.5, 0.5, 0.1)
    assert single.goal == (0.5, 0.5, 0.1)
    copy = mazesim.Simulator(world)
    copy.restore(single.snapshot())
    assert copy.goal == (0.5, 0.5, 0.1)
    assert mazesim.Simulator(mazesim.load_world("arena")).goal is None


def _bad_calls() -> list[tuple[Any, dict[str, Any], str]]:
    """(the controller, or a function that makes it; the keywords of RunSettings; what the
    error says)."""
    q = np.zeros((4096, 12))

    def tabular(table: Any, **options: Any) -> Callable[[], mazesim.TabularSettings]:
        return lambda: mazesim.TabularSettings(table, **options)

    return [
        ("spin", {}, "expected controller to be"),
        (7, {}, "expected controller to be"),
        ("tabular", {}, "needs its tables"),
        (tabular(np.zeros((4096, 11))), {}, "table"),
        (tabular(q.astype(np.float32)), {}, "float64"),
        (tabular(np.full((4096, 12), np.nan)), {}, "state 0, action 0"),
        (tabular(q, allowed_actions=np.zeros(12, bool)), {}, "allowed action"),
        (tabular(q, table_index=np.array([0, 1, 0, 0])), {}, "table indices"),
        (tabular(q, table_index=np.array([0, -1, 0, 0])), {}, "table_index"),
        (tabular(q, table_index=np.array([0, 0])), {}, "one table index per environment (4)"),
        (tabular(q, epsilon=2.0), {}, "epsilon"),
        (tabular(q, wheel_speed_limit=0.0), {}, "wheel speed limit"),
        ("braitenberg", {"seeds": [1, 2]}, "expected 4 seeds"),
        ("braitenberg", {"limits": 40}, "expected limits to be an EpisodeLimits"),
        ("braitenberg", {"trace": [np.zeros((3, 4), bool)]}, "expected trace to be a dict"),
        ("braitenberg", {"trace": {"speeds": np.zeros((3, 4, 2), np.float32)}}, "trace keys"),
        ("braitenberg", {"trace": {"poses": np.zeros((3, 4, 3))}}, 'trace["poses"]'),
        ("braitenberg", {"trace": {"poses": np.zeros((2, 4, 3), np.float32)}}, "(3, 4, 3)"),
        (lambda: mazesim.AvoidCollisionSettings(threshold=float("nan")), {}, "threshold"),
    ]


@pytest.mark.parametrize(("controller", "options", "says"), _bad_calls())
def test_bad_arguments_raise_before_anything_moves(
    controller: Any, options: dict[str, Any], says: str
) -> None:
    batch = make_batch(4, robot="e-puck" if isinstance(controller, str) else "seed")
    out = buffers(batch)
    with pytest.raises(mazesim.InvalidArgumentError) as caught:
        made = controller() if callable(controller) else controller
        batch.run(3, made, *out, settings=mazesim.RunSettings(**options))
    assert says in str(caught.value)
    assert (batch.steps() == 0).all()


def test_a_robot_without_the_sensors_of_the_controller_is_refused() -> None:
    batch = make_batch(2, robot="seed")
    with pytest.raises(mazesim.InvalidArgumentError, match="reads 8 distance sensors"):
        batch.run(3, "braitenberg", *buffers(batch))
    with pytest.raises(mazesim.InvalidArgumentError, match="steps"):
        batch.run(-1, "random", *buffers(batch))


def test_ctrl_c_stops_a_long_run() -> None:
    body = """
    import os, signal, threading
    b = _core.BatchSimulator(_core.World.builtin("arena"), num_envs=64, threads=2)
    out = buffers(b)
    threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
    try:
        b.run(10**9, "random", *out)
        print("NOT INTERRUPTED")
    except KeyboardInterrupt:
        print("INTERRUPTED")
    """
    outcome = run_hostile(body)
    assert outcome.ok and "INTERRUPTED" in outcome.stdout, outcome.describe()
    assert "NOT INTERRUPTED" not in outcome.stdout


_TABLE_VOLTS = [volts for _, volts in SHARP_TABLE]


@settings(max_examples=300, deadline=None)
@given(
    st.lists(
        st.one_of(
            st.floats(0.0, 4.0, width=32),
            st.sampled_from(_TABLE_VOLTS),
            st.floats(-10.0, 10.0, width=32, allow_subnormal=True),
            st.sampled_from([math.nan, math.inf, -math.inf]),
        ),
        min_size=6,
        max_size=6 * 20,
    ).filter(lambda v: len(v) % 6 == 0),
    st.integers(0, 5),
)
def test_the_core_discretises_as_numpy_does(volts: list[float], extra: int) -> None:
    """The core and a numpy reference (the table inverted, then Table 4.1) give the same states,
    or both refuse a reading below 0 V, infinite or NaN with the same words, quoting the same
    reading (NaN first, else the lowest)."""
    rows = np.array(volts, dtype=np.float32).reshape(-1, 6)
    observations = np.concatenate([rows, np.full((len(rows), extra), 500.0, np.float32)], axis=1)
    refused = rows[~((rows >= 0.0) & (rows < np.inf))]
    if refused.size:
        wanted = math.nan if np.isnan(refused).any() else float(refused.min())
        with pytest.raises(mazesim.InvalidArgumentError, match="readings of 0 V or more") as core:
            mazesim._core.lower_level_states(observations)
        with pytest.raises(mazesim.InvalidArgumentError, match="readings of 0 V or more") as numpy:
            _numpy_states(observations)
        for refusal in (core.value, numpy.value):
            found = re.search(r"found (\S+) V", str(refusal))
            assert found is not None and repr(float(found[1])) == repr(wanted), refusal
        return
    np.testing.assert_array_equal(
        mazesim._core.lower_level_states(observations), _numpy_states(observations)
    )


def _numpy_states(observations: npt.NDArray[np.float32]) -> npt.NDArray[np.int64]:
    """The states of ``observations`` worked out in numpy: each of the first six readings turned
    into cm, then into its Table 4.1 level, the levels read as a base-4 number."""
    levels = distance_levels(volts_to_cm(observations[:, :NUM_SENSORS]))
    return np.asarray(encode_state(levels), dtype=np.int64)


def test_lower_level_states_refuses_rows_too_short() -> None:
    with pytest.raises(mazesim.InvalidArgumentError, match=r"\(N, >= 6\)"):
        mazesim._core.lower_level_states(np.zeros((3, 5), np.float32))
    with pytest.raises(mazesim.InvalidArgumentError, match="float32"):
        mazesim._core.lower_level_states(np.zeros((3, 6)))


def test_a_crossing_stops_an_env_for_the_rest_of_the_call_only() -> None:
    batch = make_batch(64, threads=2)
    out = buffers(batch)
    batch.reset(*out)
    trace = trace_buffers(batch, 400)
    settings = mazesim.RunSettings(AT_CROSSING.limits, trace=trace)
    counters = batch.run(400, "braitenberg", *out, settings=settings)
    crossed = (trace["crossings"] != 0).any(axis=0)
    assert crossed.any() and not crossed.all()
    first = np.argmax(trace["crossings"] != 0, axis=0)
    np.testing.assert_array_equal(counters["steps"], np.where(crossed, first + 1, 400))
    np.testing.assert_array_equal(trace["episode_ends"].sum(axis=0), crossed)
    env = int(np.flatnonzero(crossed)[0])
    np.testing.assert_array_equal(trace["poses"][-1, env], trace["poses"][first[env], env])
    # The next call moves the stopped envs on.
    again = batch.run(10, "braitenberg", *out, settings=AT_CROSSING)
    assert (again["steps"][crossed] > 0).all()
