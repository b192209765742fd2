"""The environments' reward: goal bonus, collision penalty and progress along the shortest path.

The reward of one control step is::

    reward = progress * (d_before - d_after) - collision * colliding + goal * reached

where ``d`` is the shortest-path distance from the robot's centre to the goal in metres (below),
``colliding`` is 1 while the body touches a wall (so every step spent against a wall costs the
penalty) and ``reached`` is 1 on the step the robot's centre enters the goal disc, which ends the
episode. Because the progress term is a difference of one potential, ``d``, a detour or a loop earns
nothing overall: an episode's progress reward sums to ``progress * (d_start - d_end)``.

The distance ``d`` on a cell maze (a world with a ``[grid]``, such as ``seed-maze`` and every
generated maze) is measured in two stages. A breadth-first search over the open cells counts the
cells from each cell to the goal cell; a cell ``k`` cells away lies at ``D = k * cell_size``, its
centre being that far from the goal along the corridors. Inside a cell, ``d`` blends the values of
the cell's open sides, each the mean of the ``D`` of the two cells it joins, and of the goal point
(0) in the goal cell, with weights inversely proportional to the distance from the robot to each
side (Shepard's interpolation). So ``d`` is continuous across open sides, falls linearly along a
straight corridor and bends smoothly round corners; a dead end gets its back wall as one more side,
half a cell farther than its centre, so backing into it still costs. In a world without a cell maze
``d`` is the straight-line distance to the goal, and in a world without a goal it is 0 (no progress
reward and no termination).

Everything here is vectorised over environments, and a single environment runs the same code on
arrays of one row, so the native vector environment and a ``SyncVectorEnv`` agree bit for bit.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from mazesim._sizes import number_array
from mazesim.errors import InvalidArgumentError, _shown
from mazesim.maze import GoalDistance, PathDistanceTable

__all__ = ["GoalDistance", "PathDistanceTable", "RewardWeights", "step_reward"]


@dataclass(frozen=True)
class RewardWeights:
    """The documented weights of the reward.

    Attributes:
        goal: Bonus on the step the robot's centre enters the goal disc.
        collision: Penalty for every control step the body touches a wall.
        progress: Reward per metre gained along the shortest path to the goal (negative when the
            robot moves away from the goal).
    """

    goal: float = 10.0
    collision: float = 0.1
    progress: float = 10.0

    def __post_init__(self) -> None:
        for name in ("goal", "collision", "progress"):
            value = getattr(self, name)
            if not isinstance(value, numbers.Real) or not math.isfinite(value):
                raise InvalidArgumentError(
                    f"expected a finite number for the {name} reward weight, found {_shown(value)}"
                )
            # A numpy scalar (np.float32(5.0) from a sweep) weighs as the Python float it holds,
            # so rewards stay Python floats and float64 arrays whatever the weights' types.
            object.__setattr__(self, name, float(value))


def step_reward(
    weights: RewardWeights,
    before: npt.NDArray[np.float64],
    after: npt.NDArray[np.float64],
    colliding: npt.NDArray[np.bool_],
    reached: npt.NDArray[np.bool_],
) -> npt.NDArray[np.float64]:
    """The reward of one control step for each environment (see the module's description)."""
    return (
        weights.progress * (before - after)
        - weights.collision * number_array(colliding, "colliding")
        + weights.goal * number_array(reached, "reached")
    )
