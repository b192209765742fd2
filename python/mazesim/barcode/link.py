"""How the controller of the reading study sees the simulator: in lockstep, or over a link that
is not synchronised with it, as the report's ROS node was with Webots.

In ``lockstep`` (mazesim's way) the controller and the decoders see every control step's
sensors and command every step. The report's set-up had no such contract: Webots stepped on its
own clock and published the sensors; the ROS node ran its loop when its messages arrived, and the
report names this synchronisation as its unsolved problem (chapter 5) and "with more speed the
sensors do less reading" as a cause of bad barcode readings (section 4.2.2).

:class:`UnsyncedLink` models that link in the simplest way that has both effects: each robot's
node wakes up after a random number of simulator steps, drawn uniformly from
:data:`ROS_LINK_PERIODS` (32 to 96 ms at the maze worlds' 32 ms step, 64 ms on average, the
navigator's control step). Only at a wake-up does the node read the sensors (the decoders get
that sample, the others are lost to it) and send new wheel speeds; in between, the motors keep
the last ones, as a Webots motor keeps its last ``setVelocity``. The further a robot travels
between two wake-ups, the fewer samples fall on each 1.7 cm bar: this is what makes the report's
Alg. 7 fail more at higher speeds.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from mazesim.errors import (
    InvalidArgumentError,
    RegisteredName,
    _known_name,
)

__all__ = ["LINKS", "ROS_LINK_PERIODS", "UnsyncedLink", "check_link"]

#: The links the study knows: ``lockstep`` (every step) and ``ros`` (:class:`UnsyncedLink`).
LINKS = ("lockstep", "ros")
#: Simulator steps between two wake-ups of the unsynchronised node, drawn uniformly.
ROS_LINK_PERIODS = (1, 2, 3)


def check_link(name: RegisteredName) -> str:
    """Returns ``name`` if it is one of :data:`LINKS`.

    Raises:
        UnknownNameError: Any other name.
    """
    return _known_name(name, "link", LINKS)


class UnsyncedLink:
    """Wake-ups of N controller nodes that are not synchronised with the simulator.

    Args:
        num_envs: Robots, one node each.
        seed: Seed of the wake-up times (the same seed gives the same schedule).
        periods: The numbers of steps between two wake-ups, drawn uniformly (all >= 1).

    Example:
        >>> link = UnsyncedLink(3, seed=0)
        >>> awake = link.tick()  # before each simulator step: which nodes act now
        >>> awake.shape
        (3,)
    """

    def __init__(self, num_envs: int, seed: int, periods: Sequence[int] = ROS_LINK_PERIODS) -> None:
        if num_envs < 1:
            raise InvalidArgumentError(f"expected at least one robot, found {num_envs}")
        choices = np.asarray(list(periods), dtype=np.int64)
        if choices.size == 0 or (choices < 1).any():
            raise InvalidArgumentError(
                f"expected periods of at least one step, found {list(periods)}"
            )
        self.periods = choices
        self._rng = np.random.default_rng([seed, 0x5EED11])
        self._step = 0
        # The first wake-ups spread over the first period, as nodes started at random moments.
        self._next = self._rng.integers(1, int(choices.max()) + 1, size=num_envs)

    @property
    def longest_period(self) -> int:
        """The most steps between two wake-ups of a node."""
        return int(self.periods.max())

    def tick(self) -> npt.NDArray[np.bool_]:
        """Advances one simulator step; returns which nodes wake up at it (N,)."""
        self._step += 1
        awake = self._next <= self._step
        count = int(awake.sum())
        if count:
            self._next[awake] = self._step + self._rng.choice(self.periods, size=count)
        return awake
