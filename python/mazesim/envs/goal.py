"""Goal-conditioned tasks in Gymnasium-Robotics' ``GoalEnv`` form, for hindsight relabelling.

The observation is a ``Dict`` of ``observation`` (the wrapped maze env's own), ``achieved_goal``
(the robot's x, y in metres) and ``desired_goal`` (the goal disc's centre x, y). The reward is a
function of the two goals alone, :meth:`MazeGoalEnv.compute_reward`, which Stable-Baselines3's
``HerReplayBuffer`` calls on relabelled batches:

- ``"sparse"``: 0 when the achieved goal lies within the goal disc's radius of the desired goal,
  -1 otherwise (as Gymnasium-Robotics' Fetch tasks);
- ``"dense"``: minus the straight-line distance between the two, in metres.

An episode terminates when the robot's centre enters the goal disc, as in every maze env, and
``info["is_success"]`` says whether the achieved goal is within the radius.

:class:`MazeGoalVectorEnv` is the tasks' native vector env (their ``vector_entry_point``): N goal
envs stepped together by the batch engine, equal bit for bit to ``SyncVectorEnv`` over
:class:`MazeGoalEnv`.
"""

from __future__ import annotations

import math
from typing import Any, SupportsFloat

import gymnasium
import numpy as np
import numpy.typing as npt
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from mazesim._core import World
from mazesim._hot_paths import checks_own_arguments
from mazesim._sizes import number_array
from mazesim.envs.maze_env import EPuckMazeEnv
from mazesim.envs.options import DEFAULT_MAX_EPISODE_STEPS, EnvOptions
from mazesim.envs.vector import EPuckMazeVectorEnv
from mazesim.errors import InvalidArgumentError, RegisteredName, _known_name, _shown

__all__ = ["REWARD_TYPES", "MazeGoalEnv", "MazeGoalVectorEnv"]

#: The reward types of :class:`MazeGoalEnv`.
REWARD_TYPES = ("sparse", "dense")

Observation = dict[str, npt.NDArray[np.float32]]


class _MazeAttributes:
    """Reads the public attributes a goal env does not define from the maze env it wraps (the
    attribute named by ``_wrapped``): ``observation_names``, ``world``, ``options``,
    ``goal_disc`` and whatever the maze env has, as ``env.unwrapped`` gives them for every task."""

    __slots__ = ()
    _wrapped = ""

    def __getattr__(self, name: str) -> Any:
        # Only when the usual lookup fails; the wrapped env is read from the instance's own dict,
        # so a copy being built (which has none yet) is told the attribute is missing.
        inner = self.__dict__.get(self._wrapped)
        if name.startswith("_") or inner is None:
            raise AttributeError(f"{type(self).__name__} has no attribute {name}")
        try:
            return getattr(inner, name)
        except AttributeError:
            raise AttributeError(f"{type(self).__name__} has no attribute {name}") from None


