"""The e-puck2's time-of-flight sensor as Webots' E-puck PROTO (version "2") states it: the
facts the swarm-world tests hold mazesim's ``tof`` readings to."""

from __future__ import annotations

#: The ToF lookup table: distance (m), reading (mm).
TOF_TABLE = [(0.0, 19.8), (0.05, 58.5), (0.1, 111.0), (0.2, 218.9), (0.5, 531.9), (1.0, 1052.0)]


def tof_reading(distance: float) -> float:
    """The ToF table at ``distance`` (m), interpolated."""
    for (d0, v0), (d1, v1) in zip(TOF_TABLE, TOF_TABLE[1:]):
        if d0 <= distance <= d1:
            return v0 + (v1 - v0) * (distance - d0) / (d1 - d0)
    raise ValueError(distance)
