"""Steady-state measurement: warm-up first, timed blocks, episodes reset as they end."""

from __future__ import annotations

import numpy as np
import pytest

from mazesim.benchmark import MIN_WARMUP_STEPS, BenchSettings, SteadyState, measure
from mazesim.benchmark.fresh import measure_in_fresh_process
from mazesim.benchmark.steady import make_worlds
from mazesim.errors import InvalidArgumentError, MazesimError


def episode_clock(run: SteadyState) -> list[int]:
    """Steps of each env's current episode."""
    return ((run.episode_offset + run.steps_done) % run.settings.episode_steps).tolist()


def small(**fields: object) -> BenchSettings:
    base = dict(envs=4, block_steps=50, blocks=3, episode_steps=100, threads=1)
    base.update(fields)
    return BenchSettings(**base)  # type: ignore[arg-type]


def test_blocks_start_after_the_warm_up_and_follow_each_other() -> None:
    report = measure(small())
    assert report["warmup_steps_done"] == MIN_WARMUP_STEPS
    assert [b["first_step"] for b in report["blocks"]] == [1000, 1050, 1100]
    for block in report["blocks"]:
        assert block["steps"] == 50 and block["env_steps"] == 200
        assert block["wall_seconds"] > 0 and block["cpu_seconds"] >= 0
        assert block["env_steps_per_s"] == pytest.approx(200 / block["wall_seconds"])
    low, high = report["env_steps_per_s_range"]
    assert low <= report["env_steps_per_s"] <= high


def test_episodes_end_at_the_step_limit_staggered_over_the_envs() -> None:
    report = measure(small())
    # 4 envs, 100-step episodes started 25 steps apart: one reset every 25 steps, 2 a block.
    assert [b["episodes_ended"] for b in report["blocks"]] == [2, 2, 2]
    run = SteadyState(small())
    assert episode_clock(run) == [0, 25, 50, 75]
    run.advance(30)
    assert episode_clock(run) == [30, 55, 80, 5]


def test_a_reset_env_is_back_at_its_start() -> None:
    run = SteadyState(small(envs=2, episode_steps=40, workload="random"))
    start = run.poses.copy()
    run.advance(39)  # env 1 (20 steps in at first) ended its episode at step 20
    assert not np.allclose(run.poses[0], start[0], atol=1e-3)
    run.advance(1)  # env 0 reaches 40 steps: reset
    assert np.array_equal(run.poses[0], start[0])


@pytest.mark.parametrize(
    ("workload", "low", "high"),
    [("braitenberg", 0.0, 0.1), ("contact", 0.35, 0.75), ("random", 0.0, 0.1)],
)
def test_each_workload_reports_its_contact_share(workload: str, low: float, high: float) -> None:
    settings = small(envs=32, workload=workload, block_steps=120, blocks=2, episode_steps=1000)
    report = measure(settings)
    assert low <= report["contact_share"] <= high
    blocks = report["blocks"]
    total = sum(b["contact_steps"] for b in blocks) / sum(b["env_steps"] for b in blocks)
    assert report["contact_share"] == pytest.approx(total)


def test_contact_workload_touches_walls_far_more_than_braitenberg() -> None:
    shares = {
        w: measure(small(envs=32, workload=w, block_steps=240, blocks=1, episode_steps=1000))[
            "contact_share"
        ]
        for w in ("braitenberg", "contact")
    }
    assert shares["contact"] > 5 * shares["braitenberg"]


def test_same_settings_replay_whatever_the_threads() -> None:
    def poses(threads: int) -> np.ndarray:
        run = SteadyState(small(envs=6, workload="random", seed=5, threads=threads))
        run.advance(MIN_WARMUP_STEPS + 30)
        return run.poses.copy()

    assert np.array_equal(poses(1), poses(2))


def test_shared_mazes_are_one_world_for_every_env() -> None:
    shared = make_worlds(3, "shared", seed=2)
    distinct = make_worlds(3, "distinct", seed=2)
    assert len(shared) == 1 and len(distinct) == 3
    assert np.array_equal(shared[0].wall_boxes(), distinct[0].wall_boxes())
    assert not np.array_equal(distinct[0].wall_boxes(), distinct[1].wall_boxes())
    run = SteadyState(small(envs=3, mazes="shared"))
    assert run.batch.num_envs == 3 and run.advance(10)[0] >= 0


