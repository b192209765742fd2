"""How the controller meets the robot: control latency and the unsynchronised link.

Both are modelled at control-step granularity by wrapping a navigator (anything with
``reset(envs, poses)`` and ``act(observations, poses, events)``,
:class:`mazesim.episodes.Navigator`), per robot, so that one batch holds robots of several settings:

- **Latency** (:class:`DelayedNavigator`): robot ``i``'s action applied at step ``t`` is the one
  its navigator chose at step ``t - k_i``, from the sensors of that step. The navigator still sees
  every step; its commands arrive late, as over a slow bus. In the first ``k_i`` steps of an
  episode the robot runs its first command (as if the controller had been running before the
  start).
- **Unsynchronised link** (:class:`LinkedNavigator`): as in the barcode study
  (:class:`mazesim.barcode.link.UnsyncedLink`), each linked robot's controller node wakes after
  1 to 3 control steps, drawn uniformly; only then does it read the sensors and send a new
  command, and in between the motors keep the last one. A checkpoint event that happens while the
  node sleeps is delivered at its next wake-up (a queued message), so none is lost. The
  navigator's sub-task odometry keeps running on every step: it is the robot's own wheel
  odometry, which does not cross the link.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._sizes import index_array, whole_array
from mazesim.barcode.link import UnsyncedLink
from mazesim.episodes import MAX_STEPS, NavigatorWrapper

__all__ = ["DelayedNavigator", "LinkedNavigator"]


class DelayedNavigator(NavigatorWrapper):
    """A navigator whose commands reach robot ``i`` ``delays[i]`` control steps late.

    Args:
        navigator: The navigator wrapped.
        delays: (N,) control steps of latency of each robot (0: none).

    Raises:
        InvalidArgumentError: A negative delay.
    """

    def __init__(self, navigator: Any, delays: npt.ArrayLike) -> None:
        self.navigator = navigator
        # Longer than the longest episode would hold nothing back but memory (one row a step).
        self.delays = whole_array(delays, "delays", 0, MAX_STEPS).ravel()
        count = self.delays.size
        longest = int(self.delays.max()) if count else 0
        # history[j, i]: the command robot i's navigator chose j steps ago (-1: none yet).
        self.history = np.full((longest + 1, count), -1, dtype=np.int64)
        self._robots = np.arange(count)

    def reset(self, envs: npt.ArrayLike, poses: npt.ArrayLike) -> None:
        """Starts robots ``envs`` afresh: no command sent yet."""
        self.history[:, index_array(envs, "envs", self.history.shape[1])] = -1
        self.navigator.reset(envs, poses)

    def act(
        self, observations: npt.ArrayLike, poses: npt.ArrayLike, events: npt.ArrayLike
    ) -> npt.NDArray[np.int64]:
        """The commands that reach the robots now."""
        chosen = np.asarray(self.navigator.act(observations, poses, events), dtype=np.int64)
        self.history = np.roll(self.history, 1, axis=0)
        self.history[0] = chosen
        fresh = self.history[1:] < 0
        # A robot in its first steps runs its first command.
        self.history[1:][fresh] = np.broadcast_to(chosen, self.history[1:].shape)[fresh]
        return self.history[self.delays, self._robots].copy()


class LinkedNavigator(NavigatorWrapper):
    """A navigator that reaches the robots marked ``linked`` over an unsynchronised link.

    Args:
        navigator: The navigator wrapped.
        linked: (N,) bool, the robots behind the link (the others are in lockstep).
        seed: Seed of the nodes' wake-ups (:class:`UnsyncedLink`).
    """

    def __init__(self, navigator: Any, linked: npt.ArrayLike, seed: int) -> None:
        self.navigator = navigator
        self.linked = np.asarray(linked, dtype=bool).ravel()
        count = self.linked.size
        self.link = UnsyncedLink(count, seed=seed)
        self.command = np.full(count, -1, dtype=np.int64)
        self.pending = np.zeros(count, dtype=np.int64)

    def reset(self, envs: npt.ArrayLike, poses: npt.ArrayLike) -> None:
        """Starts robots ``envs`` afresh: their node sends a command at the first step."""
        robots = index_array(envs, "envs", self.command.size)
        self.command[robots] = -1
        self.pending[robots] = 0
        self.navigator.reset(envs, poses)

    def act(
        self, observations: npt.ArrayLike, poses: npt.ArrayLike, events: npt.ArrayLike
    ) -> npt.NDArray[np.int64]:
        """The commands the motors run now: new ones from the nodes awake, the last otherwise."""
        event = whole_array(events, "events")
        awake = self.link.tick() | ~self.linked | (self.command < 0)
        self.pending = np.where(event != 0, event, self.pending)
        delivered = np.where(awake, self.pending, 0)
        self.pending[awake] = 0
        chosen = np.asarray(self.navigator.act(observations, poses, delivered), dtype=np.int64)
        self.command = np.where(awake, chosen, self.command)
        return self.command.copy()
