"""The sweep's trainers ``hrl`` and ``baseline``: a setting mapped onto the learning layer's
configs, trained and evaluated there, and its learning curve gathered.

``hrl`` runs :func:`mazesim.learn.train.run_training` (the pipeline of ``mazesim train``), then
greedy episodes (:func:`mazesim.learn.evaluate.evaluate`). The setting maps onto it as follows:

- ``world`` / ``maze_size``, ``maze_seed``, ``loops``: the world the higher level learns and the
  navigator is evaluated in (it needs a cell maze and a goal);
- ``envs``, ``steps``: the lower level's robots and control steps per robot, in rounds of at most
  500 steps (:attr:`mazesim.learn.lower.LowerSettings.round_steps`) of equal length, so the
  budget is ``envs x steps`` env-steps rounded up to whole rounds;
- ``learning_rate``, ``epsilon``, ``discount``: the lower level's first learning rate of a
  state-action pair, first-round exploration and gamma (:data:`HRL_DEFAULTS` when left out);
- ``higher_episodes``: the higher level's training episodes; ``episode_steps``: control steps
  after which a higher-level or evaluation episode fails;
- ``eval_episodes``: greedy evaluation episodes; ``seed``: everything random.

``baseline`` (also named ``flat-q``) trains the one flat learner,
:func:`mazesim.learn.baseline.train_flat`, on the setting's world for ``envs x steps`` env-steps
with ``envs`` robots and evaluates it the same way; ``learning_rate``, ``epsilon``, ``discount``,
``collision_penalty`` and ``episode_steps`` set the fields of its
:class:`~mazesim.learn.baseline.FlatConfig` (whose defaults are :data:`FLAT_DEFAULTS`).

Both are seeded: the tables depend on the setting alone, not on the thread count or the machine.
Evaluation episodes draw their start jitter and sensor noise from the ``evaluate/episode``
stream of the seed (:mod:`mazesim._seeding`), which no training episode uses. ``mean_steps`` in
the result is over all evaluation episodes (an episode that fails counts its ``episode_steps``).
"""

from __future__ import annotations

import dataclasses
import math
import time
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from mazesim._core import World
from mazesim.episodes import MAX_STEPS
from mazesim.errors import InvalidArgumentError, _shown
from mazesim.learn.baseline import FlatConfig, FlatNavigator, train_flat
from mazesim.learn.evaluate import evaluate
from mazesim.learn.higher_training import HigherTraining
from mazesim.learn.learning_curve import CurvePoints, episode_progress
from mazesim.learn.lower import LowerSettings
from mazesim.learn.policy import HierarchicalPolicy
from mazesim.learn.qlearning import LearningRate
from mazesim.learn.summary import Summary
from mazesim.learn.train import TrainSettings, run_training
from mazesim.maze import checkpoint_ids

if TYPE_CHECKING:
    from mazesim.distributed.config import Setting

__all__ = [
    "FLAT_DEFAULTS",
    "HRL_DEFAULTS",
    "flat_config",
    "train_baseline",
    "train_hrl",
]

_LOWER = LowerSettings()
_TRAIN = TrainSettings()
#: What ``hrl`` uses for the hyperparameters a setting leaves out (those of ``mazesim train``).
HRL_DEFAULTS: dict[str, Any] = {
    "learning_rate": _LOWER.rate.initial,
    "epsilon": _LOWER.epsilon_start,
    "discount": _LOWER.gamma,
    "higher_episodes": _TRAIN.higher_episodes,
    "episode_steps": MAX_STEPS,
}
_FLAT = FlatConfig()
#: What ``baseline`` uses for the hyperparameters a setting leaves out (its config's defaults).
FLAT_DEFAULTS: dict[str, Any] = {
    "learning_rate": _FLAT.learning_rate,
    "epsilon": _FLAT.epsilon_start,
    "discount": _FLAT.gamma,
    "collision_penalty": -_FLAT.contact_reward,
    "episode_steps": _FLAT.max_steps,
}


def _maze_world(setting: Setting, trainer: str) -> World:
    world = setting.world()
    if world.goal is None or world.cell_maze() is None:
        raise InvalidArgumentError(
            f"setting {setting.id}: trainer {_shown(trainer)} needs a world with a [grid] maze "
            "and a "
            f"goal; {_shown(world.name)} has {'no goal' if world.goal is None else 'no cell maze'}"
        )
    return world


def _value(setting: Setting, name: str, defaults: dict[str, Any] = HRL_DEFAULTS) -> Any:
    value = setting.params.get(name)
    return defaults[name] if value is None else value


def flat_config(setting: Setting) -> FlatConfig:
    """The flat learner's config of a setting: its hyperparameters over :data:`FLAT_DEFAULTS`."""
    return dataclasses.replace(
        _FLAT,
        learning_rate=float(_value(setting, "learning_rate", FLAT_DEFAULTS)),
        epsilon_start=float(_value(setting, "epsilon", FLAT_DEFAULTS)),
        gamma=float(_value(setting, "discount", FLAT_DEFAULTS)),
        contact_reward=-float(_value(setting, "collision_penalty", FLAT_DEFAULTS)),
        max_steps=int(_value(setting, "episode_steps", FLAT_DEFAULTS)),
    )


def _lower_settings(setting: Setting) -> LowerSettings:
    """The lower level's settings: ``steps`` in equal rounds of at most 500 steps."""
    steps = int(setting.params["steps"])
    rounds = math.ceil(steps / _LOWER.round_steps)
    round_steps = math.ceil(steps / rounds)
    envs = int(setting.params["envs"])
    initial = float(_value(setting, "learning_rate"))
    return LowerSettings(
        num_envs=envs,
        total_steps=rounds * round_steps * envs,
        round_steps=round_steps,
        seed=setting.seed,
        gamma=float(_value(setting, "discount")),
        epsilon_start=float(_value(setting, "epsilon")),
        rate=LearningRate(
            initial=initial, floor=min(_LOWER.rate.floor, initial), power=_LOWER.rate.power
        ),
    )


