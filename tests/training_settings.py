"""Settings of training runs small enough for the tests (a few seconds each)."""

from __future__ import annotations

import numpy as np

from mazesim.learn.fleet import Fleet
from mazesim.learn.lower import LowerSettings, LowerTrainer
from mazesim.learn.tables import TrainedPolicy
from mazesim.learn.train import TrainSettings
from mazesim.transfer.randomise import parse_spec, robot_draw

__all__ = [
    "E_PUCK_ROUND",
    "TINY",
    "assert_same_navigator",
    "e_pucks",
    "trained",
    "trained_alike_at_one_and_two_threads",
]

#: Three lower-level rounds of 64 robots, four higher-level episodes.
TINY = TrainSettings(
    envs=64,
    steps=64 * 500 * 3,
    seed=11,
    maze_pool=8,
    higher_episodes=4,
    higher_envs=2,
    higher_max_steps=300,
    checkpoint_seconds=1e9,
)

#: Two lower-level rounds of 40 robots counting the door distance, driving on when blind.
E_PUCK_ROUND = LowerSettings(
    num_envs=40,
    total_steps=40 * 200 * 2,
    round_steps=200,
    maze_pool=6,
    seed=5,
    door_distance=True,
    blind_forward=True,
)


def e_pucks(settings: LowerSettings) -> Fleet:
    """E-pucks reading in the seed robot's volts, as ``--randomise robot=e-puck`` trains them."""
    fleet = robot_draw(parse_spec("robot=e-puck"), settings.seed)(0, settings.num_envs)
    assert isinstance(fleet, Fleet)
    return fleet


def trained(settings: LowerSettings, threads: int = 0) -> LowerTrainer:
    """A trainer of :func:`e_pucks` after every round of ``settings``."""
    trainer = LowerTrainer(settings, threads=threads, robot=e_pucks(settings))
    for k in range(settings.rounds):
        trainer.run_round(k)
    return trainer


def trained_alike_at_one_and_two_threads(settings: LowerSettings) -> LowerTrainer:
    """The one-thread trainer of :func:`e_pucks`, checked round by round against two threads."""
    one = LowerTrainer(settings, threads=1, robot=e_pucks(settings))
    two = LowerTrainer(settings, threads=2, robot=e_pucks(settings))
    for k in range(settings.rounds):
        assert one.run_round(k) == two.run_round(k)
    assert np.array_equal(one.tables.q, two.tables.q)
    return one


def assert_same_navigator(first: TrainedPolicy, second: TrainedPolicy) -> None:
    """Asserts that two trained navigators hold the same tables and training history."""
    assert first.lower_q is not None and second.lower_q is not None
    assert np.array_equal(first.lower_q, second.lower_q)
    assert first.higher_q is not None and second.higher_q is not None
    assert np.array_equal(first.higher_q, second.higher_q)
    assert first.training["history"] == second.training["history"]
