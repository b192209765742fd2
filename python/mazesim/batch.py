"""One owner of a batch simulator and its four output buffers.

A :class:`RobotBatch` holds a :class:`mazesim.BatchSimulator` of N robots together with the
buffers every call writes into (observations, poses, contact flags, checkpoint crossings), and the
table turning the twelve discrete actions (:mod:`mazesim.actions`) into wheel speeds. Everything
above it (:mod:`mazesim.episodes`, :mod:`mazesim.learn`) steps, resets and places robots through
it and reads the buffers. The buffers themselves come from the simulator
(:meth:`mazesim.BatchSimulator.output_buffers`), the one place that knows their shapes and dtypes,
as do those of the batches beside it (the native vector env, the reading study, the bench).

:meth:`RobotBatch.place` puts robots at given poses with given noise seeds: the binding's per-env
start (:meth:`mazesim.BatchSimulator.set_starts_at`) and a masked reset, so a world is never
copied or re-parsed to move a start.

Example:
    >>> import numpy as np, mazesim
    >>> from mazesim.batch import RobotBatch
    >>> batch = RobotBatch([mazesim.load_world("seed-maze")], np.zeros(2, dtype=np.int64))
    >>> x, y, yaw = batch.worlds[0].start
    >>> batch.place([1], [[x + 0.01, y, yaw]], [7])
    >>> batch.step(np.zeros(2, dtype=np.int64))
    >>> batch.poses.shape
    (2, 3)
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Union

import numpy as np
import numpy.typing as npt

from mazesim._core import BatchSimulator, RobotProfile, World
from mazesim._hot_paths import checks_own_arguments
from mazesim._sizes import MOST_ENVS, bounded_array, bounded_list, index_array, seed_array
from mazesim.actions import WHEEL_SPEED_FRACTIONS
from mazesim.errors import InvalidArgumentError, _bounded_number

__all__ = ["CONTROL_STEP_MS", "RobotBatch", "RobotChoice", "cruise_step_length"]

#: The control step of the report's navigator, in milliseconds.
CONTROL_STEP_MS = 64.0
#: A ``robot`` argument: a built-in profile's name or a profile (such as a
#: :meth:`mazesim.RobotProfile.perturbed` one) for every robot, or a sequence of them, one per
#: robot (all with the sensors of the first).
RobotChoice = Union[str, RobotProfile, Sequence[Union[str, RobotProfile]]]


def first_profile(robot: RobotChoice) -> RobotProfile:
    """The profile of the first robot of a ``robot`` argument the batch simulator accepted."""
    first = robot if isinstance(robot, (str, RobotProfile)) else robot[0]
    return first if isinstance(first, RobotProfile) else RobotProfile.load(first)


def cruise_step_length(robot: RobotProfile, control_step_ms: float = CONTROL_STEP_MS) -> float:
    """Metres the robot drives in one control step at the cruise speed (action ``00``)."""
    step = _bounded_number("control_step_ms", control_step_ms, above=0.0)
    left, right = WHEEL_SPEED_FRACTIONS[0]
    speed = 0.5 * (left + right) * robot.max_wheel_speed * robot.wheel_radius
    return float(speed * step / 1000.0)


class RobotBatch:
    """N robots of one profile (or one each), each in one of a list of worlds, with their output
    buffers.

    Args:
        worlds: The worlds; robot ``i`` starts in ``worlds[world_of_env[i]]``.
        world_of_env: (N,) index of each robot's world.
        robot: The robot profile (a name or a :class:`mazesim.RobotProfile`), or one per robot.
        noise: Sensor noise on or off.
        control_step_ms: The control step.
        threads: Worker threads (0: one per core); results do not depend on it.

    Attributes:
        profile: The first robot's profile (every robot has its sensors); the discrete actions'
            wheel speeds are fractions of its motor limit.
        one_motor_limit: Whether every robot has the first's motor limit (the core's tabular
            controller takes the fractions of each robot's own).
        observations: (N, observation_width) float32: distance sensors, then ground sensors.
        poses: (N, 3) float32 x, y, yaw.
        colliding: (N,) bool, in contact with a wall.
        crossings: (N,) int32 checkpoint crossing of the last step (+id, -id or 0).

    Raises:
        InvalidArgumentError: No world, or a robot whose world index is out of range.
    """

    def __init__(
        self,
        worlds: Sequence[World],
        world_of_env: npt.ArrayLike,
        robot: RobotChoice = "seed",
        noise: bool = True,
        control_step_ms: float = CONTROL_STEP_MS,
        threads: int = 0,
    ) -> None:
        self.worlds = bounded_list(worlds, "worlds", MOST_ENVS)
        world_index = bounded_array(world_of_env, "world_of_env", None, MOST_ENVS)
        count = world_index.size
        if not self.worlds or count < 1:
            raise InvalidArgumentError(
                f"expected at least one world and one robot, found {len(self.worlds)} world(s) "
                f"and {count} robot(s)"
            )
        world_index = index_array(world_index, "world indices", len(self.worlds))
        self.world_of_env = world_index.ravel().copy()
        self.num_envs = count
        self.control_step_ms = float(control_step_ms)
        self.simulator = BatchSimulator(
            [self.worlds[i] for i in self.world_of_env],
            robot=robot,
            seeds=0,
            noise=noise,
            control_step_ms=control_step_ms,
            threads=threads,
        )
        self.profile = first_profile(robot)
        self.wheel_speeds = (WHEEL_SPEED_FRACTIONS * self.profile.max_wheel_speed).astype(
            np.float32
        )
        self.distance_width = self.simulator.distance_width
        self.observations, self.poses, self.colliding, self.crossings = (
            self.simulator.output_buffers()
        )

    def speeds_of(self, actions: npt.ArrayLike) -> npt.NDArray[np.float32]:
        """(N, 2) wheel speeds of discrete actions (indices into the action table)."""
        return self.wheel_speeds[index_array(actions, "actions", len(self.wheel_speeds))]

    @checks_own_arguments
    def step(self, actions: npt.ArrayLike) -> None:
        """Steps every robot with discrete actions; the buffers hold the results."""
        self.step_speeds(self.speeds_of(actions))

    def step_speeds(self, speeds: npt.NDArray[np.float32]) -> None:
        """Steps every robot with (N, 2) wheel speeds in rad/s."""
        self.simulator.step(speeds, self.observations, self.poses, self.colliding, self.crossings)

    def reset(
        self, mask: npt.NDArray[np.bool_] | None = None, seeds: npt.ArrayLike | None = None
    ) -> None:
        """Resets the robots where ``mask`` is true (all without one) to their starts.

        Args:
            mask: (N,) bool, the robots to reset.
            seeds: (N,) noise seeds of the reset robots (the others' are ignored).
        """
        rows = None if seeds is None else seed_array(seeds, "seeds", self.num_envs)
        self.simulator.reset(
            self.observations, self.poses, self.colliding, self.crossings, mask=mask, seeds=rows
        )

    def observe(self) -> None:
        """Writes the current state into the buffers without stepping."""
        self.simulator.observe(self.observations, self.poses, self.colliding, self.crossings)

    def place(self, envs: npt.ArrayLike, poses: npt.ArrayLike, seeds: npt.ArrayLike) -> None:
        """Starts robots ``envs`` afresh at ``poses`` ((M, 3) x, y, yaw) with noise ``seeds``.

        Their counters restart and their rows of the buffers hold their first observations;
        the other robots are not touched.
        """
        robots = index_array(envs, "envs", self.num_envs, most=self.num_envs).ravel()
        starts = bounded_array(poses, "poses", np.float64, 3 * robots.size).reshape(robots.size, 3)
        self.simulator.set_starts_at(robots, np.ascontiguousarray(starts))
        mask = np.zeros(self.num_envs, dtype=bool)
        mask[robots] = True
        all_seeds = np.zeros(self.num_envs, dtype=np.uint64)
        all_seeds[robots] = seed_array(seeds, "seeds", robots.size).ravel()
        self.reset(mask, all_seeds)

    def collisions(self) -> npt.NDArray[np.int64]:
        """(N,) wall bumps of each robot since its last reset (the simulator's counter)."""
        return self.simulator.collisions().astype(np.int64)
