"""The canonical workload as a tuned, kinematic simulator in plain vectorised numpy.

What a careful numpy user would write: float32 throughout, every array preallocated and every
operation in place, no Python loop over environments. Environments are worked in chunks whose
working set stays in the core's cache, with the environment as the innermost (contiguous) axis so
that each operation runs over long vectors: a chunk's walls are (B, C) arrays, its rays (8, C),
the ray-box slab test (B, 8, C). One control step of a chunk:

- the Braitenberg rule on the last readings gives the wheel speeds;
- the differential drive is integrated (Euler, 32 ms);
- wall contacts are resolved by pushing the disc out of every wall box it overlaps (per axis the
  largest push, so two walls meeting at a corner are handled and collinear boxes are not counted
  twice);
- the 8 rays are cast against all the env's boxes with a slab test, read through the lookup table
  (resampled on a uniform grid, which is exact for this table) with relative Gaussian noise;
- the 3 ground sensors are point-tested against the floor paint rectangles (the last painted one
  wins), their reading per rectangle precomputed.

Simplifications, all in the peer's favour: kinematic contacts instead of a rigid-body solver, a
point sample for the ground sensors (mazesim averages a 3 mm spot), one wall reflectance per maze
(true of generated mazes; checked), no barcode-crossing detection.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from .workload import (
    CONTROL_STEP,
    F32,
    F64,
    GS_HEIGHT,
    GS_TABLE,
    PS_RANGE,
    PS_TABLE,
    Maze,
    Robot,
    braitenberg,
    lut,
)

_FAR = np.float32(1.0e6)  # padding rectangles sit out here, degenerate
_BIG = np.float32(1.0e9)
_MAX_INV = np.float32(1.0e30)


def _rotate(
    c: np.ndarray,
    s: np.ndarray,
    px: np.ndarray,
    py: np.ndarray,
    out_x: np.ndarray,
    out_y: np.ndarray,
    scratch: np.ndarray,
    at: tuple[np.ndarray, np.ndarray] | None = None,
) -> None:
    """Writes the robot-frame vectors (``px``, ``py``) turned by the heading of cosine ``c`` and
    sine ``s`` into ``out_x``, ``out_y``, moved to the robot's position ``at`` when given (points
    rather than directions); ``scratch`` is a buffer of their shape."""
    np.multiply(c, px, out=out_x)
    np.multiply(s, py, out=scratch)
    out_x -= scratch
    if at is not None:
        out_x += at[0]
    np.multiply(s, px, out=out_y)
    np.multiply(c, py, out=scratch)
    out_y += scratch
    if at is not None:
        out_y += at[1]


def _slab(
    low: np.ndarray,
    high: np.ndarray,
    origin: np.ndarray,
    inverse: np.ndarray,
    near: np.ndarray,
    far: np.ndarray,
    entry: np.ndarray,
) -> None:
    """The distances along rays of inverse direction ``inverse`` (one axis) at which they enter
    the boxes' slabs ``[low, high]`` of that axis, into ``entry``, and leave them, into ``near``;
    ``far`` is a buffer of their shape."""
    np.subtract(low, origin, out=near)
    near *= inverse
    np.subtract(high, origin, out=far)
    far *= inverse
    np.minimum(near, far, out=entry)
    np.maximum(near, far, out=near)


class UniformLut:
    """A piecewise-linear table resampled exactly on a uniform grid (its breakpoints must lie on
    the grid): one multiply, one truncation and two small gathers per column read."""

    def __init__(self, table: F64, step: float) -> None:
        x = table[:, 0]
        cells = round((x[-1] - x[0]) / step)
        if not np.allclose(np.round((x - x[0]) / step), (x - x[0]) / step, atol=1e-9):
            raise ValueError("table breakpoints are not on the grid")
        grid = x[0] + step * np.arange(cells + 1)
        value, sigma = lut(table, grid)
        self.x0 = np.float32(x[0])
        self.inv_step = np.float32(1.0 / step)
        self.top = np.float32(cells)
        # value = intercept[i] + slope[i] * u with u = (x - x0) / step clamped to [0, cells] and
        # i = floor(u); row `cells` has slope 0, so the clamped ends read the first and last rows.
        i = np.arange(cells + 1)
        slope = np.append(np.diff(value), 0.0)
        self.v_intercept = (value - slope * i).astype(np.float32)
        self.v_slope = slope.astype(np.float32)
        sslope = np.append(np.diff(sigma), 0.0)
        self.s_intercept = (sigma - sslope * i).astype(np.float32)
        self.s_slope = sslope.astype(np.float32)

    def __call__(self, x: F32, value: F32, sigma: F32, u: F32, i: np.ndarray) -> None:
        """value, sigma <- table(x); u (float32) and i (intp) are scratch of x's shape."""
        np.subtract(x, self.x0, out=u)
        u *= self.inv_step
        np.clip(u, 0.0, self.top, out=u)
        np.copyto(i, u, casting="unsafe")  # truncation = floor for u >= 0
        np.take(self.v_slope, i, out=value, mode="clip")
        value *= u
        np.take(self.v_intercept, i, out=sigma, mode="clip")
        value += sigma
        np.take(self.s_slope, i, out=sigma, mode="clip")
        sigma *= u
        np.take(self.s_intercept, i, out=u, mode="clip")
        sigma += u


