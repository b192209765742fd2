"""What the navigator's odometry is measured from in a transfer study.

A navigator's sub-tasks follow its odometry: the door sub-tasks' phases (the heading turned, with
``--door-distance`` the distance driven since the checkpoint) and, with ``--hold-heading``, the
heading it holds on the maze's grid where it sees no wall. Two sources (``--odometry``):

- ``"truth"``: the simulator's pose, as in every evaluation and in training. A wrong wheel radius
  moves the robot differently but does not mislead it.
- ``"encoders"``: each robot dead-reckons its pose from its own wheel encoders
  (:meth:`mazesim.BatchSimulator.encoders`, quantised to its profile's resolution) with the
  *nominal* wheel radius and axle length of its robot profile, as a real robot's controller
  does, from the true pose at the episode's start. The encoders count the wheels' true rotation,
  so a weaker motor is seen; a wheel radius or axle length off by 5 % makes every distance or
  turn 5 % off in what the navigator believes, and wheels that turn while a wall holds the body
  (pushing against it, or slipping along it: ``slip``) count motion that never happened.

:class:`EncoderOdometryNavigator` wraps a navigator so that the poses it is given are the
encoders' dead reckoning.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._sizes import index_array, number_array
from mazesim.episodes import NavigatorWrapper
from mazesim.odometry import advance

__all__ = ["ODOMETRY_SOURCES", "EncoderOdometryNavigator"]

#: Where a study's navigators take their odometry from.
ODOMETRY_SOURCES = ("truth", "encoders")


class EncoderOdometryNavigator(NavigatorWrapper):
    """A navigator whose poses are dead-reckoned from the robots' wheel encoders.

    Args:
        navigator: The navigator wrapped (``reset(envs, poses)``, ``act(observations, poses,
            events)``).
        read_encoders: Returns the (N, 2) wheel positions (radians; left, right) of every robot
            now, e.g. ``BatchSimulator.encoders``.
        wheel_radius: The nominal wheel radius the controller believes, in metres.
        axle_length: The nominal distance between the wheels, in metres.
    """

    def __init__(
        self,
        navigator: Any,
        read_encoders: Callable[[], npt.ArrayLike],
        wheel_radius: float,
        axle_length: float,
    ) -> None:
        self.navigator = navigator
        self.read_encoders = read_encoders
        self.wheel_radius = float(wheel_radius)
        self.axle_length = float(axle_length)
        count = np.asarray(read_encoders(), dtype=np.float64).shape[0]
        #: (N, 3) the pose each robot believes it is at.
        self.pose = np.zeros((count, 3), dtype=np.float64)
        self._last = np.zeros((count, 2), dtype=np.float64)

    def reset(self, envs: npt.ArrayLike, poses: npt.ArrayLike) -> None:
        """Starts robots ``envs`` afresh: their odometry starts from their true poses."""
        robots = index_array(envs, "envs", self.pose.shape[0])
        self.pose[robots] = number_array(poses, "poses")[robots]
        self._last[robots] = np.asarray(self.read_encoders(), dtype=np.float64)[robots]
        self.navigator.reset(envs, self.pose)

    def act(
        self, observations: npt.ArrayLike, poses: npt.ArrayLike, events: npt.ArrayLike
    ) -> npt.NDArray[np.int64]:
        """Advances every robot's odometry by its wheels' rotation since the last step, then
        asks the navigator with those poses (``poses``, the true ones, are not used)."""
        now = np.asarray(self.read_encoders(), dtype=np.float64)
        rolled = (now - self._last) * self.wheel_radius
        self._last = now.copy()
        advance(self.pose, rolled[:, 0], rolled[:, 1], self.axle_length)
        actions: npt.NDArray[np.int64] = self.navigator.act(observations, self.pose, events)
        return actions