class MazeGoalEnv(_MazeAttributes, gymnasium.Env[Observation, Any]):
    """A maze env whose goal is observed apart and whose reward :meth:`compute_reward` gives.

    Args:
        reward_type: ``"sparse"`` or ``"dense"`` (see the module's description).
        render_mode: As for :class:`~mazesim.envs.EPuckMazeEnv`.
        **options: The options of :class:`~mazesim.envs.EPuckMazeEnv`; the world must have a goal
            (or ``start_goal="random"``).

    Raises:
        UnknownNameError: An unknown reward type or render mode.
        InvalidArgumentError: A world without a goal or a bad option.
    """

    metadata: dict[str, Any] = EPuckMazeEnv.metadata
    _wrapped = "maze"

    def __init__(
        self,
        reward_type: RegisteredName = "sparse",
        render_mode: RegisteredName | None = None,
        **options: Any,
    ) -> None:
        _check_reward_type(reward_type)
        self.reward_type = reward_type
        self._dense = reward_type == "dense"
        self.maze = EPuckMazeEnv(render_mode=render_mode, **options)
        _check_goal(self.maze.world, self.maze.goal_disc, self.maze.options)
        self.render_mode = render_mode
        # The maze env's own metadata, whose render_fps is its control step's rate (7.8125 at
        # 128 ms): the class's is the default 32 ms step's, which RecordVideo would play.
        self.metadata = self.maze.metadata
        self.action_space = self.maze.action_space
        self.observation_space = _goal_space(  # type: ignore[assignment]
            self.maze.observation_space, self.maze.world
        )
        self.maze._held_bounds = _goal_bounds(self.maze.world)
        self._radius = 0.0

    def compute_reward(
        self,
        achieved_goal: npt.ArrayLike,
        desired_goal: npt.ArrayLike,
        info: Any,
    ) -> npt.NDArray[np.float64] | float:
        """The reward of reaching ``achieved_goal`` when ``desired_goal`` was asked, over any
        leading batch dimensions (the last one holds x, y); a float for one pair."""
        return _goal_reward(achieved_goal, desired_goal, self._radius, self.reward_type)

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[Observation, dict[str, Any]]:
        """Resets the maze env; the desired goal is the centre of this episode's goal disc."""
        super().reset(seed=seed)
        observation, info = self.maze.reset(seed=seed, options=options)
        goal = self.maze.goal_disc
        assert goal is not None  # checked at construction
        self._desired = np.array(goal[:2], dtype=np.float32)
        self._radius = float(goal[2])
        self._desired_x, self._desired_y = (float(v) for v in self._desired)
        return self._goal_observation(observation, info), self._goal_info(info)

    @checks_own_arguments
    def step(self, action: Any) -> tuple[Observation, SupportsFloat, bool, bool, dict[str, Any]]:
        """Steps the maze env; the reward is :meth:`compute_reward` of the step's goals."""
        observation, _, terminated, truncated, info = self.maze.step(action)
        # The achieved goal is a view of the pose the core made new this step; the desired goal
        # is copied, as a caller may change an observation it was given.
        achieved = info["pose"][:2]
        # compute_reward's float64 operations on one pair, as Python floats (numpy's array
        # calls cost more than the step here): the same values bit for bit.
        x, y = achieved.tolist()
        dx = x - self._desired_x
        dy = y - self._desired_y
        distance = math.sqrt(dx * dx + dy * dy)
        outside = distance > self._radius
        info["is_success"] = not outside  # the maze env's info is new every step
        return (
            {
                "observation": observation,
                "achieved_goal": achieved,
                "desired_goal": self._desired.copy(),
            },
            -distance if self._dense else -float(outside),
            terminated,
            truncated,
            info,
        )

    def render(self) -> npt.NDArray[np.uint8] | None:
        """The maze env's picture."""
        return self.maze.render()

    def close(self) -> None:
        """Closes the maze env."""
        self.maze.close()

    def _goal_observation(
        self, observation: npt.NDArray[np.float32], info: dict[str, Any]
    ) -> Observation:
        return {
            "observation": observation,
            "achieved_goal": np.asarray(info["pose"][:2], dtype=np.float32),
            "desired_goal": self._desired.copy(),
        }

    def _goal_info(self, info: dict[str, Any]) -> dict[str, Any]:
        achieved = np.asarray(info["pose"][:2], dtype=np.float64)
        within = float(np.linalg.norm(achieved - self._desired.astype(np.float64))) <= self._radius
        return {**info, "is_success": bool(within)}