def _evaluation(summary: Summary) -> dict[str, float]:
    """A sweep's evaluation values, read from the evaluator's one result type."""
    return {
        "success_rate": summary.success_rate,
        "mean_collisions": summary.mean_collisions,
        "mean_steps": summary.mean_steps_all,
    }


def train_hrl(setting: Setting, threads: int = 1) -> dict[str, Any]:
    """Trains the hierarchical navigator for one setting (:func:`mazesim.learn.train.run_training`)
    and evaluates it greedily (:func:`mazesim.learn.evaluate.evaluate`).

    Args:
        setting: The setting (see the module for how its parameters are used).
        threads: Threads of the batch engine (the result does not depend on them).

    Returns:
        A dict with ``tables`` (``lower_q`` and ``lower_visits``, stacked as
        :class:`mazesim.learn.lower.LowerTables`; ``higher_q``, ``higher_visits`` and the world's
        ``checkpoint_ids``), ``curves`` (the learning curve of ``mazesim train``,
        :mod:`mazesim.learn.learning_curve`: a row per lower-level round, ``stage`` ``lower``,
        then one each time higher-level episodes end, ``stage`` ``higher``), ``evaluation``,
        ``env_steps`` (both stages), ``eval_env_steps``, ``training_seconds`` and
        ``evaluation_seconds``.

    Raises:
        InvalidArgumentError: The world has no cell maze or no goal.
    """
    started = time.perf_counter()
    world = _maze_world(setting, "hrl")
    lower = _lower_settings(setting)
    episodes = int(_value(setting, "higher_episodes"))
    max_steps = int(_value(setting, "episode_steps"))
    higher = HigherTraining(
        episodes_per_world=episodes,
        envs_per_world=min(_TRAIN.higher_envs, episodes),
        max_steps=max_steps,
        seed=setting.seed,
    )
    curve = CurvePoints()
    run = run_training(lower, higher, world, threads=threads, curve=curve)
    assert run is not None  # no checkpoint callback, so it runs to its end
    env_steps = sum(stats.env_steps for stats in run.round_stats)
    env_steps += sum(result.steps for result in run.higher_results)
    training_seconds = time.perf_counter() - started

    started = time.perf_counter()
    lower_q, level = run.tables.q, run.level

    def make_navigator(world_of_env: npt.NDArray[np.int64]) -> HierarchicalPolicy:
        return HierarchicalPolicy(lower_q, level, world_of_env)

    summary = evaluate(
        make_navigator,
        [world],
        int(setting.params["eval_episodes"]),
        seed=setting.seed,
        max_steps=max_steps,
        threads=threads,
    )
    evaluation_seconds = time.perf_counter() - started
    return {
        "tables": {
            "lower_q": lower_q,
            "lower_visits": run.tables.visits,
            "higher_q": level.q[0],
            "higher_visits": level.visits[0],
            "checkpoint_ids": np.array(level.checkpoint_ids[0], dtype=np.int64),
        },
        "curves": {name: np.asarray(values) for name, values in curve.columns().items()},
        "evaluation": _evaluation(summary),
        "env_steps": env_steps,
        "eval_env_steps": summary.env_steps,
        "training_seconds": training_seconds,
        "evaluation_seconds": evaluation_seconds,
    }


def train_baseline(setting: Setting, threads: int = 1) -> dict[str, Any]:
    """Trains the flat baseline of :mod:`mazesim.learn.baseline` for one setting and evaluates it.

    Args:
        setting: The setting: its world, ``envs``, ``steps`` (``envs x steps`` env-steps),
            the hyperparameters of :func:`flat_config`, ``eval_episodes`` and ``seed``.
        threads: Threads of the batch engine (the result does not depend on them).

    Returns:
        A dict with ``tables`` (``flat_q`` and the world's ``checkpoint_ids``), ``curves``
        (the learning curve of ``mazesim train --flat``: a row each time training episodes end,
        ``stage`` ``flat``), ``evaluation``, ``env_steps``, ``eval_env_steps``,
        ``training_seconds`` and ``evaluation_seconds``.

    Raises:
        InvalidArgumentError: The world has no cell maze or no goal.
    """
    started = time.perf_counter()
    world = _maze_world(setting, "baseline")
    envs, steps = int(setting.params["envs"]), int(setting.params["steps"])
    config = flat_config(setting)
    curve = CurvePoints()
    q, _ = train_flat(
        world,
        envs * steps,
        num_envs=envs,
        seed=setting.seed,
        threads=threads,
        config=config,
        progress=episode_progress("flat", None, curve),
    )
    training_seconds = time.perf_counter() - started

    started = time.perf_counter()
    ids = checkpoint_ids(world)

    def make_navigator(world_of_env: npt.NDArray[np.int64]) -> FlatNavigator:
        return FlatNavigator(q, ids, world_of_env.size)

    summary = evaluate(
        make_navigator,
        [world],
        int(setting.params["eval_episodes"]),
        seed=setting.seed,
        max_steps=config.max_steps,
        threads=threads,
    )
    evaluation_seconds = time.perf_counter() - started
    return {
        "tables": {"flat_q": q, "checkpoint_ids": np.array(sorted(ids), dtype=np.int64)},
        "curves": {name: np.asarray(values) for name, values in curve.columns().items()},
        "evaluation": _evaluation(summary),
        "env_steps": envs * steps,
        "eval_env_steps": summary.env_steps,
        "training_seconds": training_seconds,
        "evaluation_seconds": evaluation_seconds,
    }
