"""Robots of several profiles trained side by side, each read in the seed robot's volts.

The lower level's tables are indexed by Table 4.1's six levels of the seed robot's Sharp volts. A
robot of another profile (the e-puck's eight infra-red sensors, say) can train them only through
a mapping of its readings into those volts, the one the transfer study drives it with. A
:class:`Fleet` names, for each env, its profile and its group (the robots of one base profile);
each group has a mapping of its distance readings into the seed robot's six volts (none for the
seed robot's own sensors). :class:`FleetBatch` holds each group in its own
:class:`~mazesim.batch.RobotBatch` (a batch holds robots of one set of sensors); the core's
training round drives them all at once, each group a crew with its mapping as data.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np
import numpy.typing as npt

from mazesim._core import RobotProfile, World
from mazesim.batch import RobotBatch, RobotChoice
from mazesim.errors import InvalidArgumentError

__all__ = ["Fleet", "FleetBatch", "ReadingsMap"]


class ReadingsMap(Protocol):
    """Maps (M, W) distance readings of a group's robots to (M, 6) seed-robot volts
    (:class:`mazesim.transfer.readings.SeedReadings`)."""

    def volts(self, readings: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """(M, 6) seed-robot volts of (M, W) readings."""

    def tables(self) -> dict[str, Any]:
        """The map as data, for the core's training round."""


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
    """A :class:`Fleet` as one batch per group, the crews of the core's training round.

    Args:
        worlds: The worlds; every robot starts in ``worlds[0]``.
        fleet: The robots.
        control_step_ms: The control step.
        threads: Worker threads of each group's batch (0: one per core); results do not depend
            on it.

    Attributes:
        profile: The first env's profile.
        members: Each group's robots (their numbers in the fleet).
        batches: Each group's batch (None for a group without robots).
        readings: Each group's mapping into seed volts (None: the seed robot's own).
    """

    def __init__(
        self,
        worlds: Sequence[World],
        fleet: Fleet,
        control_step_ms: float,
        threads: int = 0,
    ) -> None:
        group = np.asarray(fleet.group, dtype=np.int64)
        self.num_envs = group.size
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
        self.profile = fleet.profiles[0]
        self._tables = [
            None if readings is None else readings.tables() for readings in self.readings
        ]

    def crews(self) -> list[tuple[RobotBatch, npt.NDArray[np.int64], dict[str, Any] | None]]:
        """Each group's batch, its robots' numbers in the fleet and its readings map as data
        (None for the seed robot's own volts): the crews of the core's training round."""
        return [
            (batch, envs, tables)
            for envs, batch, tables in zip(self.members, self.batches, self._tables)
            if batch is not None
        ]
