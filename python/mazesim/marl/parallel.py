"""The PettingZoo ParallelEnv of a multi-robot task: every e-puck an agent, stepped together.

Agents are named ``epuck_0`` ... ``epuck_{R-1}`` (the robots' names in the world). An agent
leaves ``env.agents`` on the step that terminates or truncates it (PettingZoo's convention); its
robot then stands still, still an obstacle to the others, until the episode ends with the last
agent. Actions are ``Box(-1, 1, (2,))`` wheel speed fractions of the motor limit (clipped);
observations and rewards are the task's (:mod:`mazesim.marl.tasks`). ``state()`` is the global
state a centralised critic takes (PettingZoo's ``state`` and ``state_space``): every robot's
observation, then every robot's true pose ``x, y, yaw`` (metres, radians), in agent order.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import gymnasium
import numpy as np
import numpy.typing as npt
from pettingzoo import ParallelEnv

from mazesim.envs.errors import EnvClosedError, ResetNeededError, check_options, check_seed
from mazesim.envs.spaces import real_actions
from mazesim.errors import (
    InvalidActionError,
    InvalidArgumentError,
    UnknownNameError,
    _a_type,
    _shown,
)
from mazesim.marl.batch import MultiRobotBatch
from mazesim.marl.render import SwarmRenderer
from mazesim.marl.tasks import MultiRobotTask
from mazesim.render.live import LiveView, shown_in

__all__ = ["MultiRobotParallelEnv", "agent_action"]

Observation = npt.NDArray[np.float32]

#: What an env of ``render_mode="human"`` says once where no window can open (``{problem}``: the
#: reason), as the single-robot envs say it, and that PettingZoo's ``render_test``, which makes
#: an env of every declared render mode, needs nothing done.
HUMAN_MODE_HEADLESS_NOTICE = (
    'mazesim: render_mode="human" shows no window here: {problem}; its frames are drawn but not '
    'shown (render_mode="rgb_array" returns them as arrays). Nothing to do when PettingZoo\'s '
    "render_test made this env: it tries every render mode"
)


def agent_action(action: Any, agent: str) -> npt.NDArray[np.float32]:
    """One agent's action as the two wheel speeds it sets: real numbers, finite, of shape (2,).
    The one check of an action, of the parallel env's ``step`` and of the AEC env's, which
    checks each as it is given (PettingZoo's ``parallel_to_aec`` holds the actions until the
    last agent's, where a NaN was refused at another agent's step, not naming the agent).

    Raises:
        InvalidActionError: Not two finite real numbers.
    """
    checked = real_actions(action, f"the action of {agent}", "two wheel speeds (numbers)")
    if checked.shape != (2,):
        raise InvalidActionError(
            f"expected the action of {agent} of shape (2,), found {checked.shape}"
        )
    if not np.isfinite(checked).all():
        raise InvalidActionError(
            f"expected the action of {agent} to be finite wheel speeds, found {checked.tolist()}"
        )
    return checked


class MultiRobotParallelEnv(ParallelEnv[str, Observation, npt.NDArray[np.float32]]):
    """A multi-robot task as a PettingZoo ParallelEnv (a :class:`MultiRobotBatch` of one).

    Args:
        task: The task's rules.
        render_mode: None, ``"rgb_array"`` (a top-down picture of the world and every robot) or
            ``"human"`` (that picture in a window, updated at every reset and step, as the
            single-robot envs show theirs; headless where no window can open).
        control_step_ms: Control step in milliseconds.
        noise: Whether sensors and wheels are noisy.
    """

    metadata: dict[str, Any] = {
        "name": "mazesim_multi_robot",
        "render_modes": ["human", "rgb_array"],
        "is_parallelizable": True,
        "render_fps": 8,
    }

    def __init__(
        self,
        task: MultiRobotTask,
        render_mode: str | None = None,
        control_step_ms: float = 128.0,
        noise: bool = True,
    ) -> None:
        if render_mode not in (None, "human", "rgb_array"):
            raise InvalidArgumentError(
                f'expected render_mode None, "human" or "rgb_array", found {_shown(render_mode)}'
            )
        self.metadata = {**type(self).metadata, "name": task.name}
        self.render_mode = render_mode
        self.batch = MultiRobotBatch(
            task, 1, control_step_ms=control_step_ms, noise=noise, threads=1, autoreset=False
        )
        self.possible_agents = list(self.batch.agents)
        self.agents: list[str] = []
        #: Whether the env has been reset: a step with no live agent after an episode answers
        #: with nothing, one before the first reset raises.
        self._was_reset = False
        width = self.batch.observation_width
        limit = np.float32(np.finfo(np.float32).max)
        self._observation_space = gymnasium.spaces.Box(-limit, limit, (width,), np.float32)
        self._action_space = gymnasium.spaces.Box(-1.0, 1.0, (2,), np.float32)
        self._observation_spaces = {a: self._observation_space for a in self.possible_agents}
        robots = len(self.possible_agents)
        #: The global state's space: R observations, then R poses (PettingZoo's convention).
        self.state_space = gymnasium.spaces.Box(-limit, limit, (robots * (width + 3),), np.float32)
        self._observations = np.zeros((robots, width), np.float32)
        self._action_spaces = {a: self._action_space for a in self.possible_agents}
        self._renderer: SwarmRenderer | None = None
        self._live: LiveView | None = None
        self._closed = False

    def observation_space(self, agent: str) -> gymnasium.spaces.Space[Any]:
        """Every agent's observation space: ``Box`` of the task's width, float32.

        Raises:
            UnknownNameError: ``agent`` is none of ``possible_agents`` (a ``LookupError``).
        """
        return self._observation_spaces[self._agent_named(agent)]

    def action_space(self, agent: str) -> gymnasium.spaces.Space[Any]:
        """Every agent's action space: ``Box(-1, 1, (2,))`` wheel speed fractions.

        Raises:
            UnknownNameError: ``agent`` is none of ``possible_agents`` (a ``LookupError``).
        """
        return self._action_spaces[self._agent_named(agent)]

    def _agent_named(self, agent: Any) -> str:
        """``agent``, one of ``possible_agents``; else the error naming them and the one meant."""
        if isinstance(agent, str) and agent in self.possible_agents:
            return agent
        raise UnknownNameError(
            f"expected one of the agents {self.possible_agents}, found {_shown(agent)}",
            available=list(self.possible_agents),
            name=agent if isinstance(agent, str) else None,
        )

    def reset(
        self, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[dict[str, Observation], dict[str, dict[str, Any]]]:
        """Starts an episode (a new world drawn from the env's stream, seeded by ``seed``).

        Raises:
            InvalidArgumentError: ``seed`` is not None or an int in ``0..=2**64-1``, or
                ``options`` is not None or a dict (as the single-robot envs).
            EnvClosedError: The env is closed.
        """
        self._check_open()
        seed = check_seed(seed)
        check_options(options)
        observations, _ = self.batch.reset(seed)
        self._observations[...] = observations[0]
        self.agents = list(self.possible_agents)
        self._was_reset = True
        self._renderer = None
        if self.render_mode == "human":
            self.render()
        return self._per_agent(observations[0]), {a: {} for a in self.agents}

    def step(
        self, actions: dict[str, Any]
    ) -> tuple[
        dict[str, Observation],
        dict[str, float],
        dict[str, bool],
        dict[str, bool],
        dict[str, dict[str, Any]],
    ]:
        """Steps every live agent with its action (an agent without one, or an action of an
        agent the env does not have: an error; an ended agent's action is left out).

        Once every agent has ended, a step changes nothing and returns five empty dicts, as
        PettingZoo's own parallel envs (``aec_to_parallel``) do, which wrappers that keep
        ended agents in, such as SuperSuit's ``black_death_v3``, step to learn that the
        episode is over.

        Raises:
            ResetNeededError: The env was never reset.
            EnvClosedError: The env is closed.
        """
        self._check_open()
        if not self._was_reset:
            raise ResetNeededError("expected reset() before step(): no agent is live")
        if not isinstance(actions, Mapping):
            raise InvalidActionError(
                f"expected a dict of actions by agent name, found {_a_type(actions)}"
            )
        unknown = [a for a in actions if a not in self.possible_agents]
        if unknown:  # a misspelt name would leave its robot's action out unseen
            raise InvalidActionError(
                f"expected actions of the agents {self.possible_agents}, found unknown agents "
                f"{unknown}"
            )
        if not self.agents:
            return {}, {}, {}, {}, {}
        missing = [a for a in self.agents if a not in actions]
        if missing:
            raise InvalidActionError(f"expected an action for every live agent, missing {missing}")
        wheels = np.zeros((1, len(self.possible_agents), 2), np.float32)
        for i, agent in enumerate(self.possible_agents):
            if agent in self.agents:
                wheels[0, i] = agent_action(actions[agent], agent)
        observations, rewards, terminations, truncations, infos = self.batch.step(wheels)
        self._observations[...] = observations[0]
        live = self.agents
        index = {a: self.possible_agents.index(a) for a in live}
        result = (
            {a: observations[0, index[a]] for a in live},
            {a: float(rewards[0, index[a]]) for a in live},
            {a: bool(terminations[0, index[a]]) for a in live},
            {a: bool(truncations[0, index[a]]) for a in live},
            {a: _agent_info(infos, index[a]) for a in live},
        )
        self.agents = [a for a in live if not (result[2][a] or result[3][a])]
        if self.render_mode == "human":
            self.render()
        return result

    def state(self) -> npt.NDArray[np.float32]:
        """The global state (``state_space``): every robot's last observation, an ended robot's
        included, then every robot's true pose ``x, y, yaw``, in agent order; one flat float32
        array of ``R * (width + 3)`` values, a copy.

        Raises:
            ResetNeededError: Before the first ``reset``.
            EnvClosedError: The env is closed.
        """
        self._check_open()
        if self.batch.simulator is None:
            raise ResetNeededError("expected reset() before state()")
        poses = self.batch.poses[0].astype(np.float32)
        return np.concatenate([self._observations.ravel(), poses.ravel()])

    def render(self) -> npt.NDArray[np.uint8] | None:
        """A top-down RGB picture (``render_mode="rgb_array"``); with ``"human"`` the same
        picture shown in a window (:class:`~mazesim.render.live.LiveView`, which carries on
        headless where there is no display) and None; else None."""
        self._check_open()
        if self.render_mode is None:
            return None
        draw = self.batch.draws[0]
        if draw is None:
            raise InvalidArgumentError("expected reset() before render()")
        if self._renderer is None:
            self._renderer = SwarmRenderer(draw.world, self.batch.profile, draw.goals)
        frame = self._renderer.frame(self.batch.poses[0], self.batch.colliding[0])
        if self.render_mode == "rgb_array":
            return frame
        fps = float(self.metadata["render_fps"])
        title = f"mazesim: {self.metadata['name']}"
        self._live = shown_in(self._live, frame, title, fps, HUMAN_MODE_HEADLESS_NOTICE)
        return None

    def close(self) -> None:
        """Releases the picture (the simulator holds no outside resource); ``reset``, ``step``
        and ``render`` raise :class:`~mazesim.envs.EnvClosedError` from then on."""
        self._renderer = None
        if self._live is not None:
            self._live.close()
            self._live = None
        self._closed = True

    def __getstate__(self) -> dict[str, Any]:
        """What pickling and deep-copying keep: the episode as it stands (the batch keeps its
        engine as snapshots); the picture and its window are made again when asked for."""
        state = self.__dict__.copy()
        state["_renderer"] = None
        state["_live"] = None
        return state

    def _check_open(self) -> None:
        if self._closed:
            raise EnvClosedError("the env is closed: make a new one")

    def _per_agent(self, observations: Observation) -> dict[str, Observation]:
        return {a: observations[i] for i, a in enumerate(self.possible_agents)}


def _agent_info(infos: dict[str, npt.NDArray[Any]], robot: int) -> dict[str, Any]:
    """One agent's info: its values of the (1, R) arrays, as Python scalars."""
    return {key: value[0, robot].item() for key, value in infos.items() if value.ndim == 2}
