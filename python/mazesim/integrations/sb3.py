"""Stable-Baselines3 on the batch engine: a ``VecEnv`` over the native vector env.

SB3's ``DummyVecEnv`` steps its environments one by one in Python; this adapter steps them all in
one call of the batch engine and gives SB3 exactly what ``DummyVecEnv`` over the single envs would,
bit for bit under the same seeds: observations, float32 rewards, dones, and one info dict per
environment with ``TimeLimit.truncated``, ``terminal_observation`` on the step that ends an
episode (whose first observation of the next episode is returned, SB3's same-step autoreset) and
``is_success``, so SB3 logs a success rate. The one line::

    from mazesim.integrations.sb3 import make_vec_env

    envs = make_vec_env("mazesim/EPuckMaze-v0", n_envs=64, seed=0)  # VecMonitor on top
    model = stable_baselines3.PPO("MlpPolicy", envs)

Needs the optional extra ``mazesim[sb3]`` (Stable-Baselines3 2.x and torch).
"""

from __future__ import annotations

import importlib.util
import os
from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._paths import make_output_folder
from mazesim.errors import (
    InvalidArgumentError,
    MissingDependencyError,
    RegisteredName,
    WrongTypeError,
    _a_type,
    _known_name,
    _shown,
)

_MISSING = [name for name in ("stable_baselines3", "torch") if not importlib.util.find_spec(name)]
if _MISSING:
    raise MissingDependencyError(
        f"mazesim.integrations.sb3 needs Stable-Baselines3 2.x and torch ({', '.join(_MISSING)}"
        ' not installed): pip install "mazesim[sb3]", or in a checkout of mazesim: make sb3-deps'
    )

import gymnasium  # noqa: E402
from gymnasium.vector import AutoresetMode  # noqa: E402
from stable_baselines3.common.vec_env import VecEnv, VecMonitor  # noqa: E402
from stable_baselines3.common.vec_env.base_vec_env import (  # noqa: E402
    VecEnvObs,
    VecEnvStepReturn,
)

from mazesim.envs.goal import MazeGoalVectorEnv  # noqa: E402
from mazesim.envs.tasks import FORMER_IDS, task_ids  # noqa: E402
from mazesim.envs.vector import EPuckMazeVectorEnv  # noqa: E402

__all__ = ["MazesimVecEnv", "make_vec_env"]

#: The native vector envs: of the maze tasks, and of the goal-conditioned ones (``Dict``
#: observations, whose ``compute_reward`` HER calls through ``env_method``).
_NATIVE = (EPuckMazeVectorEnv, MazeGoalVectorEnv)
#: The keys of every per-environment info, in the single env's order.
_INFO_KEYS = ("pose", "collisions", "colliding", "distance_to_goal", "is_success")
#: The vector env's methods that act on every environment at once, which ``env_method`` (a call
#: of each environment's method in SB3's terms) refuses.
_WHOLE_ENGINE_METHODS = ("reset", "step", "close")
#: The vector env's attributes that hold all environments at once, and the attribute that holds
#: one environment's (what ``DummyVecEnv.get_attr`` gives: each single env's own value).
_PER_ENVIRONMENT = {
    "observation_space": "single_observation_space",
    "action_space": "single_action_space",
    "spec": "single_env_spec",
}


