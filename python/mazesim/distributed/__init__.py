"""Training sweeps and evaluations spread over a Ray cluster (or run one after the other).

A sweep file (:mod:`mazesim.distributed.config`) lists a grid of training settings; each setting
is one task (:mod:`mazesim.distributed.tasks`): train, evaluate, hand back the tables and curves.
:func:`run_sweep` runs the tasks on Ray, a local instance or an existing cluster, and gathers
everything into one output folder (:mod:`mazesim.distributed.output`); :func:`run_sequential`
runs the same tasks in this process. A setting names its trainer: ``hrl`` or ``baseline``
(also named ``flat-q``): :mod:`mazesim.distributed.hrl_trainers`, mazesim's navigator and its one
flat learner. :func:`evaluate_episodes` spreads the episodes of an evaluation over Ray workers
(``mazesim eval --address``: :mod:`mazesim.distributed.episodes`, running the chunks of
:mod:`mazesim.learn.episode_ranges`).

Ray is optional (``pip install "mazesim[ray]"``): this package imports it only when it runs
something on Ray.

Example:
    >>> from mazesim.distributed import parse_sweep_config
    >>> sweep = parse_sweep_config("[grid]\\nseed = [0, 1]\\nlearning_rate = [0.1, 0.3]\\n")
    >>> len(sweep.settings), sweep.settings[0].label
    (4, 'learning_rate=0.1')
"""

from __future__ import annotations

from mazesim.distributed.config import (
    PARAMETERS,
    Setting,
    SweepConfig,
    load_sweep_config,
    parse_sweep_config,
)
from mazesim.distributed.episodes import evaluate_episodes
from mazesim.distributed.runner import SweepSummary, run_sequential, run_sweep
from mazesim.distributed.tasks import TaskOutput, train_and_evaluate

__all__ = [
    "PARAMETERS",
    "Setting",
    "SweepConfig",
    "SweepSummary",
    "TaskOutput",
    "evaluate_episodes",
    "load_sweep_config",
    "parse_sweep_config",
    "run_sequential",
    "run_sweep",
    "train_and_evaluate",
]
