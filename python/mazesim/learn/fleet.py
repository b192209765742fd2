"""Robots of several profiles trained side by side, each read in the seed robot's volts.

The lower level's tables are indexed by Table 4.1's six levels of the seed robot's Sharp volts. A
robot of another profile (the e-puck's eight infra-red sensors, say) can train them only through
a mapping of its readings into those volts, the one the transfer study drives it with. A
:class:`Fleet` names, for each env, its profile and its group (the robots of one base profile);
each group has a mapping of its distance readings into the seed robot's six volts (none for the
seed robot's own sensors). :class:`FleetBatch` steps each group in its own
:class:`~mazesim.batch.RobotBatch` (a batch holds robots of one set of sensors) and shows the
whole fleet as one batch of seed-robot observations.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from mazesim._core import RobotProfile, World
from mazesim._sizes import bounded_array
from mazesim.batch import RobotBatch, RobotChoice
from mazesim.errors import InvalidArgumentError
from mazesim.learn.discretise import NUM_SENSORS

__all__ = ["Fleet", "FleetBatch", "ReadingsMap"]

#: Maps (M, W) distance readings of a group's robots to (M, 6) seed-robot volts.
ReadingsMap = Callable[[npt.NDArray[np.float32]], npt.ArrayLike]


@dataclass(frozen=True)
class Fleet:
    """The robots of a training round, of several base profiles.

    Attributes:
        profiles: Each env's profile (its group's base profile, perhaps perturbed). The first
            env of each group sets what the group's controllers believe of their wheels (the
            actions' wheel speeds), as a batch's first robot does.
        group: (N,) each env's group, from 0.
        readings: Each group's mapping of its readings into seed volts; None for the seed
            robot's own six sensors.
        higher: The robots of a stage that drives the navigator on raw readings (the higher
            level's training): a :data:`~mazesim.batch.RobotChoice`.
    """

    profiles: Sequence[RobotProfile]
    group: npt.NDArray[np.int64]
    readings: Sequence[ReadingsMap | None]
    higher: RobotChoice

    def __post_init__(self) -> None:
        count = len(self.profiles)
        groups = np.asarray(self.group)
        if groups.shape != (count,) or count < 1:
            raise InvalidArgumentError(
                f"expected one group per env for {count} profile(s), found the shape {groups.shape}"
            )
        if groups.min() < 0 or groups.max() >= len(self.readings):
            raise InvalidArgumentError(
                f"expected groups from 0 to {len(self.readings) - 1}, found "
                f"{int(groups.min())} to {int(groups.max())}"
            )


class FleetBatch:
    """A :class:`Fleet` stepped as one batch: the attributes a lower-level trainer reads of a
    :class:`~mazesim.batch.RobotBatch`, with observations in seed volts.

    Args:
        worlds: The worlds; every robot starts in ``worlds[0]``.
        fleet: The robots.
        control_step_ms: The control step.
        threads: Worker threads of each group's batch (0: one per core); results do not depend
            on it.

    Attributes:
        profile: The first env's profile.
        observations: (N, 6) float32 seed-robot volts of each robot's distance sensors.
        poses: (N, 3) float32 x, y, yaw.
        colliding: (N,) bool, in contact with a wall.
    """

    def __init__(
        self,
        worlds: Sequence[World],
        fleet: Fleet,
        control_step_ms: float,
        threads: int = 0,
    ) -> None:
        group = np.asarray(fleet.group, dtype=np.int64)
        count = group.size
        self.num_envs = count
        self.members = [np.flatnonzero(group == g) for g in range(len(fleet.readings))]
        self.readings = list(fleet.readings)
        self.batches: list[RobotBatch | None] = [
            RobotBatch(
                worlds,
                np.zeros(envs.size, dtype=np.int64),
                robot=[fleet.profiles[int(env)] for env in envs],
                control_step_ms=control_step_ms,
                threads=threads,
            )
            if envs.size
            else None
            for envs in self.members
        ]
        # Each env's group and its row in that group's batch.
        self.group = group
        self.row = np.zeros(count, dtype=np.int64)
        for envs in self.members:
            self.row[envs] = np.arange(envs.size)
        self.profile = fleet.profiles[0]
        self.observations = np.zeros((count, NUM_SENSORS), dtype=np.float32)
        self.poses = np.zeros((count, 3), dtype=np.float32)
        self.colliding = np.zeros(count, dtype=bool)

    def _parts(self) -> list[tuple[npt.NDArray[np.int64], RobotBatch, ReadingsMap | None]]:
        return [
            (envs, batch, readings)
            for envs, batch, readings in zip(self.members, self.batches, self.readings)
            if batch is not None
        ]

    def _gather(self) -> None:
        for envs, batch, readings in self._parts():
            distances = batch.observations[:, : batch.distance_width]
            volts = distances[:, :NUM_SENSORS] if readings is None else readings(distances)
            self.observations[envs] = np.asarray(volts, dtype=np.float32)
            self.poses[envs] = batch.poses
            self.colliding[envs] = batch.colliding

    def step(self, actions: npt.ArrayLike) -> None:
        """Steps every robot with discrete actions (each group's wheel speeds are fractions of
        its first robot's motor limit); the buffers hold the results."""
        chosen = np.asarray(actions, dtype=np.int64)
        for envs, batch, _ in self._parts():
            batch.step(chosen[envs])
        self._gather()

    def move_to_world(self, env: int, world: int) -> None:
        """Puts robot ``env`` into ``worlds[world]`` (see :meth:`RobotBatch.move_to_world`)."""
        batch = self.batches[int(self.group[env])]
        assert batch is not None  # an env's group has that env
        batch.move_to_world(int(self.row[env]), world)

    def place(self, envs: npt.ArrayLike, poses: npt.ArrayLike, seeds: npt.ArrayLike) -> None:
        """Starts robots ``envs`` afresh at ``poses`` with noise ``seeds`` (see
        :meth:`RobotBatch.place`); the other robots are not touched."""
        robots = bounded_array(envs, "envs", np.int64, self.num_envs).ravel()
        starts = bounded_array(poses, "poses", np.float64, 3 * robots.size)
        starts = starts.reshape(robots.size, 3)
        noise = bounded_array(seeds, "seeds", np.uint64, robots.size).ravel()
        for index, batch in enumerate(self.batches):
            mine = self.group[robots] == index
            if batch is not None and mine.any():
                batch.place(self.row[robots[mine]], starts[mine], noise[mine])
        self._gather()
