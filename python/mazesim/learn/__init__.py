"""Hierarchical Q-learning navigation of the report's chapter 4, done so that it reaches the goal.

The learning layer: algorithms only. It runs its episodes through :mod:`mazesim.episodes`
(which steps :mod:`mazesim.batch` and reads :mod:`mazesim.maze`), draws every random number from
the named streams of :mod:`mazesim._seeding`, and imports nothing of the command line, of Ray
(:mod:`mazesim.distributed`) or of ROS.

Two levels, as the report's section 4.1 describes them:

- the **lower level** (:mod:`mazesim.learn.subtasks`): four sub-tasks, "Corridors and Corners",
  "Right turn on a door", "Left turn on a door" and "Going forward on a door", each a tabular
  Q-learner over the twelve primitive actions (:mod:`mazesim.actions`) on the six Sharp distances
  discretised by Table 4.1 (:mod:`mazesim.learn.discretise`), trained on generated mazes with
  thousands of robots at once (:mod:`mazesim.learn.lower`);
- the **higher level** (:mod:`mazesim.learn.higher`): at each checkpoint event, a barcode crossed,
  it chooses the sub-task by SMDP Q-learning over (checkpoint, direction), trained on the target
  world (:mod:`mazesim.learn.higher_training`).

:mod:`mazesim.learn.policy` runs both levels (Alg. 5); :mod:`mazesim.learn.train` trains from
scratch with checkpoints and resume; :mod:`mazesim.learn.tables` saves and loads the tables;
:mod:`mazesim.learn.evaluate` measures a navigator (its one result type,
:class:`~mazesim.learn.summary.Summary`); :mod:`mazesim.learn.baseline` is the one flat
Q-learner, for comparison. Trained tables for ``seed-maze`` ship in the package (``mazesim eval``
uses them by default). ``mazesim.hrl``, this package's former name, still imports, with a
:class:`DeprecationWarning`.
"""

from __future__ import annotations

from mazesim.learn.discretise import (
    LEVEL_EDGES_CM,
    NUM_STATES,
    SENSOR_ORDER,
    decode_state,
    distance_levels,
    encode_state,
    observation_states,
    volts_to_cm,
)
from mazesim.learn.evaluate import EvaluationRecord, evaluate_navigator
from mazesim.learn.policy import HierarchicalPolicy
from mazesim.learn.subtasks import SUBTASK_NAMES, SubTask
from mazesim.learn.summary import Summary, summarise
from mazesim.learn.tables import TrainedPolicy, load_policy, save_policy
from mazesim.learn.train import TrainSettings, train

__all__ = [
    "LEVEL_EDGES_CM",
    "NUM_STATES",
    "SENSOR_ORDER",
    "SUBTASK_NAMES",
    "EvaluationRecord",
    "HierarchicalPolicy",
    "SubTask",
    "Summary",
    "TrainSettings",
    "TrainedPolicy",
    "decode_state",
    "distance_levels",
    "encode_state",
    "evaluate_navigator",
    "load_policy",
    "observation_states",
    "save_policy",
    "summarise",
    "train",
    "volts_to_cm",
]
