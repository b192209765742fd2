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
"""

from __future__ import annotations

import math
from typing import Any, SupportsFloat

import gymnasium
import numpy as np
import numpy.typing as npt

from mazesim._checks import checks_own_arguments
from mazesim.envs.maze_env import EPuckMazeEnv
from mazesim.errors import InvalidArgumentError

__all__ = ["REWARD_TYPES", "MazeGoalEnv"]

#: The reward types of :class:`MazeGoalEnv`.
REWARD_TYPES = ("sparse", "dense")

Observation = dict[str, npt.NDArray[np.float32]]


class MazeGoalEnv(gymnasium.Env[Observation, Any]):
    """A maze env whose goal is observed apart and whose reward :meth:`compute_reward` gives.

    Args:
        reward_type: ``"sparse"`` or ``"dense"`` (see the module's description).
        render_mode: As for :class:`~mazesim.envs.EPuckMazeEnv`.
        **options: The options of :class:`~mazesim.envs.EPuckMazeEnv`; the world must have a goal
            (or ``start_goal="random"``).

    Raises:
        InvalidArgumentError: An unknown reward type, a world without a goal or a bad option.
    """

    metadata: dict[str, Any] = EPuckMazeEnv.metadata

    def __init__(
        self, reward_type: str = "sparse", render_mode: str | None = None, **options: Any
    ) -> None:
        if reward_type not in REWARD_TYPES:
            raise InvalidArgumentError(
                f"expected reward_type to be one of {', '.join(REWARD_TYPES)}; "
                f"found {reward_type!r}"
            )
        self.reward_type = reward_type
        self._dense = reward_type == "dense"
        self.maze = EPuckMazeEnv(render_mode=render_mode, **options)
        if self.maze.goal_disc is None and self.maze.options.start_goal != "random":
            raise InvalidArgumentError(
                f"expected a world with a goal (or start_goal='random'); found "
                f"{self.maze.world.name!r} without one"
            )
        self.render_mode = render_mode
        self.action_space = self.maze.action_space
        # Random mazes of one size share their bounds: the sample maze's hold for every episode.
        bounds = self.maze.world.bounds
        low = np.array(bounds[:2], dtype=np.float32)
        high = np.array(bounds[2:], dtype=np.float32)
        goal_space = gymnasium.spaces.Box(low, high, dtype=np.float32)
        self.observation_space = gymnasium.spaces.Dict(  # type: ignore[assignment]
            {
                "observation": self.maze.observation_space,
                "achieved_goal": goal_space,
                "desired_goal": goal_space,
            }
        )
        self._radius = 0.0

    def compute_reward(
        self,
        achieved_goal: npt.ArrayLike,
        desired_goal: npt.ArrayLike,
        info: Any,
    ) -> npt.NDArray[np.float64] | float:
        """The reward of reaching ``achieved_goal`` when ``desired_goal`` was asked, over any
        leading batch dimensions (the last one holds x, y); a float for one pair."""
        achieved = np.asarray(achieved_goal, dtype=np.float64)
        desired = np.asarray(desired_goal, dtype=np.float64)
        for name, goals in (("achieved_goal", achieved), ("desired_goal", desired)):
            if goals.shape[-1:] != (2,) or not np.isfinite(goals).all():
                found = f"shape {goals.shape}" if goals.shape[-1:] != (2,) else "NaN or infinity"
                raise InvalidArgumentError(
                    f"expected {name} to be finite (x, y) pairs (a last dimension of 2), "
                    f"found {found}"
                )
        distance = np.linalg.norm(achieved - desired, axis=-1)
        if self.reward_type == "dense":
            reward = -distance
        else:
            reward = -(distance > self._radius).astype(np.float64)
        return float(reward) if reward.ndim == 0 else reward

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
