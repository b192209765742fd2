"""Hierarchical Q-learning navigation of the report's chapter 4, done so that it reaches the goal.

Two levels, as the report's section 4.1 describes them:

- the **lower level** (:mod:`mazesim.hrl.subtasks`): four sub-tasks, "Corridors and Corners",
  "Right turn on a door", "Left turn on a door" and "Going forward on a door", each a tabular
  Q-learner over the twelve primitive actions (:mod:`mazesim.actions`) on the six Sharp distances
  discretised by Table 4.1 (:mod:`mazesim.hrl.discretise`), trained on generated mazes with
  thousands of robots at once (:mod:`mazesim.hrl.lower`);
- the **higher level** (:mod:`mazesim.hrl.higher`): at each checkpoint event, a barcode crossed,
  it chooses the sub-task by SMDP Q-learning over (checkpoint, direction), trained on the target
  world (:mod:`mazesim.hrl.episodes`).

:mod:`mazesim.hrl.policy` runs both levels (Alg. 5); :mod:`mazesim.hrl.train` trains from scratch
with checkpoints and resume; :mod:`mazesim.hrl.tables` saves and loads the tables;
:mod:`mazesim.hrl.evaluate` measures a navigator and writes the report's trajectory pictures and
trace; :mod:`mazesim.hrl.baseline` is a flat Q-learner for comparison. Trained tables for
``seed-maze`` ship in the package (``mazesim eval`` uses them by default).

Example:
    >>> import mazesim
    >>> from mazesim.hrl import evaluate_navigator, load_policy
    >>> policy = load_policy()  # the navigator shipped for seed-maze
    >>> report = evaluate_navigator(policy, [mazesim.load_world("seed-maze")], 4)
    >>> report.summaries["truth"].success_rate
    1.0
"""

from __future__ import annotations

from mazesim.hrl.discretise import (
    LEVEL_EDGES_CM,
    NUM_STATES,
    SENSOR_ORDER,
    decode_state,
    distance_levels,
    encode_state,
    observation_states,
    volts_to_cm,
)
from mazesim.hrl.evaluate import Summary, evaluate_navigator
from mazesim.hrl.policy import HierarchicalPolicy
from mazesim.hrl.subtasks import SUBTASK_NAMES, SubTask
from mazesim.hrl.tables import TrainedPolicy, load_policy, save_policy
from mazesim.hrl.train import TrainSettings, train

__all__ = [
    "LEVEL_EDGES_CM",
    "NUM_STATES",
    "SENSOR_ORDER",
    "SUBTASK_NAMES",
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
    "train",
    "volts_to_cm",
]
