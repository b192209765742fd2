"""The functions every versioned task module offers, made once from the module's ``task``:
``parallel_env``, ``raw_env``, ``env`` (PettingZoo's conventions) and ``batch_env`` (the native
batch)."""

from __future__ import annotations

import inspect
from collections.abc import Callable
from typing import Any, NamedTuple

from pettingzoo import AECEnv
from pettingzoo.utils.conversions import parallel_to_aec_wrapper
from pettingzoo.utils.wrappers import OrderEnforcingWrapper

from mazesim.envs.errors import ResetNeededError
from mazesim.errors import InvalidArgumentError, UnknownNameError, _closest_name, _shown
from mazesim.marl.batch import MultiRobotBatch
from mazesim.marl.parallel import MultiRobotParallelEnv, agent_action
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
        return _OrderEnforcing(parallel_to_aec_wrapper(parallel_env(**options)))

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

    # The functions above call the checked task (a closure's name is looked up at each call).
    task = _refusing_unknown_options(task, parallel_env)
    return EntryPoints(parallel_env, raw_env, env, batch_env)


def _refusing_unknown_options(
    task: Callable[..., MultiRobotTask], parallel_env: Callable[..., Any]
) -> Callable[..., MultiRobotTask]:
    """``task``, refusing an option it does not take with
    :class:`~mazesim.errors.InvalidArgumentError` naming the options of ``parallel_env`` (its
    own keywords and the task's) and the one meant, for a typo, rather than Python's
    ``TypeError``. A ``task`` that passes any keyword on (``**rewards``) leaves those to the
    rules' own check."""
    parameters = inspect.signature(task).parameters.values()
    if any(p.kind is p.VAR_KEYWORD for p in parameters):
        return task
    names = [p.name for p in parameters]
    own = [
        p.name
        for p in inspect.signature(parallel_env).parameters.values()
        if p.kind is not p.VAR_KEYWORD
    ]
    where = task.__module__.rsplit(".", 1)[-1]

    def checked_task(**options: Any) -> MultiRobotTask:
        for name in options:
            if name not in names:
                meant = _closest_name(name, own + names)
                raise InvalidArgumentError(
                    f"{where}: expected no argument named {_shown(name)}, found one; its "
                    "arguments: "
                    f"{', '.join(own + names)}"
                    + (f"; did you mean {_shown(meant)}?" if meant else "")
                )
        return task(**options)

    return checked_task


class _OrderEnforcing(OrderEnforcingWrapper[Any, Any, Any]):
    """PettingZoo's order check of an AEC env (what ``parallel_to_aec`` adds), raising the
    package's :class:`~mazesim.envs.ResetNeededError` (also gymnasium's ``ResetNeeded``) where
    PettingZoo raises a bare ``AssertionError``: ``step``, ``observe``, ``state``, ``render`` or
    ``agent_iter`` before the first ``reset``."""

    def _reset_first(self, what: str) -> None:
        if not self._has_reset:
            raise ResetNeededError(f"expected reset() before {what}()")

    def step(self, action: Any) -> None:
        self._reset_first("step")
        agent = self.agent_selection
        ended = self.terminations.get(agent, False) or self.truncations.get(agent, False)
        if not ended:  # an ended agent steps with None, as PettingZoo's AEC loop gives it
            agent_action(action, agent)  # refused now, naming the agent, not at the last one
        super().step(action)

    def observe(self, agent: Any) -> Any:
        self._reset_first("observe")
        if not (isinstance(agent, str) and agent in self.possible_agents):
            raise UnknownNameError(
                f"expected one of the agents {self.possible_agents}, found {_shown(agent)}",
                available=list(self.possible_agents),
                name=agent if isinstance(agent, str) else None,
            )
        return super().observe(agent)

    def state(self) -> Any:
        self._reset_first("state")
        return super().state()

    def render(self) -> Any:
        self._reset_first("render")
        return super().render()

    def agent_iter(self, max_iter: int = 2**63) -> Any:
        self._reset_first("agent_iter")
        return super().agent_iter(max_iter)