class MazeGoalVectorEnv(_MazeAttributes, VectorEnv[Observation, Any, Any]):
    """N goal envs stepped together by the batch engine: ``gymnasium.make_vec`` of a
    goal-conditioned task (its ``vector_entry_point``).

    Observations are the ``Dict`` of :class:`MazeGoalEnv` batched (``observation`` (N, width),
    ``achieved_goal`` and ``desired_goal`` (N, 2) float32), rewards (N,) float64 its
    :meth:`MazeGoalEnv.compute_reward`; episodes, autoreset, seeds and infos are those of
    :class:`~mazesim.envs.EPuckMazeVectorEnv`, ``info["is_success"]`` whether each achieved goal
    is within its goal disc. It equals ``SyncVectorEnv`` over N :class:`MazeGoalEnv` with the
    same seeds, bit for bit.

    Args:
        num_envs: Number of environments.
        reward_type: ``"sparse"`` or ``"dense"`` (see the module's description).
        max_episode_steps: The time limit in steps; None for no limit.
        render_mode: None or ``"rgb_array"``.
        **options: The keywords of :class:`~mazesim.envs.EPuckMazeVectorEnv` (``threads``,
            ``autoreset_mode``, ``vector_kwargs``) and its environments' options; the world must
            have a goal (or ``start_goal="random"``).

    Raises:
        UnknownNameError: An unknown reward type or render mode.
        InvalidArgumentError: A world without a goal or a bad option.
    """

    metadata: dict[str, Any] = EPuckMazeVectorEnv.metadata
    _wrapped = "mazes"

    def __init__(
        self,
        num_envs: int = 1,
        reward_type: RegisteredName = "sparse",
        max_episode_steps: int | None = DEFAULT_MAX_EPISODE_STEPS,
        render_mode: RegisteredName | None = None,
        **options: Any,
    ) -> None:
        _check_reward_type(reward_type)
        self.reward_type = reward_type
        self.mazes = EPuckMazeVectorEnv(
            num_envs, max_episode_steps=max_episode_steps, render_mode=render_mode, **options
        )
        world = self.mazes._worlds[0]  # its sample world: a sampler is not called again
        _check_goal(world, world.goal, self.mazes.options)
        self.num_envs = self.mazes.num_envs
        self.render_mode = render_mode
        self.metadata = self.mazes.metadata
        self.single_action_space = self.mazes.single_action_space
        self.action_space = self.mazes.action_space
        self.single_observation_space = _goal_space(self.mazes.single_observation_space, world)
        self.mazes._held_bounds = _goal_bounds(world)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self._discs = np.zeros((self.num_envs, 3))
        self._restarting = np.zeros(self.num_envs, dtype=bool)

    #: The spec ``gymnasium.make_vec`` recorded, and the spec of one of its environments (as the
    #: maze vector env's).
    spec = EPuckMazeVectorEnv.spec
    single_env_spec = EPuckMazeVectorEnv.single_env_spec

    @property
    def max_episode_steps(self) -> int | None:
        """The time limit in steps, or None."""
        return self.mazes.max_episode_steps

    @property
    def autoreset_mode(self) -> AutoresetMode:
        """gymnasium's autoreset mode (as :class:`~mazesim.envs.EPuckMazeVectorEnv`'s)."""
        return self.mazes.autoreset_mode

    def reset(
        self,
        *,
        seed: int | list[int | None] | None = None,
        options: dict[str, Any] | None = None,
    ) -> tuple[Observation, dict[str, Any]]:
        """Resets all environments, or those of ``options["reset_mask"]``, as
        :meth:`EPuckMazeVectorEnv.reset`; each desired goal is its episode's goal disc."""
        observations, info = self.mazes.reset(seed=seed, options=options)
        mask = info["_pose"]
        self._discs[mask] = self.mazes.goal_discs[mask]
        self._restarting[mask] = False
        achieved = info["pose"][:, :2]
        info["is_success"] = self._distances(achieved) <= self._discs[:, 2]
        info["is_success"][~mask] = False
        return self._observations(observations, achieved), info

    @checks_own_arguments
    def step(
        self, actions: npt.NDArray[Any]
    ) -> tuple[
        Observation,
        npt.NDArray[np.float64],
        npt.NDArray[np.bool_],
        npt.NDArray[np.bool_],
        dict[str, Any],
    ]:
        """Steps every environment, as :meth:`EPuckMazeVectorEnv.step`; the rewards are
        :meth:`MazeGoalEnv.compute_reward` of each step's goals."""
        observations, _, terminated, truncated, info = self.mazes.step(actions)
        pose = info["final_info"]["pose"] if "final_info" in info else info["pose"]
        ended = info.get("_final_info", np.zeros(self.num_envs, dtype=bool))
        # The step's goals: the ended environments' (SAME_STEP) from their final pose.
        achieved = np.where(ended[:, None], pose[:, :2], info["pose"][:, :2])
        distances = self._distances(achieved)
        outside = distances > self._discs[:, 2]
        rewards = -distances if self.reward_type == "dense" else -outside.astype(np.float64)
        success = ~outside
        restarted = self._restarting
        if restarted.any():  # NEXT_STEP: these began a new episode with this step's observation
            rewards[restarted] = 0.0
        if self.autoreset_mode == AutoresetMode.NEXT_STEP:
            self._restarting = terminated | truncated
        if ended.any():  # SAME_STEP: the ended episode's last observation, with its own goals
            info["final_info"]["is_success"] = success & ended
            final = info["final_obs"]
            for i in np.flatnonzero(ended):
                final[i] = {
                    "observation": final[i],
                    "achieved_goal": pose[i, :2].copy(),
                    "desired_goal": self._discs[i, :2].astype(np.float32),
                }
        renewed = restarted | ended
        if renewed.any():
            self._discs[renewed] = self.mazes.goal_discs[renewed]
            achieved = info["pose"][:, :2]
            success[renewed] = (self._distances(achieved) <= self._discs[:, 2])[renewed]
        info["is_success"] = success
        return self._observations(observations, achieved), rewards, terminated, truncated, info

    def compute_reward(
        self,
        achieved_goal: npt.ArrayLike,
        desired_goal: npt.ArrayLike,
        info: Any,
    ) -> npt.NDArray[np.float64] | float:
        """:meth:`MazeGoalEnv.compute_reward` of these episodes' goal disc radius (one for all
        the environments: the world's goal, or a third of a cell of the task's mazes).

        Raises:
            InvalidArgumentError: The environments' goal discs differ in radius.
        """
        radii = np.unique(self._discs[:, 2])
        if len(radii) != 1:
            raise InvalidArgumentError(
                f"expected one goal radius for all environments, found {radii.tolist()}"
            )
        return _goal_reward(achieved_goal, desired_goal, float(radii[0]), self.reward_type)

    def render(self) -> tuple[npt.NDArray[np.uint8], ...] | None:
        """The maze vector env's pictures."""
        return self.mazes.render()

    def close_extras(self, **kwargs: Any) -> None:
        """Closes the maze vector env."""
        self.mazes.close()

    def _distances(self, achieved: npt.NDArray[np.float32]) -> npt.NDArray[np.float64]:
        """The distance of each achieved goal to its desired goal, in float64 as
        :meth:`MazeGoalEnv.step` computes it."""
        desired = self._discs[:, :2].astype(np.float32).astype(np.float64)
        delta = number_array(achieved, "achieved") - desired
        return np.sqrt(delta[:, 0] * delta[:, 0] + delta[:, 1] * delta[:, 1])

    def _observations(
        self, observations: npt.NDArray[np.float32], achieved: npt.NDArray[np.float32]
    ) -> Observation:
        return {
            "observation": observations,
            "achieved_goal": np.ascontiguousarray(number_array(achieved, "achieved", np.float32)),
            "desired_goal": self._discs[:, :2].astype(np.float32),
        }


