"""Gymnasium environments: ``mazesim/EPuckMaze-v0`` and its native vector env.

The task suite (:mod:`mazesim.envs.tasks`) is registered once both mazesim and gymnasium are
imported, in either order (``pip install "mazesim[gym]"``); ``import mazesim`` alone does not
import gymnasium::

    import gymnasium
    import mazesim  # registers mazesim/EPuckMaze-v0

    env = gymnasium.make("mazesim/EPuckMaze-v0", action_mode="discrete")
    envs = gymnasium.make_vec("mazesim/EPuckMaze-v0", num_envs=1024)  # on the batch engine

:class:`EPuckMazeEnv` is one robot in a maze, :class:`EPuckMazeVectorEnv` runs N of them in the
batch engine and equals ``SyncVectorEnv`` bit for bit. The observation, action and reward are
documented in :mod:`mazesim.envs.spaces` and :mod:`mazesim.envs.reward`, the pictures in
:mod:`mazesim.render.topdown`.
"""

from __future__ import annotations

import importlib.util

from mazesim.errors import MissingDependencyError

if importlib.util.find_spec("gymnasium") is None:
    raise MissingDependencyError(
        'mazesim.envs needs gymnasium (1.0 or newer): pip install "mazesim[gym]" '
        "or pip install gymnasium"
    )

from mazesim.envs.errors import EnvClosedError, ResetNeededError  # noqa: E402
from mazesim.envs.maze_env import EPuckMazeEnv  # noqa: E402
from mazesim.envs.options import DEFAULT_MAX_EPISODE_STEPS  # noqa: E402
from mazesim.envs.reward import RewardWeights  # noqa: E402
from mazesim.envs.tasks import TASKS, Task, register_tasks  # noqa: E402
from mazesim.envs.vector import EPuckMazeVectorEnv  # noqa: E402
from mazesim.render.topdown import TopDownRenderer  # noqa: E402

__all__ = [
    "DEFAULT_MAX_EPISODE_STEPS",
    "ENV_ID",
    "EPuckMazeEnv",
    "EPuckMazeVectorEnv",
    "EnvClosedError",
    "ResetNeededError",
    "RewardWeights",
    "TASKS",
    "Task",
    "TopDownRenderer",
    "register_envs",
    "register_tasks",
]

#: The id of the maze environment in gymnasium's registry.
ENV_ID = "mazesim/EPuckMaze-v0"


def register_envs() -> None:
    """Registers the task suite (:mod:`mazesim.envs.tasks`), ``mazesim/EPuckMaze-v0`` first, with
    single and vector entry points.

    Importing this package calls it, and ``import mazesim`` imports this package when gymnasium
    is imported (:mod:`mazesim._gym_registration`); calling it again does nothing.
    """
    register_tasks()


register_envs()
