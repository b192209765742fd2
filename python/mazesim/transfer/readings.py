"""Another robot's readings in the navigator's terms: the seed robot's Sharp volts.

The navigator learned on the ``seed`` robot: six Sharp GP2Y0A41SK0F sensors in volts, in the
report's order (front, back, left, right, left-front, right-front), turned into Table 4.1's levels
by distance. To run it on another profile, :class:`SeedReadings` turns that profile's readings
into the volts the seed robot would read at the same distances:

1. each of the six directions takes the other robot's sensors whose heading is nearest to it
   (within 0.05 rad of the nearest: the e-puck's front is ps0 and ps7, at -17 and +17 degrees);
2. each reading becomes a distance through its own sensor's lookup table, inverted
   (:meth:`mazesim.RobotProfile.distance_from_reading`); a direction takes the nearest of its
   sensors' distances;
3. a distance in the last tenth of the sensor's range (at 0.9 of its farthest table distance or
   beyond) counts as "no wall seen" and becomes 40 cm, the Sharp's farthest;
4. the distance becomes seed volts through the seed robot's Sharp table.

The e-puck's own infra-red sensors see 7 cm at most, so on the e-puck profiles Table 4.1's
levels 1 and 2 (7-20 cm) fold into "far": the study measures what that costs. The AlphaBot2 has
the seed robot's sensors (farther from its centre, on a larger body), so its readings pass
through unchanged but for step 3.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._core import RobotProfile
from mazesim._sizes import number_array
from mazesim.episodes import NavigatorWrapper
from mazesim.learn.discretise import NUM_SENSORS, SHARP_TABLE
from mazesim.odometry import wrap_angle

__all__ = ["FAR_CM", "SeedReadings", "SeedReadingsNavigator"]

#: The distance a direction that sees no wall is given, in metres (the Sharp table's farthest).
FAR_M = SHARP_TABLE[-1][0]
#: The same in cm.
FAR_CM = 100.0 * FAR_M
#: Share of a sensor's range beyond which it counts as seeing no wall.
SEEN_SHARE = 0.9
#: Headings within this many radians of a direction's nearest count as that direction's too.
HEADING_TOLERANCE = 0.05
#: Readings sampled to invert a sensor's table.
INVERSE_SAMPLES = 2048

_SHARP_DISTANCES = np.array([d for d, _ in SHARP_TABLE])
_SHARP_VOLTS = np.array([v for _, v in SHARP_TABLE])


def _angle_between(a: npt.NDArray[np.float64], b: float) -> npt.NDArray[np.float64]:
    return np.abs(wrap_angle(a - b))


class SeedReadings:
    """Maps a profile's distance readings to the seed robot's six Sharp volts.

    Args:
        profile: The robot that reads.
    """

    def __init__(self, profile: RobotProfile) -> None:
        seed = RobotProfile.builtin("seed")
        directions = seed.distance_sensor_poses()[:NUM_SENSORS, 2]
        headings = profile.distance_sensor_poses()[:, 2]
        self.sensors: list[list[int]] = []
        for direction in directions:
            gaps = _angle_between(headings, float(direction))
            self.sensors.append(
                [int(i) for i in np.flatnonzero(gaps <= gaps.min() + HEADING_TOLERANCE)]
            )
        limits = profile.distance_sensor_limits()
        self.seen_up_to = SEEN_SHARE * limits[:, 1]
        self.grids: list[npt.NDArray[np.float64]] = []
        self.distances: list[npt.NDArray[np.float64]] = []
        for index in range(len(headings)):
            top = 1.5 * profile.distance_sensor_max
            grid = np.linspace(0.0, top, INVERSE_SAMPLES)
            self.grids.append(grid)
            self.distances.append(
                np.array([profile.distance_from_reading(index, float(r)) for r in grid])
            )

    def distances_m(self, readings: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """(N, 6) distances in metres of the six directions from (N, W) readings."""
        rows = number_array(readings, "readings")
        out = np.empty((rows.shape[0], NUM_SENSORS))
        for place, sensors in enumerate(self.sensors):
            seen = []
            for index in sensors:
                distance = np.interp(rows[:, index], self.grids[index], self.distances[index])
                seen.append(np.where(distance >= self.seen_up_to[index], FAR_M, distance))
            out[:, place] = np.min(seen, axis=0)
        return out

    def volts(self, readings: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """(N, 6) seed-robot volts at the distances the readings show."""
        return np.interp(self.distances_m(readings), _SHARP_DISTANCES, _SHARP_VOLTS)

    def tables(self) -> dict[str, Any]:
        """The map as data, for the core's training round (``readings`` of a crew of
        :func:`mazesim._core.train_lower_round`), which computes :meth:`volts` from it."""
        directions = np.zeros((NUM_SENSORS, len(self.grids)), dtype=bool)
        for place, sensors in enumerate(self.sensors):
            directions[place, sensors] = True
        return {
            "directions": directions,
            "readings": np.stack(self.grids),
            "distances": np.stack(self.distances),
            "seen_up_to": np.ascontiguousarray(self.seen_up_to, dtype=np.float64),
            "far": float(FAR_M),
            "table_distances": _SHARP_DISTANCES,
            "table_volts": _SHARP_VOLTS,
        }


class SeedReadingsNavigator(NavigatorWrapper):
    """A navigator of the seed robot driving another profile through :class:`SeedReadings`.

    Args:
        navigator: The seed robot's navigator.
        profile: The profile it drives.
    """

    def __init__(self, navigator: Any, profile: RobotProfile) -> None:
        self.navigator = navigator
        self.readings = SeedReadings(profile)

    def reset(self, envs: npt.ArrayLike, poses: npt.ArrayLike) -> None:
        """Starts robots ``envs`` afresh."""
        self.navigator.reset(envs, poses)

    def act(
        self, observations: npt.ArrayLike, poses: npt.ArrayLike, events: npt.ArrayLike
    ) -> npt.NDArray[np.int64]:
        """The navigator's actions on the readings in seed volts."""
        rows = np.asarray(observations)
        volts = self.readings.volts(rows).astype(rows.dtype)
        return np.asarray(self.navigator.act(volts, poses, events), dtype=np.int64)