def make_vec_env(
    env_id: RegisteredName = "mazesim/EPuckMaze-v0",
    n_envs: int = 1,
    seed: int | None = None,
    start_index: int = 0,
    monitor_dir: str | None = None,
    wrapper_class: Any = None,
    env_kwargs: dict[str, Any] | None = None,
    vec_env_cls: Any = None,
    vec_env_kwargs: dict[str, Any] | None = None,
    monitor_kwargs: dict[str, Any] | None = None,
    wrapper_kwargs: dict[str, Any] | None = None,
    *,
    monitor: bool = True,
    **options: Any,
) -> VecEnv:
    """SB3's vectorised environment of a mazesim task, stepped by the batch engine.

    It takes the arguments of SB3's ``stable_baselines3.common.env_util.make_vec_env`` with their
    meaning, except the two that wrap single envs, which the batch engine does not have.

    Args:
        env_id: A registered mazesim task (its options and time limit are used), or a task's
            former id (``mazesim/UnseenMaze-v1``), with gymnasium's warning that it is out of
            date.
        n_envs: Number of environments.
        seed: Environment i is seeded with ``seed + start_index + i`` at the first reset (as SB3
            does).
        start_index: Added to the seeds, as in SB3.
        monitor_dir: Where ``VecMonitor`` writes its CSV log (``<monitor_dir>/monitor.csv``);
            None for none.
        wrapper_class: Must be None: the environments are not single envs that could be wrapped
            one by one (use SB3's own ``make_vec_env`` for that).
        env_kwargs: Keyword arguments of the task, as ``options``.
        vec_env_cls: None or :class:`MazesimVecEnv`: the batch engine is the vector env.
        vec_env_kwargs: Keyword arguments of the native vector env (``threads``).
        monitor_kwargs: Keyword arguments of ``VecMonitor`` (``info_keywords``).
        wrapper_kwargs: Must be None or empty, as ``wrapper_class``.
        monitor: Whether to wrap it in SB3's ``VecMonitor`` (episode returns and lengths in
            ``info["episode"]``, as ``Monitor`` gives with ``DummyVecEnv``).
        **options: More keyword arguments of the task (``threads`` included).

    Returns:
        A :class:`MazesimVecEnv`, in a ``VecMonitor`` if ``monitor``.

    Raises:
        InvalidArgumentError: An option has a wrong type or value, or a single-env wrapper or
            another vector env class was asked for.
        UnknownNameError: ``env_id`` is not a mazesim task (the message lists them).
    """
    if wrapper_class is not None or wrapper_kwargs:
        raise InvalidArgumentError(
            "expected wrapper_class and wrapper_kwargs to be None: the batch engine steps every "
            "environment at once, so there is no single env to wrap (use "
            "stable_baselines3.common.env_util.make_vec_env for that); "
            f"found wrapper_class={_shown(wrapper_class)}, wrapper_kwargs={_shown(wrapper_kwargs)}"
        )
    if vec_env_cls is not None and vec_env_cls is not MazesimVecEnv:
        raise InvalidArgumentError(
            f"expected vec_env_cls to be None or MazesimVecEnv, found {_shown(vec_env_cls)}"
        )
    keywords = {**(env_kwargs or {}), **(vec_env_kwargs or {}), **options}
    if not (isinstance(env_id, str) and env_id in FORMER_IDS):  # made as gymnasium.make does
        _known_name(env_id, "env_id", task_ids())
    vector = gymnasium.make_vec(
        env_id,
        n_envs,
        vectorization_mode="vector_entry_point",
        autoreset_mode=AutoresetMode.SAME_STEP,
        **keywords,
    )
    native = vector.unwrapped
    if not isinstance(native, _NATIVE):
        raise InvalidArgumentError(f"expected a mazesim task, found {_shown(env_id)}")
    venv: VecEnv = MazesimVecEnv(native)
    if seed is not None:
        venv.seed(seed + start_index)
    if not monitor:
        return venv
    filename = None if monitor_dir is None else os.path.join(monitor_dir, "monitor")
    if monitor_dir is not None:
        make_output_folder(monitor_dir, "monitor_dir")
    return VecMonitor(venv, filename=filename, **(monitor_kwargs or {}))


