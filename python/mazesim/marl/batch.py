"""The native batch of multi-robot environments: one :class:`mazesim.BatchSimulator` of N
environments x R robots, a task's rules on (N, R, ...) arrays, and an API of arrays.

A PettingZoo env of :mod:`mazesim.marl` is this batch with one environment, so N of them
reset with seeds ``s, s + 1, ...`` and stepped one by one give, bit for bit, what one batch of N
reset with seed ``s`` gives (``tests/marl/test_native_batch.py``).

Seeding: environment ``i`` draws its episodes (world, starts, goals, the simulator's noise seed)
from its own stream ``numpy.random.default_rng(seed + i)`` (wrapping past ``2**64 - 1``, as the
single-robot vector env); every later reset continues that stream, so a run is replayed exactly
from its seed.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._core import BatchSimulator, RobotProfile
from mazesim._sizes import MOST_ENVS
from mazesim.envs.errors import MAX_SEED, is_seed
from mazesim.envs.spaces import real_actions
from mazesim.errors import InvalidActionError, InvalidArgumentError, _shown
from mazesim.marl.tasks import EpisodeDraw, MultiRobotTask, RobotStates, agent_names

__all__ = ["MultiRobotBatch", "StepResult"]

StepResult = tuple[
    npt.NDArray[np.float32],
    npt.NDArray[np.float32],
    npt.NDArray[np.bool_],
    npt.NDArray[np.bool_],
    dict[str, npt.NDArray[Any]],
]


class MultiRobotBatch:
    """N environments of a multi-robot task, each of R robots, stepped together.

    A robot whose episode ended (terminated or truncated) stands still, its wheels stopped, and
    gets reward 0 until its environment's episode ends, which is when every robot's has. With
    ``autoreset`` such an environment starts its next episode in the same call (the returned
    observations are the new episode's first, the rewards and flags the ended step's);
    without, it waits for :meth:`reset_envs`.

    Args:
        task: The task's rules (:mod:`mazesim.marl.tasks`).
        num_envs: Number of environments.
        robot: The robots' profile (a built-in name or a profile file's path).
        control_step_ms: Control step in milliseconds.
        noise: Whether sensors and wheels are noisy.
        threads: Threads of the batch engine (0: one per core).
        autoreset: Whether an environment whose robots are all done restarts at once.
    """

    def __init__(
        self,
        task: MultiRobotTask,
        num_envs: int,
        *,
        robot: str = "e-puck",
        control_step_ms: float = 128.0,
        noise: bool = True,
        threads: int = 0,
        autoreset: bool = True,
    ) -> None:
        most = MOST_ENVS // task.num_robots
        if not 1 <= num_envs <= most:
            raise InvalidArgumentError(f"expected num_envs from 1 to {most}, found {num_envs}")
        self.task = task
        self.num_envs = num_envs
        self.num_robots = task.num_robots
        self.agents = agent_names(task.num_robots)
        self.profile = RobotProfile.load(robot)
        self.max_wheel_speed = float(self.profile.max_wheel_speed)
        self.control_step_ms = control_step_ms
        self.noise = noise
        self.threads = threads
        self.autoreset = autoreset
        task.bind(num_envs)
        n, r = num_envs, task.num_robots
        self.simulator: BatchSimulator | None = None
        self.draws: list[EpisodeDraw | None] = [None] * n
        self._rngs: list[np.random.Generator] = []
        self._readings = np.zeros((n, r, 0), np.float32)
        self.poses = np.zeros((n, r, 3), np.float32)
        self.colliding = np.zeros((n, r), bool)
        self._crossings = np.zeros((n, r), np.int32)
        self.actions = np.zeros((n, r, 2), np.float32)
        self.live = np.zeros((n, r), bool)
        self.steps = np.zeros(n, np.int64)

    def __getstate__(self) -> dict[str, Any]:
        """What pickling and deep-copying keep: everything, the batch engine as one snapshot per
        environment, as the single-robot vector env keeps its own."""
        state = self.__dict__.copy()
        simulator = state.pop("simulator")
        state["_snapshots"] = (
            None if simulator is None else [simulator.snapshot_env(i) for i in range(self.num_envs)]
        )
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        """Rebuilds the batch engine of the episodes' worlds from its snapshots: the copy steps
        on, bit for bit, as the original does."""
        snapshots = state.pop("_snapshots")
        self.__dict__.update(state)
        self.simulator = None
        if snapshots is not None:
            simulator = self._new_simulator([d for d in self.draws if d is not None])
            for i, snapshot in enumerate(snapshots):
                simulator.restore_env(i, snapshot)
            self.simulator = simulator

    def _new_simulator(self, draws: Sequence[EpisodeDraw]) -> BatchSimulator:
        """The batch engine of the episodes ``draws``, one per environment, at their starts."""
        return BatchSimulator(
            [d.world for d in draws],
            robot=self.profile,
            seeds=[d.seed for d in draws],
            noise=self.noise,
            control_step_ms=self.control_step_ms,
            threads=self.threads,
        )

    @property
    def observation_width(self) -> int:
        """Values in each robot's observation."""
        return len(self.task.observation_names)

    def reset(
        self, seed: int | Sequence[int] | None = None
    ) -> tuple[npt.NDArray[np.float32], dict[str, npt.NDArray[Any]]]:
        """Starts a new episode in every environment.

        Args:
            seed: Environment ``i``'s stream is seeded with ``seed + i`` (or ``seed[i]``); None
                keeps the streams (fresh ones from the operating system the first time).

        Returns:
            (N, R, width) observations and infos ((N, R) arrays by key).
        """
        n = self.num_envs
        if seed is not None:
            seeds: list[Any] = []
            if is_seed(seed):
                seeds = [(int(seed) + i) % (MAX_SEED + 1) for i in range(n)]  # type: ignore[arg-type]
            elif isinstance(seed, Sequence) and not isinstance(seed, str) and len(seed) == n:
                seeds = list(seed)
            if len(seeds) != n or not all(is_seed(s) for s in seeds):
                raise InvalidArgumentError(
                    f"expected seed to be None, an int in 0..={MAX_SEED} or {n} of them, "
                    f"found {_shown(seed)}"
                )
            self._rngs = [np.random.default_rng(s) for s in seeds]
        elif not self._rngs:
            entropy = np.random.SeedSequence().spawn(n)
            self._rngs = [np.random.default_rng(s) for s in entropy]
        self.reset_envs(np.ones(n, bool))
        return self.task.observe(self._states()), {}

    def reset_envs(self, envs: npt.NDArray[np.bool_]) -> None:
        """Starts the next episode of the environments in the (N,) mask ``envs``, each drawn
        from its stream; their rows of the state change, the others' do not."""
        indices = np.flatnonzero(envs)
        for i in indices:
            self.draws[i] = self.task.draw(self._rngs[i])
        draws = [d for d in self.draws if d is not None]
        if self.simulator is None:
            if len(draws) != self.num_envs:
                raise InvalidArgumentError("expected the first reset to start every environment")
            self.simulator = self._new_simulator(draws)
            width = self.simulator.observation_width
            self._readings = np.zeros((self.num_envs, self.num_robots, width), np.float32)
        else:
            for i in indices:
                draw = self.draws[i]
                assert draw is not None
                self.simulator.set_world(int(i), draw.world, draw.seed)
        self.simulator.observe(*self._buffers())
        self.actions[indices] = 0.0
        self.live[indices] = True
        self.steps[indices] = 0
        for i in indices:
            draw = self.draws[i]
            assert draw is not None
            self.task.start(int(i), draw, self.poses[i])

    def _buffers(self, *arrays: npt.NDArray[Any]) -> list[npt.NDArray[Any]]:
        """The step's buffers (``arrays`` first, then readings, poses, colliding, crossings) as
        the batch takes them: with their robot axis, or without it when each environment holds
        one robot (a batch of one-robot worlds keeps the one-robot shapes); views either way."""
        every = [*arrays, self._readings, self.poses, self.colliding, self._crossings]
        return [a[:, 0] for a in every] if self.num_robots == 1 else every

    def _states(self) -> RobotStates:
        return RobotStates(self._readings, self.poses, self.colliding, self.actions)

    def step(self, actions: npt.ArrayLike) -> StepResult:
        """Steps every environment once with (N, R, 2) wheel speed fractions in [-1, 1] (larger
        values are clipped; a robot whose episode ended ignores its row).

        Returns:
            Observations (N, R, width) float32, rewards (N, R) float32, terminations and
            truncations (N, R) bool (True only on the step that ends a robot's episode), infos:
            (N, R) arrays by key, plus ``"reset"``, the (N,) environments restarted by
            ``autoreset`` after this step.

        Raises:
            InvalidActionError: Actions of another shape, or not finite.
            InvalidArgumentError: Called before :meth:`reset`.
        """
        if self.simulator is None:
            raise InvalidArgumentError("expected reset() before step()")
        n, r = self.num_envs, self.num_robots
        wanted = real_actions(actions)
        if wanted.shape != (n, r, 2):
            raise InvalidActionError(f"expected actions of shape {(n, r, 2)}, found {wanted.shape}")
        if not np.isfinite(wanted).all():
            raise InvalidActionError("expected finite actions, found NaN or infinite values")
        applied = np.where(self.live[..., None], np.clip(wanted, -1.0, 1.0), np.float32(0.0))
        self.actions[...] = applied
        commands = np.array(applied * np.float32(self.max_wheel_speed), np.float32, order="C")
        self.simulator.step(*self._buffers(commands))
        self.steps += 1
        live = self.live.copy()
        states = self._states()
        rewards, ended, infos = self.task.reward(states, live)
        terminations = ended & live
        out_of_time = (self.steps >= self.task.max_cycles)[:, None]
        truncations = live & ~terminations & out_of_time
        self.live &= ~(terminations | truncations)
        finished: npt.NDArray[np.bool_] = np.logical_not(self.live.any(axis=1))
        observations = self.task.observe(states)
        infos["reset"] = np.zeros(n, bool)
        if self.autoreset and finished.any():
            self.reset_envs(finished)
            observations = np.where(
                finished[:, None, None], self.task.observe(self._states()), observations
            )
            infos["reset"] = finished
        return observations, rewards, terminations, truncations, infos
