"""Multi-agent RL on several e-pucks: PettingZoo environments and a native batch of them.

Each task is a versioned module, as PettingZoo's own environments are:

- :mod:`mazesim.marl.maze_goals_v0`: every robot to its own goal in an unseen maze without
  touching the walls or each other (JaxNav's task, on e-pucks);
- :mod:`mazesim.marl.aggregation_v0`: a swarm gathers into one cluster (Gauci et al. 2014).

Each module has ``parallel_env()`` (a PettingZoo ``ParallelEnv``), ``env()`` and ``raw_env()``
(the AEC version, by PettingZoo's ``parallel_to_aec``) and ``batch_env(num_envs)`` (the native
batch, :class:`mazesim.marl.batch.MultiRobotBatch`: N environments x R robots stepped by one
batch engine, with (N, R, ...) arrays). They need PettingZoo: ``pip install "mazesim[marl]"``.
"""

from __future__ import annotations

import importlib.util

from mazesim.errors import MissingDependencyError

if importlib.util.find_spec("pettingzoo") is None:
    raise MissingDependencyError(
        'mazesim.marl needs PettingZoo (1.24 or newer): pip install "mazesim[marl]" '
        "or pip install pettingzoo"
    )

__all__ = ["aggregation_v0", "maze_goals_v0"]
