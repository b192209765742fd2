"""The native vector environment of ``mazesim/EPuckMaze-v0``, backed by the batch engine.

``gymnasium.make_vec("mazesim/EPuckMaze-v0", num_envs=N)`` (the registration's
``vector_entry_point``) builds it. All N environments step in one call of
:class:`mazesim.BatchSimulator`, in parallel and without the GIL, into buffers allocated once; the
Python work per step is a few numpy operations over all environments, whatever N is.

It behaves exactly as ``SyncVectorEnv`` over N :class:`~mazesim.envs.EPuckMazeEnv` with the same
seeds, bit for bit: environment ``i`` is seeded with ``seed + i`` and draws its episodes from its
own RNG, episodes end in the same way (the time limit is ``max_episode_steps``), autoreset is
NEXT_STEP (the step after an episode ends returns the first observation of the next one, with
reward 0 and neither terminated nor truncated), and infos are dicts of arrays, each key ``k`` with
a boolean mask ``_k`` of the environments that have it.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import gymnasium
import numpy as np
import numpy.typing as npt
from gymnasium.envs.registration import EnvSpec
from gymnasium.utils import seeding
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from mazesim._core import BatchSimulator, World
from mazesim._hot_paths import checks_own_arguments
from mazesim.envs.errors import (
    MAX_SEED,
    EnvClosedError,
    ResetNeededError,
    check_options,
    is_seed,
)
from mazesim.envs.maze_env import VECTOR_RENDER_MODES, check_render_mode, step_length_ms
from mazesim.envs.navigation import StartAndGoal, distance_table, navigation_features
from mazesim.envs.options import (
    DEFAULT_MAX_EPISODE_STEPS,
    EnvOptions,
    draw_seed,
    json_world_spec,
)
from mazesim.envs.reward import step_reward
from mazesim.envs.spaces import ActionConverter, ObservationLayout, sensor_ranges
from mazesim.errors import (
    InvalidArgumentError,
    RegisteredName,
    WrongTypeError,
    _a_type,
    _known_name,
    _shown,
)
from mazesim.maze import GoalDistance, PathDistanceTable
from mazesim.render.episode import EpisodeTrace
from mazesim.render.topdown import TopDownRenderer

__all__ = ["EPuckMazeVectorEnv"]

_INFO_KEYS = ("pose", "collisions", "colliding", "distance_to_goal", "is_success")
#: The keywords a ``make_vec`` spec holds for the vector env itself, not for its environments.
_VECTOR_KEYWORDS = (
    "num_envs",
    "vectorization_mode",
    "vector_kwargs",
    "wrappers",
    "threads",
    "autoreset_mode",
    "max_episode_steps",
)


class EPuckMazeVectorEnv(VectorEnv[npt.NDArray[np.float32], npt.NDArray[Any], npt.NDArray[Any]]):
    """N maze environments stepped together by the batch engine.

    Observations, actions, rewards, episode ends and infos are those of
    :class:`~mazesim.envs.EPuckMazeEnv`, batched: observations (N, width) float32, actions
    (N, 2) float32 in [-1, 1] or (N,) integers in 0..11, rewards (N,) float64, terminations and
    truncations (N,) bool. ``info["checkpoint"]`` and its mask ``info["_checkpoint"]`` appear on
    steps where at least one environment crossed a barcode.

    ``reset(seed=s)`` seeds environment i with ``s + i`` (or takes a list of N seeds);
    ``reset(options={"reset_mask": mask})`` resets only the environments where the (N,) bool
    ``mask`` is true and leaves the others' observations as they were.

    Args:
        num_envs: Number of environments.
        max_episode_steps: The time limit in steps (truncation); None for no limit.
        render_mode: None or ``"rgb_array"``: :meth:`render` returns one image per environment.
        threads: Worker threads of the batch engine (0: one per core). The results do not depend
            on it.
        autoreset_mode: gymnasium's ``AutoresetMode`` (or its value, ``"NextStep"`` or
            ``"SameStep"``). NEXT_STEP (the default): the step after an episode ends starts the
            next one. SAME_STEP (what Stable-Baselines3 expects): the step that ends an episode
            returns the first observation of the next one, and the last observation and info of
            the ended episode in ``info["final_obs"]`` and ``info["final_info"]`` (masks
            ``_final_obs``, ``_final_info``), as ``SyncVectorEnv`` does in that mode. DISABLED:
            no environment restarts by itself; reset the ended ones with
            ``reset(options={"reset_mask": terminated | truncated})`` before the next step
            (stepping an ended environment raises ResetNeeded).
        vector_kwargs: The vector env's own keywords as a dict (``threads``,
            ``autoreset_mode``, ...), as ``SyncVectorEnv`` takes them; merged with the
            keywords above.
        **options: The options of :meth:`mazesim.envs.options.EnvOptions.create`, as for
            :class:`~mazesim.envs.EPuckMazeEnv`; with ``world="random"`` every environment draws
            its own maze at each reset.

    Raises:
        InvalidArgumentError: An option has a wrong type or value.
        UnknownNameError: The world or robot profile does not exist.
    """

    metadata: dict[str, Any] = {
        "render_modes": VECTOR_RENDER_MODES,
        "render_fps": 31.25,
        "autoreset_mode": AutoresetMode.NEXT_STEP,
    }

    def __init__(
        self,
        num_envs: int = 1,
        max_episode_steps: int | None = DEFAULT_MAX_EPISODE_STEPS,
        render_mode: RegisteredName | None = None,
        threads: int = 0,
        autoreset_mode: AutoresetMode | str = AutoresetMode.NEXT_STEP,
        vector_kwargs: dict[str, Any] | None = None,
        **options: Any,
    ) -> None:
        if vector_kwargs:
            merged = _vector_keywords(
                vector_kwargs,
                max_episode_steps=max_episode_steps,
                render_mode=render_mode,
                threads=threads,
                autoreset_mode=autoreset_mode,
            )
            max_episode_steps = merged["max_episode_steps"]
            render_mode = merged["render_mode"]
            threads = merged["threads"]
            autoreset_mode = merged["autoreset_mode"]
        if not isinstance(num_envs, (int, np.integer)) or num_envs < 1:
            raise InvalidArgumentError(
                f"expected num_envs to be at least 1, found {_shown(num_envs)}"
            )
        if max_episode_steps is not None and (
            not isinstance(max_episode_steps, (int, np.integer)) or max_episode_steps < 1
        ):
            raise InvalidArgumentError(
                "expected max_episode_steps to be at least 1 or None, found "
                f"{_shown(max_episode_steps)}"
            )
        check_render_mode(render_mode, VECTOR_RENDER_MODES)
        self.autoreset_mode = _autoreset_mode(autoreset_mode)
        self.options = EnvOptions.from_keywords(options)
        self.num_envs = int(num_envs)
        self._threads = threads
        self.max_episode_steps = None if max_episode_steps is None else int(max_episode_steps)
        self.render_mode = render_mode
        first = self.options.sample_world()
        self.metadata = {
            **type(self).metadata,
            "render_fps": 1000.0 / step_length_ms(self.options, first),
            "autoreset_mode": self.autoreset_mode,
        }
        self._layout = ObservationLayout(self.options.robot, first, self.options.include_pose)
        self._actions = ActionConverter(
            self.options.action_mode, self.options.robot.max_wheel_speed, self.options.clip_actions
        )
        table = PathDistanceTable.of_world(first)
        self._features = navigation_features(
            self.options.observation,
            self.num_envs,
            self.options.robot,
            first,
            table,
            self.options.include_pose,
        )
        features = self._features
        self.single_observation_space = self._layout.space if features is None else features.space
        # The positions in metres the observation space holds, as the single env's.
        self._held_bounds = self._layout.position_bounds if features is None else None
        self.single_action_space = self._actions.space
        n = self.num_envs
        # The batch first: it checks num_envs against the memory it needs before the spaces
        # below allocate per-environment bounds.
        batch = self._new_batch(first)
        self._batch: BatchSimulator | None = batch
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self._sensors, self._poses, self._colliding, self._crossings = batch.output_buffers()
        self._worlds: list[World] = [first] * n
        self._renderers: list[TopDownRenderer | None] = [None] * n
        # Each environment's trail and overlay, kept only when frames are rendered.
        self._traces = [EpisodeTrace() for _ in range(n)] if self.render_mode else None
        self._drawn: list[StartAndGoal | None] = [None] * n
        self._goal = GoalDistance(n, table)
        self._previous = np.zeros((n, 2), dtype=np.float32)
        self._rngs: list[np.random.Generator | None] = [None] * n
        self._distance = np.zeros(n)
        self._reached = np.zeros(n, dtype=bool)
        self._elapsed = np.zeros(n, dtype=np.int64)
        self._autoreset = np.zeros(n, dtype=bool)
        self._ended = np.zeros(n, dtype=bool)
        self._needs_reset = True

    #: The spec ``gymnasium.make`` recorded, a ``World`` given as ``world`` in its JSON form
    #: (:func:`~mazesim.envs.options.world_as_json`) so that ``spec.to_json()`` works.
    spec = json_world_spec()

    @property
    def single_env_spec(self) -> EnvSpec | None:
        """The spec of one of its environments, as ``gymnasium.make`` records a single env's: the
        task's id and options without the vector env's own keywords (``num_envs``, ``threads``,
        ``autoreset_mode``, ...) and its time limit as ``max_episode_steps``, so
        ``gymnasium.make(envs.single_env_spec)`` makes one environment of the same task. None
        when the env has no spec (made without ``gymnasium.make_vec``)."""
        spec = self.spec
        if spec is None:
            return None
        kwargs = {key: value for key, value in spec.kwargs.items() if key not in _VECTOR_KEYWORDS}
        return dataclasses.replace(spec, kwargs=kwargs, max_episode_steps=self.max_episode_steps)

    @property
    def observation_names(self) -> list[str]:
        """What each column of the observations holds (sensor names, then x, y, yaw, or the
        navigation features)."""
        return list(self._layout.names if self._features is None else self._features.names)

    @property
    def goal_discs(self) -> npt.NDArray[np.float64]:
        """(N, 3): x, y and radius (metres) of each environment's goal disc in its current
        episode; a NaN row for an environment whose world has no goal."""
        return self._open_batch().goals()

    def reset(
        self,
        *,
        seed: int | list[int | None] | None = None,
        options: dict[str, Any] | None = None,
    ) -> tuple[npt.NDArray[np.float32], dict[str, Any]]:
        """Resets all environments, or those of ``options["reset_mask"]``.

        Raises:
            InvalidArgumentError: The seeds or the reset mask do not match ``num_envs``, or
                ``options`` is not a dict.
            EnvClosedError: The env is closed.
        """
        batch = self._open_batch()
        n = self.num_envs
        seeds = self._seeds(seed)
        mask = self._reset_mask(check_options(options, ("reset_mask",)).get("reset_mask"))
        super().reset(seed=seeds[0] if is_seed(seed) else None)
        envs = np.flatnonzero(mask) if mask is not None else np.arange(n)
        for i in envs:
            if seeds[i] is not None or self._rngs[i] is None:
                self._rngs[i] = seeding.np_random(seeds[i])[0]
        self._reset_envs(batch, envs)
        self._distance[envs] = self._goal.evaluate(self._poses)[0][envs]
        self._reached[envs] = False
        self._ended[envs] = False
        self._needs_reset = False
        return self._observations(), self._info(mask)

    @checks_own_arguments
    def step(
        self, actions: npt.NDArray[Any]
    ) -> tuple[
        npt.NDArray[np.float32],
        npt.NDArray[np.float64],
        npt.NDArray[np.bool_],
        npt.NDArray[np.bool_],
        dict[str, Any],
    ]:
        """Steps every environment; those whose episode ended at the last step start a new one.

        Raises:
            InvalidActionError: The actions have a wrong shape or dtype, are NaN or infinite, or
                lie outside the space (continuous ones only with ``clip_actions=False``); the
                message names the environment.
            ResetNeededError: :meth:`reset` has not been called yet.
            EnvClosedError: The env is closed.
        """
        batch = self._open_batch()
        if self._needs_reset:
            raise ResetNeededError("call reset() before step()")
        if self.autoreset_mode == AutoresetMode.DISABLED and self._ended.any():
            raise ResetNeededError(
                "expected the ended environments to be reset with "
                'reset(options={"reset_mask": ...}) before step() (autoreset_mode=DISABLED); '
                f"found environments {np.flatnonzero(self._ended).tolist()} not reset"
            )
        speeds = self._actions.batch(actions, self.num_envs)
        if self._features is not None:
            self._previous = speeds / self._actions.max_speed
        batch.step(speeds, self._sensors, self._poses, self._colliding, self._crossings)
        restarting = self._autoreset.copy()
        any_restart = bool(restarting.any())
        if any_restart:
            # The ended environments took one more step above; resetting discards it.
            self._reset_envs(batch, np.flatnonzero(restarting))
        distance, reached = self._goal.evaluate(self._poses)
        rewards = step_reward(
            self.options.reward, self._distance, distance, self._colliding, reached
        )
        self._distance = distance
        self._elapsed += 1
        terminated = reached
        if self.max_episode_steps is None:
            truncated = np.zeros(self.num_envs, dtype=bool)
        else:
            truncated = self._elapsed >= self.max_episode_steps
        if any_restart:
            rewards[restarting] = 0.0
            terminated[restarting] = False
            truncated[restarting] = False
            self._elapsed[restarting] = 0
        self._reached = terminated.copy()
        if self._traces is not None:
            self._note_steps(rewards, terminated, restarting if any_restart else None)
        observations = self._observations()
        if self.autoreset_mode == AutoresetMode.DISABLED:
            self._ended = terminated | truncated
            return observations, rewards, terminated, truncated, self._info(None)
        if self.autoreset_mode == AutoresetMode.NEXT_STEP:
            self._autoreset = terminated | truncated
            return observations, rewards, terminated, truncated, self._info(None)
        ended = terminated | truncated
        if not ended.any():
            return observations, rewards, terminated, truncated, self._info(None)
        # SAME_STEP: the ended environments start their next episode now; what they ended with
        # goes into info["final_obs"] and info["final_info"], as SyncVectorEnv puts it there.
        final_info = self._info(ended)
        final_obs = np.full(self.num_envs, None, dtype=object)
        envs = np.flatnonzero(ended)
        for i in envs:
            final_obs[i] = observations[i].copy()
        self._reset_envs(batch, envs)
        self._distance[envs] = self._goal.evaluate(self._poses)[0][envs]
        self._reached[envs] = False
        info = self._info(None)
        info.update(
            final_obs=final_obs, _final_obs=ended, final_info=final_info, _final_info=ended.copy()
        )
        return self._observations(), rewards, terminated, truncated, info

    def render(self) -> tuple[npt.NDArray[np.uint8], ...] | None:
        """One top-down (height, width, 3) uint8 image per environment, with
        ``render_mode="rgb_array"``.

        Raises:
            EnvClosedError: The env is closed (as the single env's ``render`` says).
        """
        self._open_batch()
        if self.render_mode is None:
            gymnasium.logger.warn(
                'render() needs a render mode: make the env with render_mode="rgb_array"'
            )
            return None
        frames = []
        for i in range(self.num_envs):
            renderer = self._renderers[i]
            if renderer is None:
                renderer = self._renderer_for(i)
                self._renderers[i] = renderer
            x, y, yaw = (float(v) for v in self._poses[i])
            steps = int(self._elapsed[i])
            seconds = steps * step_length_ms(self.options, self._worlds[i]) / 1000.0
            trace = self._traces[i] if self._traces is not None else EpisodeTrace(x, y)
            frames.append(
                trace.frame(renderer, (x, y, yaw), bool(self._colliding[i]), seconds, steps)
            )
        return tuple(frames)

    def _note_steps(
        self,
        rewards: npt.NDArray[np.float64],
        reached: npt.NDArray[np.bool_],
        restarted: npt.NDArray[np.bool_] | None,
    ) -> None:
        """Counts the step in each environment's trace (those just restarted have begun anew)."""
        assert self._traces is not None
        poses = self._poses.tolist()
        for i, trace in enumerate(self._traces):
            if restarted is not None and restarted[i]:
                continue
            x, y, _ = poses[i]
            trace.note(
                x,
                y,
                float(rewards[i]),
                bool(reached[i]),
                int(self._crossings[i]),
                bool(self._colliding[i]),
                int(self._elapsed[i]),
            )

    def close_extras(self, **kwargs: Any) -> None:
        """Releases the batch engine and the renderers."""
        self._batch = None
        self._renderers = [None] * self.num_envs

    def _observations(self) -> npt.NDArray[np.float32]:
        """The observations of the current state (a new array)."""
        if self._features is None:
            return self._layout.assemble(self._sensors, self._poses)
        return self._features.observe(self._sensors, self._poses, self._previous)

    def __getstate__(self) -> dict[str, Any]:
        """What pickling and deep-copying keep: everything, the batch engine as one snapshot per
        environment (the renderers are made again when needed)."""
        state = self.__dict__.copy()
        batch = state.pop("_batch")
        state["_renderers"] = [None] * self.num_envs
        state["_batch_snapshots"] = (
            None if batch is None else [batch.snapshot_env(i) for i in range(self.num_envs)]
        )
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        """Rebuilds the batch engine from its snapshots: the copy goes on as the original."""
        snapshots = state.pop("_batch_snapshots")
        self.__dict__.update(state)
        self._batch = None
        if snapshots is not None:
            batch = self._new_batch(list(self._worlds))
            for i, snapshot in enumerate(snapshots):
                batch.restore_env(i, snapshot)
            self._batch = batch

    # -- helpers -------------------------------------------------------------------------------

    def _new_batch(self, worlds: World | list[World]) -> BatchSimulator:
        """The batch engine of the envs in ``worlds`` (one for all, or one each), seeds 0."""
        return BatchSimulator(
            worlds,
            self.num_envs,
            robot=self.options.robot,
            seeds=0,
            noise=self.options.noise,
            control_step_ms=self.options.control_step_ms,
            threads=self._threads,
        )

    def _open_batch(self) -> BatchSimulator:
        if self._batch is None:
            raise EnvClosedError("the vector env is closed: make a new one")
        return self._batch

    def _seeds(self, seed: Any) -> list[int | None]:
        """One seed (or None) per environment: ``seed + i``, or the list's, checked.

        Numpy integers count as the ints they hold; anything else is refused by name (gymnasium
        documents ``seed`` as an int or a list of ``num_envs`` ints or None). The seeds accepted
        are the single env's (:func:`mazesim.envs.errors.is_seed`); ``seed + i`` wraps around
        past :data:`~mazesim.envs.errors.MAX_SEED`."""
        n = self.num_envs
        if seed is None:
            return [None] * n
        if is_seed(seed):
            return [(int(seed) + i) % (MAX_SEED + 1) for i in range(n)]
        if not isinstance(seed, (list, tuple)) or len(seed) != n:
            found = f"{len(seed)}" if isinstance(seed, (list, tuple)) else repr(seed)
            raise InvalidArgumentError(
                f"expected seed to be None, an int in 0..={MAX_SEED} or a list of {n} of them "
                f"(one per env), found {found}"
            )
        for i, one in enumerate(seed):
            if one is not None and not is_seed(one):
                raise InvalidArgumentError(
                    f"expected seed {i} to be None or an int in 0..={MAX_SEED}, found {_shown(one)}"
                )
        return [None if one is None else int(one) for one in seed]

    def _reset_mask(self, mask: Any) -> npt.NDArray[np.bool_] | None:
        if mask is None:
            return None
        n = self.num_envs
        if not isinstance(mask, np.ndarray) or mask.dtype != np.bool_ or mask.shape != (n,):
            found = (
                f"shape {mask.shape} of {mask.dtype}"
                if isinstance(mask, np.ndarray)
                else type(mask).__name__
            )
            raise InvalidArgumentError(
                f'expected options["reset_mask"] to be a numpy bool array of shape ({n},), '
                f"found {found}"
            )
        if not mask.any():
            raise InvalidArgumentError('expected options["reset_mask"] to have a True value')
        return mask.copy()

    def _reset_envs(self, batch: BatchSimulator, envs: npt.NDArray[np.intp]) -> None:
        """Starts the next episode of ``envs``, drawing mazes and seeds from their RNGs."""
        mask = np.zeros(self.num_envs, dtype=bool)
        mask[envs] = True
        seeds = np.zeros(self.num_envs, dtype=np.uint64)
        placed: list[int] = []
        starts: list[tuple[float, float, float]] = []
        goals: list[tuple[float, float, float]] = []
        for i in envs:
            rng = self._rngs[i]
            if rng is None:
                rng = self._rngs[i] = seeding.np_random()[0]
            world, drawn = self.options.next_world(rng, self._held_bounds)
            seeds[i] = episode_seed = draw_seed(rng)
            if world is not None:
                batch.set_world(int(i), world, episode_seed)
                self._worlds[i] = world
            if drawn is not None:
                placed.append(int(i))
                starts.append(drawn.start)
                goals.append(drawn.goal)
            if world is not None or drawn is not None:
                self._drawn[i] = drawn
                self._renderers[i] = None
                goal = None if drawn is None else drawn.goal
                table = distance_table(self._worlds[i], goal)
                self._goal.set(int(i), table)
                if self._features is not None:
                    self._features.set(int(i), self._worlds[i], table)
        if self._features is not None:
            self._features.restart(envs)
        if placed:
            where = np.array(placed, dtype=np.int64)
            batch.set_starts_at(where, np.array(starts, dtype=np.float64))
            batch.set_goals_at(where, np.array(goals, dtype=np.float64))
        batch.reset(self._sensors, self._poses, self._colliding, self._crossings, mask, seeds)
        self._previous[envs] = 0.0
        self._elapsed[envs] = 0
        self._autoreset[envs] = False
        if self._traces is not None:
            for i in envs.tolist():
                self._traces[i].restart(float(self._poses[i, 0]), float(self._poses[i, 1]))

    def _info(self, mask: npt.NDArray[np.bool_] | None) -> dict[str, Any]:
        """The infos of the envs in ``mask`` (all without one), laid out as ``SyncVectorEnv``
        lays out those of single envs: values of the others are zero, masks ``_key``."""
        batch = self._open_batch()
        values: dict[str, npt.NDArray[Any]] = {
            "pose": self._poses.copy(),
            "collisions": batch.collisions().astype(np.int64),
            "colliding": self._colliding.copy(),
            "distance_to_goal": self._distance.copy(),
            "is_success": self._reached.copy(),
        }
        has = np.ones(self.num_envs, dtype=bool) if mask is None else mask
        info: dict[str, Any] = {}
        for key in _INFO_KEYS:
            array = values[key]
            if mask is not None:
                array[~mask] = 0
            info[key] = array
            info[f"_{key}"] = has.copy()
        crossed = (self._crossings != 0) & has
        if crossed.any():
            info["checkpoint"] = np.where(crossed, self._crossings, 0).astype(np.int64)
            info["_checkpoint"] = crossed
        return info

    def _renderer_for(self, env: int) -> TopDownRenderer:
        """A renderer of env ``env``'s world, start and goal: another env's if they are equal."""
        world, drawn = self._worlds[env], self._drawn[env]
        for i, other in enumerate(self._worlds):
            renderer = self._renderers[i]
            if renderer is not None and other is world and self._drawn[i] == drawn:
                return renderer
        return TopDownRenderer(
            world,
            self.options.robot,
            self.options.render_size,
            sensor_ranges(self.options.robot).ray_length,
            start=None if drawn is None else drawn.start,
            goal=None if drawn is None else drawn.goal,
        )


def _vector_keywords(vector_kwargs: Any, **given: Any) -> dict[str, Any]:
    """``given`` updated with ``vector_kwargs``, which may hold only the vector env's own
    keywords."""
    if not isinstance(vector_kwargs, dict):
        raise WrongTypeError(f"expected vector_kwargs to be a dict, found {_a_type(vector_kwargs)}")
    unknown = sorted(str(key) for key in vector_kwargs if key not in given)
    if unknown:
        raise InvalidArgumentError(
            f"expected vector_kwargs among {', '.join(given)}; found unknown {', '.join(unknown)}"
        )
    return {**given, **vector_kwargs}


def _autoreset_mode(mode: AutoresetMode | RegisteredName) -> AutoresetMode:
    """The autoreset mode of ``mode`` (the mode or its value); raises UnknownNameError for a
    stranger, with the value meant for one spelt otherwise ("next_step", "NEXT_STEP")."""
    modes = {m.value: m for m in AutoresetMode}
    if isinstance(mode, AutoresetMode):
        return mode
    return modes[_known_name(mode, "autoreset_mode (an AutoresetMode or its value)", tuple(modes))]
