"""The canonical workload in jax.numpy: one env's step written once, jitted, vmapped over the
envs and run ``steps_per_call`` steps at a time by ``lax.scan``, as a gymnax, jumanji or Kinetix
user would write it.

The model is the numpy peer's (``peers.numpy_peer``), so the two can be checked against each other
step for step: the Braitenberg rule on the last readings, the differential drive integrated over
32 ms, wall contacts resolved by pushing the disc out of the boxes it overlaps (per axis the
largest push each way), the 8 rays slab-tested against every box of the env's maze and read
through the lookup table with relative Gaussian noise, the 3 ground sensors point-tested against
the floor paint (the last painted region wins). float32 throughout (JAX's default).

``ground=False`` and ``noise=False`` leave out the ground sensors and the noise: the leaner env a
JAX user may write first (``jax-lean`` in bench_vs_peers.py).

Calls are dispatched asynchronously, as JAX does; :meth:`JaxPeer.sync` waits for the last one, and
the timers call it at the end of each timed round, so JAX may overlap its Python dispatch with
its computation, in its favour.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import jax
import jax.numpy as jnp
import numpy as np

from .workload import CONTROL_STEP, F32, GS_HEIGHT, GS_TABLE, PS_RANGE, PS_TABLE, Maze, Robot, lut

_FAR = 1.0e6  # padding boxes sit out here, degenerate
_MAX_INV = 1.0e30


def _pad(rows: Sequence[np.ndarray], width: int, fill: float) -> np.ndarray:
    out = np.full((len(rows), width, *rows[0].shape[1:]), fill)
    for k, r in enumerate(rows):
        out[k, : len(r)] = r
    return out


def _braitenberg(ps: jax.Array) -> tuple[jax.Array, jax.Array]:
    """The workload's rule (``peers.workload.braitenberg``) on one env's ps0-ps7."""
    a = jnp.clip((ps - 67.19) / 300.0, 0.0, 1.0)
    right_side = a[0] + 0.7 * a[1] + 0.4 * a[2]
    left_side = a[7] + 0.7 * a[6] + 0.4 * a[5]
    front = 0.5 * (a[0] + a[7])
    base = 5.0 * (1.0 - front)
    turn = 4.0 * (right_side - left_side) + 6.0 * front
    return jnp.clip(base - turn, -6.28, 6.28), jnp.clip(base + turn, -6.28, 6.28)


class _Model:
    """One env's step, as pure functions of its state and its maze's arrays."""

    def __init__(self, robot: Robot, noise: bool, ground: bool) -> None:
        self.radius = float(robot.body_radius)
        self.forward = robot.wheel_radius / 2.0 * CONTROL_STEP
        self.turn = robot.wheel_radius / robot.axle_length * CONTROL_STEP
        ps = robot.ps_poses
        self.ps_x, self.ps_y = (
            jnp.asarray(ps[:, 0], jnp.float32),
            jnp.asarray(ps[:, 1], jnp.float32),
        )
        self.ps_cos = jnp.asarray(np.cos(ps[:, 2]), jnp.float32)
        self.ps_sin = jnp.asarray(np.sin(ps[:, 2]), jnp.float32)
        gs = robot.gs_positions
        self.gs_x, self.gs_y = (
            jnp.asarray(gs[:, 0], jnp.float32),
            jnp.asarray(gs[:, 1], jnp.float32),
        )
        self.ps_table = jnp.asarray(PS_TABLE, jnp.float32)
        self.noise = noise
        self.ground = ground

    def contacts(
        self, x: jax.Array, y: jax.Array, walls: jax.Array
    ) -> tuple[jax.Array, jax.Array, jax.Array]:
        """Pushes the disc at (x, y) out of the boxes it overlaps; walls (B, 4)."""
        qx = x - jnp.clip(x, walls[:, 0], walls[:, 1])
        qy = y - jnp.clip(y, walls[:, 2], walls[:, 3])
        d2 = qx * qx + qy * qy
        colliding = jnp.min(d2) < self.radius * self.radius
        factor = jnp.maximum(self.radius / jnp.sqrt(jnp.maximum(d2, 1e-12)) - 1.0, 0.0)
        qx, qy = qx * factor, qy * factor
        return x + jnp.max(qx) + jnp.min(qx), y + jnp.max(qy) + jnp.min(qy), colliding

    def sense(self, pose: jax.Array, maze: dict[str, jax.Array], gauss: jax.Array) -> jax.Array:
        """ps0-ps7 (and gs0-gs2 with ``ground``) at ``pose``; ``gauss`` holds the normal draws."""
        x, y, th = pose[0], pose[1], pose[2]
        c, s = jnp.cos(th), jnp.sin(th)
        ox = x + c * self.ps_x - s * self.ps_y
        oy = y + s * self.ps_x + c * self.ps_y
        inv_dx = jnp.clip(1.0 / (c * self.ps_cos - s * self.ps_sin), -_MAX_INV, _MAX_INV)
        inv_dy = jnp.clip(1.0 / (s * self.ps_cos + c * self.ps_sin), -_MAX_INV, _MAX_INV)
        walls = maze["walls"]  # (B, 4) -> slab test as (B, 8)
        t1 = (walls[:, 0:1] - ox) * inv_dx
        t2 = (walls[:, 1:2] - ox) * inv_dx
        t3 = (walls[:, 2:3] - oy) * inv_dy
        t4 = (walls[:, 3:4] - oy) * inv_dy
        entry = jnp.maximum(jnp.maximum(jnp.minimum(t1, t2), jnp.minimum(t3, t4)), 0.0)
        leave = jnp.minimum(jnp.maximum(t1, t2), jnp.maximum(t3, t4))
        hit = jnp.where(entry <= leave, entry, jnp.inf)
        dist = jnp.minimum(jnp.min(hit, axis=0), PS_RANGE) * maze["inv_refl"]
        table = self.ps_table
        ps = jnp.interp(dist, table[:, 0], table[:, 1])
        if self.noise:
            sigma = jnp.interp(dist, table[:, 0], table[:, 2])
            ps = jnp.maximum(ps * (1.0 + sigma * gauss[:8]), 0.0)
        if not self.ground:
            return ps
        gx = x + c * self.gs_x - s * self.gs_y
        gy = y + s * self.gs_x + c * self.gs_y
        paint = maze["paint"]  # (P, 4) -> point test as (P, 3)
        inside = (
            (gx >= paint[:, 0:1])
            & (gx <= paint[:, 1:2])
            & (gy >= paint[:, 2:3])
            & (gy <= paint[:, 3:4])
        )
        layer = jnp.arange(1, paint.shape[0] + 1)[:, None]
        top = jnp.max(jnp.where(inside, layer, 0), axis=0)  # 0: bare floor
        gs = maze["ground_value"][top]
        if self.noise:
            gs = jnp.maximum(gs * (1.0 + maze["ground_sigma"][top] * gauss[8:]), 0.0)
        return jnp.concatenate([ps, gs])

    def step(
        self, pose: jax.Array, obs: jax.Array, maze: dict[str, jax.Array], gauss: jax.Array
    ) -> tuple[jax.Array, jax.Array, jax.Array]:
        """One control step of one env: (pose, observations, colliding) after it."""
        wl, wr = _braitenberg(obs[:8])
        v = (wl + wr) * self.forward
        th = pose[2]
        x = pose[0] + jnp.cos(th) * v
        y = pose[1] + jnp.sin(th) * v
        th = jnp.remainder(th + (wr - wl) * self.turn + math.pi, 2.0 * math.pi) - math.pi
        x, y, colliding = self.contacts(x, y, maze["walls"])
        pose = jnp.stack([x, y, th])
        return pose, self.sense(pose, maze, gauss), colliding


class JaxPeer:
    """N environments as JAX arrays: ``step()`` runs ``steps_per_call`` control steps of all of
    them in one jitted call (vmap over envs inside ``lax.scan`` over steps)."""

    def __init__(
        self,
        mazes: Sequence[Maze],
        robot: Robot,
        seed: int = 0,
        noise: bool = True,
        steps_per_call: int = 1,
        ground: bool = True,
    ) -> None:
        self.name = "jax" if ground and noise else "jax-lean"
        self.steps_per_call = steps_per_call
        self.model = _Model(robot, noise, ground)
        self.width = 11 if ground else 8
        refl = []
        for m in mazes:
            if not np.all(m.wall_reflectance == m.wall_reflectance[0]):
                raise ValueError("the JAX peer expects one wall reflectance per maze")
            refl.append(m.wall_reflectance[0])
        npaint = max(1, max(len(m.paint) for m in mazes))
        background = np.array([m.floor_background for m in mazes])[:, None]
        paint_refl = _pad([m.paint_reflectance for m in mazes], npaint, 1.0)
        ground_value, ground_sigma = lut(
            GS_TABLE, GS_HEIGHT / np.concatenate([background, paint_refl], axis=1)
        )
        nb = max(len(m.walls) for m in mazes)
        self.mazes = {
            "walls": jnp.asarray(_pad([m.walls for m in mazes], nb, _FAR), jnp.float32),
            "inv_refl": jnp.asarray(1.0 / np.array(refl), jnp.float32),
            "paint": jnp.asarray(_pad([m.paint for m in mazes], npaint, _FAR), jnp.float32),
            "ground_value": jnp.asarray(ground_value, jnp.float32),
            "ground_sigma": jnp.asarray(ground_sigma, jnp.float32),
        }
        self.start = jnp.asarray([m.start for m in mazes], jnp.float32)
        self.n = len(mazes)
        self.key = jax.random.PRNGKey(seed)
        self.pose = self.start
        self.obs = jnp.zeros((self.n, self.width), jnp.float32)
        self.colliding = jnp.zeros(self.n, bool)
        self._run = jax.jit(self._steps, static_argnums=4)
        self._sense = jax.jit(self._sense_all)

    def _gauss(self, key: jax.Array) -> jax.Array:
        return jax.random.normal(key, (self.n, 11), jnp.float32)

    def _sense_all(self, pose: jax.Array, key: jax.Array) -> jax.Array:
        return jax.vmap(self.model.sense)(pose, self.mazes, self._gauss(key))

    def _steps(
        self, pose: jax.Array, obs: jax.Array, colliding: jax.Array, key: jax.Array, steps: int
    ) -> tuple[Any, ...]:
        step_all = jax.vmap(self.model.step)

        def one(carry: tuple[Any, ...], _: None) -> tuple[tuple[Any, ...], None]:
            pose, obs, _colliding, key = carry
            key, draw = jax.random.split(key)
            pose, obs, colliding = step_all(pose, obs, self.mazes, self._gauss(draw))
            return (pose, obs, colliding, key), None

        carry, _ = jax.lax.scan(one, (pose, obs, colliding, key), None, length=steps)
        return tuple(carry)

    def reset(self) -> None:
        self.key, draw = jax.random.split(self.key)
        self.pose = self.start
        self.obs = self._sense(self.pose, draw)
        self.colliding = jnp.zeros(self.n, bool)

    def step(self) -> None:
        """``steps_per_call`` control steps of every env, dispatched without waiting."""
        self.pose, self.obs, self.colliding, self.key = self._run(
            self.pose, self.obs, self.colliding, self.key, self.steps_per_call
        )

    def sync(self) -> None:
        """Waits for the steps dispatched so far."""
        self.obs.block_until_ready()

    def set_poses(self, poses: F32) -> None:
        """Places the robots at `poses` (N, 3) and reads the sensors there (for checks)."""
        self.pose = jnp.asarray(poses, jnp.float32)
        self.key, draw = jax.random.split(self.key)
        self.obs = self._sense(self.pose, draw)

    def observations(self) -> F32:
        return np.asarray(self.obs)

    def poses(self) -> F32:
        return np.asarray(self.pose)

    def contacts(self) -> np.ndarray:
        return np.asarray(self.colliding)
