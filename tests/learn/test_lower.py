"""The lower level's training: rounds that depend on the settings alone."""

from __future__ import annotations

import numpy as np

from mazesim.learn.lower import LowerSettings, LowerTrainer, training_mazes
from mazesim.learn.train import TrainSettings

SMALL = LowerSettings(num_envs=20, total_steps=20 * 60 * 2, round_steps=60, maze_pool=6)


def test_a_round_is_the_same_with_1_or_2_threads() -> None:
    one, two = LowerTrainer(SMALL, threads=1), LowerTrainer(SMALL, threads=2)
    assert one.run_round(0) == two.run_round(0)
    assert np.array_equal(one.tables.q, two.tables.q)
    assert np.array_equal(one.tables.visits, two.tables.visits)


def test_a_resumed_trainer_goes_on_as_one_never_stopped() -> None:
    # Round 1's randomness is its own stream: a fresh trainer given round 0's tables goes on alike.
    straight = LowerTrainer(SMALL, threads=1)
    straight.run_round(0)
    stopped = LowerTrainer(SMALL, threads=1)
    stopped.run_round(0)
    resumed = LowerTrainer(SMALL, tables=stopped.tables, threads=1)
    assert straight.run_round(1) == resumed.run_round(1)
    assert np.array_equal(straight.tables.q, resumed.tables.q)


def test_rounds_learn_and_count_their_steps() -> None:
    trainer = LowerTrainer(SMALL, threads=1)
    stats = trainer.run_round(0)
    assert stats.env_steps == 20 * 60 and stats.epsilon == SMALL.epsilon_start
    assert trainer.tables.visits.sum() > 0 and np.any(trainer.tables.q != 0.0)
    assert 0.0 <= stats.contact_share <= 1.0


def test_the_maze_pool_depends_on_the_seed_alone() -> None:
    first = [world.to_toml() for world in training_mazes(0, 4)]
    assert first == [world.to_toml() for world in training_mazes(0, 4)]
    assert first != [world.to_toml() for world in training_mazes(1, 4)]


def test_train_settings_take_the_lower_levels_defaults() -> None:
    defaults, lower = TrainSettings(), LowerSettings()
    assert (defaults.envs, defaults.steps, defaults.seed, defaults.maze_pool) == (
        lower.num_envs,
        lower.total_steps,
        lower.seed,
        lower.maze_pool,
    )
