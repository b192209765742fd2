"""Checks that two peers model the same workload: from the same poses, the same next poses and
readings; from the same start, the same trajectories while they stay together.

Both runners must run with the noise off and share their mazes; each needs ``set_poses``,
``step``, ``poses`` and ``observations`` (the numpy and JAX peers have them).
"""

from __future__ import annotations

from typing import Any, Protocol

import numpy as np

from .workload import F32


class Checked(Protocol):
    name: str

    def reset(self) -> None: ...
    def step(self) -> None: ...
    def poses(self) -> F32: ...
    def set_poses(self, poses: F32) -> None: ...
    def observations(self) -> F32: ...


def _gaps(a: Checked, b: Checked) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    pa, pb = np.asarray(a.poses(), np.float64), np.asarray(b.poses(), np.float64)
    position = np.hypot(pa[:, 0] - pb[:, 0], pa[:, 1] - pb[:, 1])
    heading = np.abs(np.angle(np.exp(1j * (pa[:, 2] - pb[:, 2]))))
    oa, ob = np.asarray(a.observations()), np.asarray(b.observations())
    width = min(oa.shape[1], ob.shape[1])
    readings = np.abs(oa[:, :width] - ob[:, :width]) / np.maximum(np.abs(ob[:, :width]), 1.0)
    return position, heading, readings


def step_agreement(a: Checked, b: Checked, poses: F32) -> dict[str, Any]:
    """Places both runners' robots at ``poses``, steps each once and compares: the largest
    position (m) and heading (rad) gap, and the largest relative reading gap, after the step."""
    a.set_poses(poses)
    b.set_poses(poses)
    a.step()
    b.step()
    position, heading, readings = _gaps(a, b)
    return {
        "poses": len(poses),
        "max_position_gap_m": float(position.max()),
        "max_heading_gap_rad": float(heading.max()),
        "max_relative_reading_gap": float(readings.max()),
    }


def trajectory_agreement(a: Checked, b: Checked, steps: int, tolerance: float) -> dict[str, Any]:
    """Resets both runners and steps them together for ``steps`` steps. Rounding differences grow
    where a robot grazes a wall, so a trajectory may part from the other's at some point; this
    reports the share of robots still within ``tolerance`` metres of their twin at the end, the
    first step at which any robot was farther, and the median gap at the end."""
    a.reset()
    b.reset()
    first_apart = None
    position = np.zeros(0)
    for k in range(steps):
        a.step()
        b.step()
        position, _, _ = _gaps(a, b)
        if first_apart is None and position.max() > tolerance:
            first_apart = k + 1
    return {
        "steps": steps,
        "tolerance_m": tolerance,
        "share_within_tolerance": float((position <= tolerance).mean()),
        "first_step_apart": first_apart,
        "median_final_gap_m": float(np.median(position)),
    }
