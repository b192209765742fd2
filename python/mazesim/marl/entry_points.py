"""The functions every versioned task module offers, made once from the module's ``task``:
``parallel_env``, ``raw_env``, ``env`` (PettingZoo's conventions) and ``batch_env`` (the native
batch)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, NamedTuple

from pettingzoo import AECEnv
from pettingzoo.utils.conversions import parallel_to_aec

from mazesim.marl.batch import MultiRobotBatch
from mazesim.marl.parallel import MultiRobotParallelEnv
from mazesim.marl.tasks import MultiRobotTask

__all__ = ["EntryPoints", "entry_points"]


class EntryPoints(NamedTuple):
    """A task module's functions; each passes its ``**options`` to the module's ``task``."""

    parallel_env: Callable[..., MultiRobotParallelEnv]
    raw_env: Callable[..., AECEnv]
    env: Callable[..., AECEnv]
    batch_env: Callable[..., MultiRobotBatch]


def entry_points(task: Callable[..., MultiRobotTask]) -> EntryPoints:
    """The functions of the task module whose rules ``task(**options)`` makes."""

    def parallel_env(
        render_mode: str | None = None,
        control_step_ms: float = 128.0,
        noise: bool = True,
        **options: Any,
    ) -> MultiRobotParallelEnv:
        """The PettingZoo ParallelEnv; ``options`` are the module's ``task``'s."""
        return MultiRobotParallelEnv(task(**options), render_mode, control_step_ms, noise)

    def raw_env(**options: Any) -> AECEnv:
        """The AEC version (PettingZoo's ``parallel_to_aec`` of ``parallel_env``)."""
        return parallel_to_aec(parallel_env(**options))

    def env(**options: Any) -> AECEnv:
        """The AEC version, as PettingZoo's own modules' ``env()`` gives it."""
        return raw_env(**options)

    def batch_env(
        num_envs: int,
        threads: int = 0,
        control_step_ms: float = 128.0,
        noise: bool = True,
        **options: Any,
    ) -> MultiRobotBatch:
        """The native batch of ``num_envs`` environments (autoreset), each as
        ``parallel_env``'s; ``options`` are the module's ``task``'s."""
        return MultiRobotBatch(
            task(**options),
            num_envs,
            control_step_ms=control_step_ms,
            noise=noise,
            threads=threads,
        )

    return EntryPoints(parallel_env, raw_env, env, batch_env)