def _spread(a: np.ndarray, k: int) -> np.ndarray:
    """(n, C) -> contiguous (n, k, C), row i repeated k times."""
    return np.ascontiguousarray(np.broadcast_to(a[:, None, :], (a.shape[0], k, a.shape[1])))


def _pad(rows: Sequence[F64], width: int, fill: float) -> F64:
    out = np.full((len(rows), width), fill)
    for k, r in enumerate(rows):
        out[k, : len(r)] = r
    return out


class _Chunk:
    """C environments stepped together; all arrays have the environment as their last axis."""

    def __init__(
        self,
        mazes: Sequence[Maze],
        robot: Robot,
        ps_lut: UniformLut,
        seed: int,
        obs: F32,
        pose: F32,
        colliding: np.ndarray,
    ) -> None:
        c = len(mazes)
        self.c = c
        self.robot = robot
        self.ps_lut = ps_lut
        self.rng = np.random.default_rng(seed)
        f32 = np.float32

        # Walls: (B, C) bounds; padding boxes are degenerate points far away.
        nb = max(len(m.walls) for m in mazes)
        bounds = np.stack([_pad([m.walls[:, k] for m in mazes], nb, _FAR).T for k in range(4)])
        self.bx0, self.bx1, self.by0, self.by1 = (b.astype(f32) for b in bounds)
        # The slab test's copies, one per ray: (B, 8, C) against rays (8, C). Broadcasting a
        # (B, 1, C) array against (8, C) instead would cost numpy an inner loop per (box, ray).
        self.sx0, self.sx1, self.sy0, self.sy1 = (
            _spread(b, 8) for b in (self.bx0, self.bx1, self.by0, self.by1)
        )
        refl = []
        for m in mazes:
            if not np.all(m.wall_reflectance == m.wall_reflectance[0]):
                raise ValueError("the numpy peer expects one wall reflectance per maze")
            refl.append(m.wall_reflectance[0])
        self.inv_refl = (1.0 / np.array(refl)).astype(f32)

        # Floor paint: (P, 3, C) bounds against ground points (3, C); index 0 = background.
        npaint = max(1, max(len(m.paint) for m in mazes))
        if npaint >= 255:
            raise ValueError("too many paint regions for a uint8 index")
        pb = np.stack([_pad([m.paint[:, k] for m in mazes], npaint, _FAR).T for k in range(4)])
        self.px0, self.px1, self.py0, self.py1 = (_spread(b.astype(f32), 3) for b in pb)
        reflectance = np.empty((npaint + 1, c))
        reflectance[0] = [m.floor_background for m in mazes]
        reflectance[1:] = _pad([m.paint_reflectance for m in mazes], npaint, 1.0).T
        gv, gs = lut(GS_TABLE, GS_HEIGHT / reflectance)
        # Flat (P + 1) x C tables, gathered at index * C + env.
        self.g_value = gv.astype(f32).ravel()
        self.g_sigma = gs.astype(f32).ravel()
        self.priority = _spread(
            np.repeat(np.arange(1, npaint + 1, dtype=np.uint8)[:, None], c, axis=1), 3
        )
        self.column = np.arange(c, dtype=np.intp)

        self.start = np.array([m.start for m in mazes], dtype=f32).T.copy()  # (3, C)

        # Robot constants as (k, C) arrays, for the same reason.
        ps, gs = robot.ps_poses, robot.gs_positions
        self.ps_x, self.ps_y, self.ps_cos, self.ps_sin = (
            np.repeat(col[:, None], c, axis=1).astype(f32)
            for col in (ps[:, 0], ps[:, 1], np.cos(ps[:, 2]), np.sin(ps[:, 2]))
        )
        self.gs_x, self.gs_y = (
            np.repeat(col[:, None], c, axis=1).astype(f32) for col in (gs[:, 0], gs[:, 1])
        )

        # State and outputs: this chunk's columns of the peer's arrays.
        self.obs, self.pose, self.colliding = obs, pose, colliding
        self.noise = np.zeros((11, c), f32)
        # Scratch.
        e = lambda *shape: np.empty(shape, f32)  # noqa: E731
        self.wl, self.wr, self.v, self.w, self.cos, self.sin, self.t = (e(c) for _ in range(7))
        self.ctrl = e(8, c)
        self.qx, self.qy, self.d2, self.qt = (e(nb, c) for _ in range(4))
        self.ox, self.oy, self.dx, self.dy, self.r8 = (e(8, c) for _ in range(5))
        self.dist = e(8, c)
        self.lut_u = e(8, c)
        self.lut_i = np.empty((8, c), np.intp)
        self.t1, self.t2, self.t3, self.t4, self.t5 = (e(nb, 8, c) for _ in range(5))
        self.zero = np.zeros((nb, 8, c), f32)  # numpy's maximum against a scalar is slow
        self.gx, self.gy = e(3, c), e(3, c)
        self.inside = np.empty((npaint, 3, c), bool)
        self.inside2 = np.empty((npaint, 3, c), bool)
        self.layer = np.empty((npaint, 3, c), np.uint8)
        self.top = np.empty((3, c), np.uint8)
        self.gidx = np.empty((3, c), np.intp)
        self.g3 = e(3, c)

    # -- one control step -------------------------------------------------------------------

    def reset(self, noise: bool) -> None:
        self.pose[...] = self.start
        self.colliding[...] = False
        self._sense(noise)

    def step(self, noise: bool) -> None:
        r = self.robot
        x, y, th = self.pose
        braitenberg(self.obs[:8], self.wl, self.wr, self.ctrl)
        # Differential drive, integrated with the heading at the start of the step.
        v, w, t = self.v, self.w, self.t
        np.add(self.wl, self.wr, out=v)
        v *= r.wheel_radius / 2.0 * CONTROL_STEP  # forward displacement
        np.subtract(self.wr, self.wl, out=w)
        w *= r.wheel_radius / r.axle_length * CONTROL_STEP  # turn
        np.cos(th, out=self.cos)
        np.sin(th, out=self.sin)
        np.multiply(self.cos, v, out=t)
        x += t
        np.multiply(self.sin, v, out=t)
        y += t
        th += w
        th += math.pi
        np.remainder(th, 2.0 * math.pi, out=th)
        th -= math.pi
        self._contacts()
        self._sense(noise)

    def _contacts(self) -> None:
        """Pushes each disc out of the boxes it overlaps."""
        radius = np.float32(self.robot.body_radius)
        x, y = self.pose[0], self.pose[1]
        qx, qy, d2 = self.qx, self.qy, self.d2
        np.maximum(x, self.bx0, out=qx)  # closest point of each box (np.clip is slower)
        np.minimum(qx, self.bx1, out=qx)
        np.maximum(y, self.by0, out=qy)
        np.minimum(qy, self.by1, out=qy)
        np.subtract(x, qx, out=qx)  # from it to the centre
        np.subtract(y, qy, out=qy)
        np.multiply(qx, qx, out=d2)
        np.multiply(qy, qy, out=self.qt)
        d2 += self.qt
        np.less(d2.min(axis=0), radius * radius, out=self.colliding)
        if not self.colliding.any():
            return
        # factor = max(r / |d| - 1, 0): the push along (dx, dy) that brings |d| to r.
        np.maximum(d2, np.float32(1e-12), out=d2)
        np.sqrt(d2, out=d2)
        np.divide(radius, d2, out=d2)
        d2 -= 1.0
        np.maximum(d2, 0.0, out=d2)
        qx *= d2
        qy *= d2
        x += qx.max(axis=0)
        x += qx.min(axis=0)
        y += qy.max(axis=0)
        y += qy.min(axis=0)

    def _sense(self, noise: bool) -> None:
        x, y = self.pose[0], self.pose[1]
        th = self.pose[2]
        c, s = self.cos, self.sin
        np.cos(th, out=c)
        np.sin(th, out=s)
        ox, oy, dx, dy, r8 = self.ox, self.oy, self.dx, self.dy, self.r8
        if noise:
            self.rng.standard_normal(dtype=np.float32, out=self.noise)
        # Ray origins and directions in the world frame.
        _rotate(c, s, self.ps_x, self.ps_y, ox, oy, r8, at=(x, y))
        _rotate(c, s, self.ps_cos, self.ps_sin, dx, dy, r8)
        np.divide(1.0, dx, out=dx)  # inverse directions, finite
        np.clip(dx, -_MAX_INV, _MAX_INV, out=dx)
        np.divide(1.0, dy, out=dy)
        np.clip(dy, -_MAX_INV, _MAX_INV, out=dy)
        # Slab test of every ray against every box: (B, 8, C) entry and exit distances.
        t1, t2, t3, t4, t5 = self.t1, self.t2, self.t3, self.t4, self.t5
        _slab(self.sx0, self.sx1, ox, dx, t1, t2, t3)  # x entry t3, exit t1
        _slab(self.sy0, self.sy1, oy, dy, t2, t4, t5)  # y entry t5, exit t2
        np.maximum(t3, t5, out=t3)  # entry
        np.minimum(t1, t2, out=t1)  # exit
        np.maximum(t3, self.zero, out=t3)  # the ray starts at its origin (0 inside a box)
        # A miss (exit before entry) is pushed out of range: entry += max(entry - exit, 0) * BIG.
        # (numpy's masked assignment is several times slower than these four passes.)
        np.subtract(t3, t1, out=t1)
        np.maximum(t1, self.zero, out=t1)
        t1 *= _BIG
        t3 += t1
        # Nearest hit per ray, as seen through the wall's reflection factor; no hit reads the range.
        dist = self.dist
        np.min(t3, axis=0, out=dist)
        np.minimum(dist, PS_RANGE, out=dist)
        dist *= self.inv_refl
        ps, sigma = self.obs[:8], r8
        self.ps_lut(dist, ps, sigma, self.lut_u, self.lut_i)
        if noise:
            sigma *= self.noise[:8]
            sigma += 1.0
            ps *= sigma
            np.maximum(ps, 0.0, out=ps)
        self._ground(noise)

    def _ground(self, noise: bool) -> None:
        x, y = self.pose[0], self.pose[1]
        c, s = self.cos, self.sin
        gx, gy, g3 = self.gx, self.gy, self.g3
        _rotate(c, s, self.gs_x, self.gs_y, gx, gy, g3, at=(x, y))
        inside, other = self.inside, self.inside2
        np.greater_equal(gx, self.px0, out=inside)
        np.less_equal(gx, self.px1, out=other)
        inside &= other
        np.greater_equal(gy, self.py0, out=other)
        inside &= other
        np.less_equal(gy, self.py1, out=other)
        inside &= other
        np.multiply(inside, self.priority, out=self.layer)  # the last painted region wins
        np.max(self.layer, axis=0, out=self.top)
        idx = self.gidx
        np.copyto(idx, self.top)
        idx *= self.c
        idx += self.column
        gs = self.obs[8:]
        np.take(self.g_value, idx, out=gs, mode="clip")
        if noise:
            np.take(self.g_sigma, idx, out=g3, mode="clip")
            g3 *= self.noise[8:]
            g3 += 1.0
            gs *= g3
            np.maximum(gs, 0.0, out=gs)


