"""The canonical workload hand-built with pymunk (Chipmunk2D), as a Python user would write it.

One ``pymunk.Space`` per environment, seen from above (no gravity): every wall a static box
(``pymunk.Poly``), the e-puck a dynamic circle driven by setting its velocity from the wheel speeds
each step, then ``space.step(0.032)``. The 8 distance sensors are ``segment_query_first`` rays
that ignore the robot's own circle; the 3 ground sensors look the floor paint up in Python
(rectangles binned by maze cell, the last painted one wins). The per-environment work is a Python
loop, as it must be with one space per environment; the lookup tables and the noise are then
applied to all environments at once with numpy, which is the cheap part.

Scale: Chipmunk's default collision slop (0.1 length units) is 10 cm in metres, more than the
e-puck's radius, so the slop is set to a tenth of a millimetre.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import pymunk

from .workload import (
    CELL_SIZE,
    CONTROL_STEP,
    F32,
    GS_HEIGHT,
    GS_TABLE,
    PS_RANGE,
    PS_TABLE,
    Maze,
    Robot,
    braitenberg,
    lut,
)

WALLS = 0b01
ROBOT = 0b10
RAY_FILTER = pymunk.ShapeFilter(categories=0b100, mask=WALLS)
COLLISION_SLOP = 1e-4  # metres
ROBOT_MASS = 0.16  # kg


class _Env:
    """One maze in its own space with its robot, and its floor paint binned by cell."""

    def __init__(self, maze: Maze, robot: Robot) -> None:
        space = pymunk.Space()
        space.gravity = (0.0, 0.0)
        space.collision_slop = COLLISION_SLOP
        self.reflectance: dict[pymunk.Shape, float] = {}
        for (x0, x1, y0, y1), f in zip(maze.walls, maze.wall_reflectance):
            box = pymunk.Poly(space.static_body, [(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
            box.friction = 0.0
            box.elasticity = 0.0
            box.filter = pymunk.ShapeFilter(categories=WALLS)
            space.add(box)
            self.reflectance[box] = float(f)
        r = robot.body_radius
        body = pymunk.Body(ROBOT_MASS, pymunk.moment_for_circle(ROBOT_MASS, 0.0, r))
        disc = pymunk.Circle(body, r)
        disc.friction = 0.0
        disc.elasticity = 0.0
        disc.filter = pymunk.ShapeFilter(categories=ROBOT, mask=WALLS)
        space.add(body, disc)
        self.space = space
        self.body = body
        self.start = maze.start

        # Floor: per cell, the paint rectangles over it (drawing order reversed: first match wins),
        # each as (x0, x1, y0, y1, ground value, ground sigma).
        xmin, ymin, xmax, ymax = maze.bounds
        self.origin = (xmin, ymin)
        self.cols = max(1, math.ceil((xmax - xmin) / CELL_SIZE))
        self.rows = max(1, math.ceil((ymax - ymin) / CELL_SIZE))
        value, sigma = lut(GS_TABLE, GS_HEIGHT / maze.paint_reflectance)
        bg_value, bg_sigma = lut(GS_TABLE, GS_HEIGHT / maze.floor_background)
        self.background = (float(bg_value), float(bg_sigma))
        self.cells: list[list[tuple[float, float, float, float, float, float]]] = [
            [] for _ in range(self.cols * self.rows)
        ]
        for k in range(len(maze.paint) - 1, -1, -1):
            x0, x1, y0, y1 = (float(v) for v in maze.paint[k])
            rect = (x0, x1, y0, y1, float(value[k]), float(sigma[k]))
            for j in range(self._row(y0), self._row(y1) + 1):
                for i in range(self._col(x0), self._col(x1) + 1):
                    self.cells[j * self.cols + i].append(rect)

    def _col(self, x: float) -> int:
        return min(self.cols - 1, max(0, int((x - self.origin[0]) / CELL_SIZE)))

    def _row(self, y: float) -> int:
        return min(self.rows - 1, max(0, int((y - self.origin[1]) / CELL_SIZE)))

    def floor(self, x: float, y: float) -> tuple[float, float]:
        """Ground sensor value and sigma at (x, y)."""
        for x0, x1, y0, y1, value, sigma in self.cells[self._row(y) * self.cols + self._col(x)]:
            if x0 <= x <= x1 and y0 <= y <= y1:
                return value, sigma
        return self.background

    def place(self, x: float, y: float, yaw: float) -> None:
        self.body.position = (x, y)
        self.body.angle = yaw
        self.body.velocity = (0.0, 0.0)
        self.body.angular_velocity = 0.0
        self.space.reindex_shapes_for_body(self.body)


class PymunkPeer:
    """N environments, each its own pymunk space, stepped one after the other."""

    name = "pymunk"
    steps_per_call = 1

    def __init__(
        self, mazes: Sequence[Maze], robot: Robot, seed: int = 0, noise: bool = True
    ) -> None:
        self.envs = [_Env(m, robot) for m in mazes]
        self.robot = robot
        self.noise = noise
        self.rng = np.random.default_rng(seed)
        n = len(self.envs)
        self.obs = np.zeros((11, n), np.float32)  # rows: ps0-ps7, gs0-gs2
        self.left = np.zeros(n, np.float32)
        self.right = np.zeros(n, np.float32)
        self.scratch = np.zeros((8, n), np.float32)
        self.gauss = np.zeros((11, n), np.float32)
        self.rays = [(float(x), float(y), math.cos(h), math.sin(h)) for x, y, h in robot.ps_poses]
        self.ground = [(float(x), float(y)) for x, y in robot.gs_positions]

    def reset(self) -> None:
        for env in self.envs:
            env.place(*env.start)
        self._sense()

    def step(self) -> None:
        braitenberg(self.obs[:8], self.left, self.right, self.scratch)
        half_r = self.robot.wheel_radius / 2.0
        turn = self.robot.wheel_radius / self.robot.axle_length
        for env, wl, wr in zip(self.envs, self.left.tolist(), self.right.tolist()):
            body = env.body
            v = (wl + wr) * half_r
            a = body.angle
            body.velocity = (math.cos(a) * v, math.sin(a) * v)
            body.angular_velocity = (wr - wl) * turn
            env.space.step(CONTROL_STEP)
        self._sense()

    def _sense(self) -> None:
        rays, ground, reach = self.rays, self.ground, PS_RANGE
        dist: list[float] = []
        gval: list[float] = []
        gsig: list[float] = []
        for env in self.envs:
            body, space, refl = env.body, env.space, env.reflectance
            x, y = body.position
            a = body.angle
            c, s = math.cos(a), math.sin(a)
            for sx, sy, hc, hs in rays:
                ox = x + c * sx - s * sy
                oy = y + s * sx + c * sy
                dx = c * hc - s * hs
                dy = s * hc + c * hs
                hit = space.segment_query_first(
                    (ox, oy), (ox + dx * reach, oy + dy * reach), 0.0, RAY_FILTER
                )
                dist.append(reach if hit is None else hit.alpha * reach / refl[hit.shape])
            for gx, gy in ground:
                value, sigma = env.floor(x + c * gx - s * gy, y + s * gx + c * gy)
                gval.append(value)
                gsig.append(sigma)
        n = len(self.envs)
        d = np.array(dist, dtype=np.float32).reshape(n, 8).T
        ps, ps_sigma = lut(PS_TABLE, d)
        gs = np.array(gval, dtype=np.float32).reshape(n, 3).T
        gs_sigma = np.array(gsig, dtype=np.float32).reshape(n, 3).T
        if self.noise:
            self.rng.standard_normal(dtype=np.float32, out=self.gauss)
            ps = ps * (1.0 + ps_sigma * self.gauss[:8])
            gs = gs * (1.0 + gs_sigma * self.gauss[8:])
        np.maximum(ps, 0.0, out=self.obs[:8], casting="unsafe")
        np.maximum(gs, 0.0, out=self.obs[8:])

    def set_poses(self, poses: F32) -> None:
        """Places the robots at `poses` (N, 3) and reads the sensors there (for checks)."""
        for env, (x, y, yaw) in zip(self.envs, np.asarray(poses, dtype=np.float64)):
            env.place(x, y, yaw)
        self._sense()

    def observations(self) -> F32:
        return self.obs.T

    def poses(self) -> F32:
        return np.array(
            [(*env.body.position, env.body.angle) for env in self.envs], dtype=np.float32
        )
