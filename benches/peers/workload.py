"""The canonical workload of docs/performance.md, as the hand-written peers need it.

Mazes come from ``mazesim.generate_maze`` (5 x 5 cells of 0.25 m, 0.01 m walls, a tenth of extra
openings, one distinct maze per environment); geometry and floor paint are read back from the
``World`` so that all runners step the very same mazes. The e-puck's geometry comes from its
profile; its lookup tables are those of docs/robots.md (Webots' E-puck PROTO).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

import mazesim

MAZE_CELLS = 5
CELL_SIZE = 0.25
WALL_THICKNESS = 0.01
LOOPS = 0.1
CONTROL_STEP = 0.032  # seconds: one control step = one physics step

# Infra-red distance sensors ps0-ps7: distance (m) -> raw value, relative noise sigma.
PS_TABLE = np.array(
    [
        [0.0, 4095.0, 0.002],
        [0.005, 2133.33, 0.003],
        [0.01, 1465.73, 0.007],
        [0.015, 601.46, 0.0406],
        [0.02, 383.84, 0.01472],
        [0.03, 234.93, 0.0241],
        [0.04, 158.03, 0.0287],
        [0.05, 120.0, 0.04225],
        [0.06, 104.09, 0.03065],
        [0.07, 67.19, 0.04897],
    ]
)
PS_RANGE = 0.07
# Ground sensors gs0-gs2 read LUT(GS_HEIGHT / f) of the floor reflectance f under them.
GS_TABLE = np.array([[0.0, 1000.0, 0.002], [0.016, 300.0, 0.004]])
GS_HEIGHT = 0.0033

F32 = npt.NDArray[np.float32]
F64 = npt.NDArray[np.float64]


def make_worlds(envs: int) -> list[mazesim.World]:
    """One distinct maze per environment: env i gets the maze of seed i."""
    return [
        mazesim.generate_maze(
            width=MAZE_CELLS,
            height=MAZE_CELLS,
            seed=i,
            loops=LOOPS,
            layout=mazesim.MazeLayout(cell_size=CELL_SIZE, wall_thickness=WALL_THICKNESS),
        )
        for i in range(envs)
    ]


@dataclass(frozen=True)
class Robot:
    """The e-puck as the peers model it."""

    body_radius: float
    wheel_radius: float
    axle_length: float
    max_wheel_speed: float
    ps_poses: F64  # (8, 3): x, y, heading in the robot frame
    gs_positions: F64  # (3, 2): x, y in the robot frame


def epuck() -> Robot:
    profile = mazesim.RobotProfile.builtin("e-puck")
    return Robot(
        body_radius=profile.body_radius,
        wheel_radius=profile.wheel_radius,
        axle_length=profile.axle_length,
        max_wheel_speed=profile.max_wheel_speed,
        ps_poses=np.asarray(profile.distance_sensor_poses(), dtype=np.float64),
        gs_positions=np.asarray(profile.ground_sensor_positions(), dtype=np.float64),
    )


def _quarter_turns(yaw: float) -> int:
    """The number of quarter turns in `yaw`; the peers handle axis-aligned rectangles only."""
    turns = round(yaw / (math.pi / 2))
    if abs(yaw - turns * math.pi / 2) > 1e-6:
        raise ValueError(f"rectangle at yaw {yaw} is not axis-aligned")
    return turns


@dataclass(frozen=True)
class Maze:
    """One maze as axis-aligned rectangles."""

    walls: F64  # (B, 4): xmin, xmax, ymin, ymax
    wall_reflectance: F64  # (B,)
    paint: F64  # (P, 4): xmin, xmax, ymin, ymax, in drawing order (the last one wins)
    paint_reflectance: F64  # (P,)
    floor_background: float
    start: tuple[float, float, float]
    bounds: tuple[float, float, float, float]  # xmin, ymin, xmax, ymax


def _aabbs(center: F64, size: F64, yaw: F64) -> F64:
    swap = np.array([_quarter_turns(float(a)) % 2 == 1 for a in yaw], dtype=bool)
    half = np.where(swap[:, None], size[:, ::-1], size) / 2.0
    return np.stack(
        [
            center[:, 0] - half[:, 0],
            center[:, 0] + half[:, 0],
            center[:, 1] - half[:, 1],
            center[:, 1] + half[:, 1],
        ],
        axis=1,
    )


def maze_of(world: mazesim.World) -> Maze:
    boxes = np.asarray(world.wall_boxes(), dtype=np.float64)
    walls = _aabbs(boxes[:, 0:2], boxes[:, 2:4], boxes[:, 4])
    regions = world.paint_regions()
    if any(r["shape"] != "rect" for r in regions):
        raise ValueError("the peers handle rectangular floor paint only")
    if regions:
        center = np.array([r["center"] for r in regions], dtype=np.float64)
        size = np.array([r["size"] for r in regions], dtype=np.float64)
        yaw = np.array([r["yaw"] for r in regions], dtype=np.float64)
        paint = _aabbs(center, size, yaw)
        paint_reflectance = np.array([r["reflectance"] for r in regions], dtype=np.float64)
    else:
        paint = np.zeros((0, 4))
        paint_reflectance = np.zeros(0)
    return Maze(
        walls=walls,
        wall_reflectance=boxes[:, 5].copy(),
        paint=paint,
        paint_reflectance=paint_reflectance,
        floor_background=float(world.floor_background),
        start=tuple(float(v) for v in world.start),  # type: ignore[arg-type]
        bounds=tuple(float(v) for v in world.bounds),  # type: ignore[arg-type]
    )


def lut(table: F64, x: npt.ArrayLike) -> tuple[F64, F64]:
    """Reference lookup: value and relative sigma at `x`, interpolated linearly, clamped."""
    return np.interp(x, table[:, 0], table[:, 1]), np.interp(x, table[:, 0], table[:, 2])


def braitenberg(ps: F32, left: F32, right: F32, a: F32) -> None:
    """The workload's wheel speeds from the raw ps0-ps7 readings `ps` (8, n), into `left` and
    `right` (n,); `a` is an (8, n) float32 scratch array.

    a_i = clip((ps_i - 67.19) / 300, 0, 1); right_side = a0 + 0.7 a1 + 0.4 a2;
    left_side = a7 + 0.7 a6 + 0.4 a5; front = 0.5 (a0 + a7); base = 5 (1 - front);
    turn = 4 (right_side - left_side) + 6 front; left = base - turn, right = base + turn,
    both clipped to +-6.28 rad/s.
    """
    np.subtract(ps, 67.19, out=a)
    np.divide(a, 300.0, out=a)
    np.clip(a, 0.0, 1.0, out=a)
    a0, a1, a2, a5, a6, a7 = a[0], a[1], a[2], a[5], a[6], a[7]
    s, t = a[3], a[4]  # ps3 and ps4 (rear) are not used: their rows serve as scratch
    np.subtract(a0, a7, out=s)
    np.subtract(a1, a6, out=t)
    t *= 0.7
    s += t
    np.subtract(a2, a5, out=t)
    t *= 0.4
    s += t  # right_side - left_side
    np.add(a0, a7, out=t)
    t *= 0.5  # front
    s *= 4.0
    np.multiply(t, 6.0, out=a0)
    s += a0  # turn
    np.subtract(1.0, t, out=t)
    t *= 5.0  # base
    np.subtract(t, s, out=left)
    np.add(t, s, out=right)
    np.clip(left, -6.28, 6.28, out=left)
    np.clip(right, -6.28, 6.28, out=right)


class Sanity:
    """Physical checks on poses (n, 3) of robots in `mazes`: the share inside their maze's outer
    walls, the deepest penetration of the body into a wall (metres, 0 if none) and the mean
    distance from the start."""

    def __init__(self, mazes: Sequence[Maze], radius: float) -> None:
        nb = max(len(m.walls) for m in mazes)
        self.walls = np.full((len(mazes), nb, 4), 1.0e6)  # padding: far away
        for k, m in enumerate(mazes):
            self.walls[k, : len(m.walls)] = m.walls
        self.bounds = np.array([m.bounds for m in mazes])
        self.start = np.array([m.start for m in mazes])
        self.radius = radius

    def __call__(self, poses: npt.ArrayLike) -> dict[str, float]:
        p = np.asarray(poses, dtype=np.float64)
        x, y = p[:, 0:1], p[:, 1:2]
        r = self.radius
        b = self.bounds
        inside = (
            (b[:, 0] + r <= p[:, 0])
            & (p[:, 0] <= b[:, 2] - r)
            & (b[:, 1] + r <= p[:, 1])
            & (p[:, 1] <= b[:, 3] - r)
        )
        w = self.walls
        qx = np.clip(x, w[:, :, 0], w[:, :, 1])
        qy = np.clip(y, w[:, :, 2], w[:, :, 3])
        gap = np.hypot(x - qx, y - qy).min(axis=1) - r
        moved = np.hypot(p[:, 0] - self.start[:, 0], p[:, 1] - self.start[:, 1])
        return {
            "inside_share": float(inside.mean()),
            "max_penetration_m": float(max(0.0, -gap.min())),
            "mean_distance_from_start_m": float(moved.mean()),
        }