class NumpyPeer:
    """N environments in chunks of `chunk`. Observations (11, N: ps0-ps7, gs0-gs2), poses
    (3, N: x, y, yaw) and contact flags (N,) live in arrays the chunks write in place."""

    name = "numpy"
    steps_per_call = 1

    def __init__(
        self,
        mazes: Sequence[Maze],
        robot: Robot,
        chunk: int = 256,
        seed: int = 0,
        noise: bool = True,
    ) -> None:
        self.noise = noise
        n = len(mazes)
        self.obs = np.zeros((11, n), np.float32)
        self.pose = np.zeros((3, n), np.float32)
        self.colliding = np.zeros(n, np.bool_)
        ps_lut = UniformLut(PS_TABLE, 0.005)
        self.chunks = [
            _Chunk(
                mazes[i : i + chunk],
                robot,
                ps_lut,
                seed + i,
                self.obs[:, i : i + chunk],
                self.pose[:, i : i + chunk],
                self.colliding[i : i + chunk],
            )
            for i in range(0, n, chunk)
        ]

    def reset(self) -> None:
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            for ch in self.chunks:
                ch.reset(self.noise)

    def step(self) -> None:
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            for ch in self.chunks:
                ch.step(self.noise)

    def set_poses(self, poses: F32) -> None:
        """Places the robots at `poses` (N, 3) and reads the sensors there (for checks)."""
        at = 0
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            for ch in self.chunks:
                ch.pose[...] = poses[at : at + ch.c].T
                ch._sense(self.noise)
                at += ch.c

    def observations(self) -> F32:
        return self.obs.T

    def poses(self) -> F32:
        return self.pose.T