class MazesimVecEnv(VecEnv):
    """An SB3 ``VecEnv`` over a native :class:`~mazesim.envs.EPuckMazeVectorEnv` (or
    :class:`~mazesim.envs.goal.MazeGoalVectorEnv`, a goal-conditioned task's), bare or in
    gymnasium vector wrappers that keep its observations and actions (a
    :class:`~mazesim.envs.curriculum.MazeSizeCurriculumWrapper`, for one: SB3 then trains
    through the curriculum).

    Args:
        vector_env: The native vector env, made with ``autoreset_mode=AutoresetMode.SAME_STEP``,
            or a wrapper of it; its steps and resets go through the wrappers.

    Raises:
        InvalidArgumentError: The vector env is not native or does not reset in the same step.
    """

    def __init__(self, vector_env: gymnasium.vector.VectorEnv) -> None:
        native = getattr(vector_env, "unwrapped", None)
        if not isinstance(native, _NATIVE):
            raise WrongTypeError(
                "expected a mazesim EPuckMazeVectorEnv or MazeGoalVectorEnv, or a gymnasium "
                f"vector wrapper of one, found {_a_type(vector_env)}"
            )
        if native.autoreset_mode != AutoresetMode.SAME_STEP:
            raise InvalidArgumentError(
                "expected a vector env made with autoreset_mode=AutoresetMode.SAME_STEP "
                f"(SB3 resets in the same step), found {native.autoreset_mode}"
            )
        #: What steps and resets go through: the wrappers, if any (typed Any: they take a list
        #: of seeds, as the native env does, where gymnasium's types say one seed).
        self.vector_env: Any = vector_env
        #: The native env, whose attributes and methods are each environment's.
        self.native = native
        self.render_mode = vector_env.render_mode
        super().__init__(
            vector_env.num_envs,
            vector_env.single_observation_space,
            vector_env.single_action_space,
        )
        # The frame rate of the environments' control step, which DummyVecEnv takes from its
        # first env's metadata and VecVideoRecorder plays videos at (30 without it).
        self.metadata = {**self.metadata, "render_fps": native.metadata["render_fps"]}
        self._actions: Any = None

    def reset(self) -> VecEnvObs:
        """Resets every environment, with the seeds and options given since the last reset."""
        seeds = None if all(s is None for s in self._seeds) else list(self._seeds)
        options = self._options[0] if all(o == self._options[0] for o in self._options) else None
        if options is None:
            raise InvalidArgumentError("expected the same reset options for every environment")
        observations, info = self.vector_env.reset(seed=seeds, options=options or None)
        self.reset_infos = self._split(info, np.ones(self.num_envs, dtype=bool))
        self._reset_seeds()
        self._reset_options()
        return observations

    def step_async(self, actions: npt.NDArray[Any]) -> None:
        """Keeps the actions for :meth:`step_wait`."""
        self._actions = actions

    def step_wait(self) -> VecEnvStepReturn:
        """Steps every environment; an ended episode restarts at once (see the module)."""
        observations, rewards, terminated, truncated, info = self.vector_env.step(self._actions)
        dones = terminated | truncated
        final = info.get("_final_info")
        if final is None:
            infos = self._split(info, np.ones(self.num_envs, dtype=bool))
        else:
            infos = self._split(info, ~final)
            ended = np.flatnonzero(final)
            step_infos = self._split(info["final_info"], final)
            reset_infos = self._split(info, final)
            for i in ended.tolist():
                infos[i] = step_infos[i]
                infos[i]["terminal_observation"] = info["final_obs"][i]
                self.reset_infos[i] = reset_infos[i]
        for entry, time_limit in zip(infos, (truncated & ~terminated).tolist()):
            entry["TimeLimit.truncated"] = time_limit
        return observations, rewards.astype(np.float32), dones, infos

    def _split(self, info: dict[str, Any], rows: npt.NDArray[np.bool_]) -> list[dict[str, Any]]:
        """One dict per environment of the vector env's info, for the environments in ``rows``
        (empty dicts elsewhere), with Python scalars as a single env gives them.

        The vector env's info arrays are new at every call, so each environment's pose is a row
        of its own array's (no environment shares one with another)."""
        columns = [list(info["pose"]), *(info[key].tolist() for key in _INFO_KEYS[1:])]
        if rows.all():
            infos = [dict(zip(_INFO_KEYS, values)) for values in zip(*columns)]
        else:
            infos = [{} for _ in range(self.num_envs)]
            for i in np.flatnonzero(rows).tolist():
                infos[i] = {key: column[i] for key, column in zip(_INFO_KEYS, columns)}
        crossed = info.get("_checkpoint")
        if crossed is not None:
            checkpoints = info["checkpoint"]
            for i in np.flatnonzero(crossed & rows).tolist():
                infos[i]["checkpoint"] = int(checkpoints[i])
        return infos

    def close(self) -> None:
        """Closes the vector env."""
        self.vector_env.close()

    def get_images(self) -> Sequence[npt.NDArray[Any] | None]:
        """One image per environment (``render_mode="rgb_array"``)."""
        frames = self.vector_env.render()
        return list(frames) if frames is not None else [None] * self.num_envs

    def get_attr(self, attr_name: str, indices: Any = None) -> list[Any]:
        """The vector env's attribute, once per environment of ``indices``.

        SB3 documents ``get_attr`` as each environment's own attribute (``DummyVecEnv`` reads it
        from every single env), so ``observation_space`` and ``action_space`` are the spaces of
        one environment, not the vector env's batched ones, and ``spec`` is one environment's
        (``gymnasium.make(spec)`` makes an env of the same task, say for evaluation).
        """
        value = getattr(self.native, _PER_ENVIRONMENT.get(attr_name, attr_name))
        return [value for _ in self._indices(indices)]

    def set_attr(self, attr_name: str, value: Any, indices: Any = None) -> None:
        """Not supported: the environments share one engine."""
        raise InvalidArgumentError(
            f"expected no set_attr on the batch engine's environments, found {_shown(attr_name)}"
        )

    def env_method(
        self, method_name: str, *method_args: Any, indices: Any = None, **method_kwargs: Any
    ) -> list[Any]:
        """Calls the vector env's method once, and gives its result for each of ``indices``.

        SB3 documents ``env_method`` as a call of each environment's method, one result per
        environment: ``render`` gives each environment's own image (as ``DummyVecEnv`` does),
        and ``reset``, ``step`` and ``close``, which would act on every environment of the one
        engine at once, are refused (use the ``VecEnv``'s own ``reset``, ``step`` and ``close``).

        Raises:
            InvalidArgumentError: ``method_name`` is ``reset``, ``step`` or ``close``.
        """
        targets = list(self._indices(indices))
        if method_name in _WHOLE_ENGINE_METHODS:
            raise InvalidArgumentError(
                f"expected env_method of a method that acts on one environment, found "
                f"{_shown(method_name)}, which acts on all {self.num_envs} environments of the "
                "batch "
                f"engine at once: call the VecEnv's own {method_name}()"
            )
        if method_name == "render" and not method_args and not method_kwargs:
            frames = self.get_images()
            return [frames[i] for i in targets]
        result = getattr(self.native, method_name)(*method_args, **method_kwargs)
        return [result for _ in targets]

    def env_is_wrapped(self, wrapper_class: type, indices: Any = None) -> list[bool]:
        """False: the environments are not gymnasium envs with wrappers."""
        return [False for _ in self._indices(indices)]

    def _indices(self, indices: Any) -> Iterable[int]:
        if indices is None:
            return range(self.num_envs)
        if isinstance(indices, int):
            return [indices]
        return list(indices)