def _check_reward_type(reward_type: RegisteredName) -> None:
    _known_name(reward_type, "reward_type", REWARD_TYPES)


def _check_goal(world: World, goal: tuple[float, float, float] | None, options: EnvOptions) -> None:
    """Refuses a world without a goal unless every episode draws its own."""
    if goal is None and options.start_goal != "random":
        raise InvalidArgumentError(
            f"expected a world with a goal (or start_goal='random'); found {_shown(world.name)} "
            "without one"
        )


def _goal_space(observation_space: gymnasium.Space[Any], world: World) -> gymnasium.spaces.Dict:
    """The goal env's observation space; random mazes of one size share their bounds, so the
    sample maze's hold for every episode (a drawn world outside them is refused at its reset)."""
    goal_space = _goal_box(world)
    return gymnasium.spaces.Dict(
        {"observation": observation_space, "achieved_goal": goal_space, "desired_goal": goal_space}
    )


def _goal_box(world: World) -> gymnasium.spaces.Box:
    """The space of the goals, x and y in metres within ``world``'s bounds."""
    bounds = world.bounds
    low = np.array(bounds[:2], dtype=np.float32)
    high = np.array(bounds[2:], dtype=np.float32)
    return gymnasium.spaces.Box(low, high, dtype=np.float32)


def _goal_bounds(world: World) -> tuple[float, float, float, float]:
    """The x, y bounds in metres of the goals the space of ``world`` holds: within the pose's of
    the raw readings, so the maze env checks each drawn world against these."""
    box = _goal_box(world)
    return (float(box.low[0]), float(box.low[1]), float(box.high[0]), float(box.high[1]))


def _goal_reward(
    achieved_goal: npt.ArrayLike, desired_goal: npt.ArrayLike, radius: float, reward_type: str
) -> npt.NDArray[np.float64] | float:
    """:meth:`MazeGoalEnv.compute_reward`."""
    achieved = number_array(achieved_goal, "achieved_goal", checked_after=True)
    desired = number_array(desired_goal, "desired_goal", checked_after=True)
    for name, goals in (("achieved_goal", achieved), ("desired_goal", desired)):
        if goals.shape[-1:] != (2,) or not np.isfinite(goals).all():
            found = f"shape {goals.shape}" if goals.shape[-1:] != (2,) else "NaN or infinity"
            raise InvalidArgumentError(
                f"expected {name} to be finite (x, y) pairs (a last dimension of 2), found {found}"
            )
    distance = np.linalg.norm(achieved - desired, axis=-1)
    reward = -distance if reward_type == "dense" else -(distance > radius).astype(np.float64)
    return float(reward) if reward.ndim == 0 else reward
