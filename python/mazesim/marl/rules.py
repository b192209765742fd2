"""Reference policies of the multi-robot tasks, on the agents' own observations: a random policy
and a hand rule per task, each a function from (..., width) observations to (..., 2) actions.

- ``goal_seeking`` (``maze_goals_v0``): the report's avoid-collision rule (Alg. 1: a front
  sensor above 80 turns the robot away from it, wheels at 0 and full speed) where something is
  close ahead, else steer towards the goal (a proportional turn on its bearing).
- ``gathering`` (``aggregation_v0``): steer towards the centroid of the other robots; with
  something close ahead, stand still if it is the nearest robot (the robot has joined the
  cluster), else turn away from it as the avoid-collision rule does.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import numpy.typing as npt

from mazesim.marl.tasks import PROXIMITY_MAX

__all__ = ["HAND_RULES", "Policy", "gathering", "goal_seeking", "random_policy"]

Policy = Callable[[npt.NDArray[np.float32]], npt.NDArray[np.float32]]

#: The avoid-collision rule's threshold on a raw proximity reading (the report's Alg. 1).
OBSTACLE_THRESHOLD = 80.0
#: Gain of the proportional turn towards a bearing, per radian.
TURN_GAIN = 2.0
#: Range (metres) within which the nearest robot ahead counts as joined.
JOINED_RANGE = 0.1


def _front(observations: npt.NDArray[np.float32]) -> tuple[npt.NDArray[np.bool_], ...]:
    """Whether something is close ahead, and whether more of it is on the right."""
    raw = observations[..., :8].astype(np.float64) * PROXIMITY_MAX
    right = raw[..., 0] + raw[..., 1]
    left = raw[..., 6] + raw[..., 7]
    close = raw[..., [0, 1, 6, 7]].max(axis=-1) > OBSTACLE_THRESHOLD
    return close, right > left


def _steer(
    forward: npt.NDArray[np.float64], left: npt.NDArray[np.float64]
) -> npt.NDArray[np.float64]:
    """Wheel fractions of a proportional turn towards the bearing (forward, left)."""
    turn = TURN_GAIN * np.arctan2(left, forward)
    return np.clip(np.stack((1.0 - turn, 1.0 + turn), axis=-1), -1.0, 1.0)


def _avoid(right_side: npt.NDArray[np.bool_]) -> npt.NDArray[np.float64]:
    """Alg. 1's turn away: an obstacle on the right turns left (left wheel stopped)."""
    return np.where(right_side[..., None], [0.0, 1.0], [1.0, 0.0])


def goal_seeking(observations: npt.NDArray[np.float32]) -> npt.NDArray[np.float32]:
    """The hand rule of ``maze_goals_v0`` (see the module)."""
    close, right_side = _front(observations)
    towards = _steer(
        observations[..., 8].astype(np.float64), observations[..., 9].astype(np.float64)
    )
    return np.where(close[..., None], _avoid(right_side), towards).astype(np.float32)


def gathering(
    observations: npt.NDArray[np.float32], arena_side: float = 1.0
) -> npt.NDArray[np.float32]:
    """The hand rule of ``aggregation_v0`` (see the module); ``arena_side`` as the task's."""
    close, right_side = _front(observations)
    nearest = observations[..., 8].astype(np.float64) * arena_side
    ahead = observations[..., 9] > 0.5
    joined = close & (nearest < JOINED_RANGE) & ahead
    towards = _steer(
        observations[..., 12].astype(np.float64), observations[..., 13].astype(np.float64)
    )
    actions = np.where(close[..., None], _avoid(right_side), towards)
    return np.where(joined[..., None], 0.0, actions).astype(np.float32)


def random_policy(seed: int) -> Policy:
    """Uniform random wheel fractions in [-1, 1], from a stream seeded with ``seed``."""
    rng = np.random.default_rng(seed)

    def act(observations: npt.NDArray[np.float32]) -> npt.NDArray[np.float32]:
        return rng.uniform(-1.0, 1.0, size=(*observations.shape[:-1], 2)).astype(np.float32)

    return act


#: The hand rule of each task, by its module's name.
HAND_RULES: dict[str, Policy] = {"maze_goals_v0": goal_seeking, "aggregation_v0": gathering}