def test_memory_per_env_comes_from_a_fresh_process() -> None:
    def bytes_per_env(mazes: str) -> float:
        report = measure_in_fresh_process(small(envs=256, mazes=mazes, blocks=1, block_steps=10))
        memory = report["memory"]
        assert memory["engine_bytes_per_env"] > 0
        resident: float = memory["resident_bytes_per_env"]
        return resident

    distinct, shared = bytes_per_env("distinct"), bytes_per_env("shared")
    assert distinct > 1000 and shared > 0
    assert shared < distinct  # 255 fewer mazes to hold


@pytest.mark.parametrize(
    ("field", "value", "message"),
    [
        # A count out of its range and a registered name: refused when the settings are made.
        ("warmup_steps", 999, "warmup_steps to be a whole number from 1,000 to .*, found 999"),
        ("envs", 0, "envs to be a whole number from 1 to .*, found 0"),
        ("workload", "push", "expected workload to be one of braitenberg, contact, random"),
        ("mazes", "same", "expected mazes to be one of distinct, shared; found 'same'"),
    ],
)
def test_bad_settings_are_refused(field: str, value: object, message: str) -> None:
    with pytest.raises(MazesimError, match=message):
        SteadyState(small(**{field: value}))


def test_many_steps_per_call_replay_single_steps_bit_for_bit() -> None:
    # Episodes of 100 steps over 4 envs end at multiples of 25 steps: calls of 25 steps reset
    # the same envs at the same steps as single steps do, and the engine's Braitenberg rule is
    # the numpy one, so both ways give the very same batch.
    def final(per_call: int) -> tuple[np.ndarray, np.ndarray, tuple[int, int]]:
        run = SteadyState(small(steps_per_call=per_call, threads=2))
        counts = run.advance(MIN_WARMUP_STEPS + 150)
        return run.poses.copy(), run.observations.copy(), counts

    poses_1, obs_1, counts_1 = final(1)
    poses_25, obs_25, counts_25 = final(25)
    assert np.array_equal(poses_1, poses_25)
    assert np.array_equal(obs_1, obs_25)
    assert counts_1 == counts_25


def test_many_steps_per_call_keep_the_blocks_and_episodes() -> None:
    report = measure(small(steps_per_call=50, workload="random"))
    assert [b["first_step"] for b in report["blocks"]] == [1000, 1050, 1100]
    assert [b["episodes_ended"] for b in report["blocks"]] == [2, 2, 2]
    assert report["settings"]["steps_per_call"] == 50


def test_the_random_workload_in_the_engine_draws_afresh_in_every_call() -> None:
    run = SteadyState(small(envs=2, steps_per_call=10, workload="random", episode_steps=10_000))
    headings = []
    for _ in range(3):
        headings.append(run.poses[:, 2].astype(np.float64))
        run.advance(10)
    headings.append(run.poses[:, 2].astype(np.float64))
    # A robot's turn over a call depends on its wheel speeds only: calls that repeated their
    # draws would turn every robot by the same angle each time.
    turns = np.angle(np.exp(1j * np.diff(headings, axis=0)))
    assert not np.allclose(turns[1], turns[2], atol=1e-4)


def test_a_workload_without_an_engine_controller_runs_one_step_per_call() -> None:
    with pytest.raises(InvalidArgumentError, match="contact workload runs one step per call"):
        SteadyState(small(workload="contact", steps_per_call=10))


def test_a_seed_too_large_for_the_last_env_is_refused() -> None:
    with pytest.raises(InvalidArgumentError, match="at most 2\\^64 - 4 for 4 envs"):
        SteadyState(small(seed=2**64 - 2))


def test_a_huge_episode_limit_costs_no_memory() -> None:
    # The envs ending at a step are computed, not looked up in a table per step of an episode.
    run = SteadyState(small(episode_steps=2**31 - 1))
    _, episodes = run.advance(10)
    assert episodes == 0
    assert episode_clock(run) == [10, 536870921, 1073741833, 1610612745]
