"""Navigation episodes: N robots driving from a maze's start to its goal, in one batch.

A :class:`NavigationBatch` runs one episode per robot at a time on the ``seed`` robot, with sensor
noise and a small random jitter of the start pose (:class:`StartJitter`: up to 2 cm along each
axis and 10 degrees of heading, uniformly), and says when a robot reached the goal disc or ran out
of time. Episode ``k`` draws its jitter and its noise seed from ``(seed, k)`` alone, so a result
does not depend on how many robots run side by side.

Checkpoint events come from the simulator's ground truth of barcode crossings, or, with
``events="robust"``, from :class:`mazesim.barcode.RobustDecoder` reading each robot's ground
sensor (with wheel encoders integrated from the actions); both give ``+id`` for an arrival,
``-id`` for a departure and 0 for nothing.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from mazesim._core import BatchSimulator, RobotProfile, World
from mazesim.actions import WHEEL_SPEED_FRACTIONS
from mazesim.errors import InvalidArgumentError
from mazesim.hrl.mazes import CellMaze, world_with_start
from mazesim.hrl.subtasks import CONTROL_STEP_MS, cruise_step_length

__all__ = [
    "EVENT_SOURCES",
    "NavigationBatch",
    "StartJitter",
    "shortest_path_steps",
]

#: Where checkpoint events come from.
EVENT_SOURCES = ("truth", "robust")
#: Control steps an episode may last by default (about 4 minutes at 64 ms).
DEFAULT_MAX_STEPS = 4000


@dataclass(frozen=True)
class StartJitter:
    """Uniform jitter of the start pose: up to ``position`` metres along x and y and ``yaw``
    radians of heading, either way."""

    position: float = 0.02
    yaw: float = math.radians(10.0)


def shortest_path_steps(world: World, control_step_ms: float = CONTROL_STEP_MS) -> float:
    """Control steps of the shortest path at cruise speed.

    The path runs from the start cell's centre through the cell centres of a breadth-first
    shortest path to the goal cell's centre, less the goal's radius; turns cost nothing.
    """
    maze = CellMaze(world)
    goal = world.goal
    radius = 0.0 if goal is None else goal[2]
    length = max(maze.shortest_path_length() - radius, 0.0)
    return length / cruise_step_length(RobotProfile.builtin("seed"), control_step_ms)


class NavigationBatch:
    """N robots each driving episodes from a world's start towards its goal.

    Args:
        worlds: The worlds; robot ``i`` drives in ``worlds[world_of_env[i]]``.
        world_of_env: (N,) index of each robot's world; by default all in ``worlds[0]``.
        num_envs: Number of robots (the length of ``world_of_env`` when that is given).
        seed: Seed of the episodes' jitter and noise.
        jitter: The start jitter; ``StartJitter(0, 0)`` for none.
        noise: Sensor noise on or off.
        max_steps: Control steps after which an episode ends unfinished.
        events: ``"truth"`` or ``"robust"`` (see the module).
        control_step_ms: The control step.
        threads: Worker threads of the batch (0: one per core).

    Raises:
        InvalidArgumentError: A world has no goal, or a bad argument.
    """

    def __init__(
        self,
        worlds: Sequence[World],
        world_of_env: npt.ArrayLike | None = None,
        num_envs: int = 1,
        seed: int = 0,
        jitter: StartJitter | None = None,
        noise: bool = True,
        max_steps: int = DEFAULT_MAX_STEPS,
        events: str = "truth",
        control_step_ms: float = CONTROL_STEP_MS,
        threads: int = 0,
    ) -> None:
        if events not in EVENT_SOURCES:
            raise InvalidArgumentError(
                f"expected events from one of {', '.join(EVENT_SOURCES)}, found {events!r}"
            )
        self.worlds = list(worlds)
        if not self.worlds:
            raise InvalidArgumentError("expected at least one world, found none")
        goals = []
        for world in self.worlds:
            if world.goal is None:
                raise InvalidArgumentError(f"world {world.name!r} has no goal to drive to")
            goals.append(world.goal)
        self.goals = np.array(goals, dtype=np.float64)
        if world_of_env is None:
            self.world_of_env = np.zeros(num_envs, dtype=np.int64)
        else:
            self.world_of_env = np.asarray(world_of_env, dtype=np.int64).ravel()
        count = self.world_of_env.size
        if count < 1 or self.world_of_env.min() < 0 or self.world_of_env.max() >= len(worlds):
            raise InvalidArgumentError("expected at least one robot, each in one of the worlds")
        self.num_envs = count
        self.seed = int(seed)
        self.jitter = jitter if jitter is not None else StartJitter()
        self.max_steps = int(max_steps)
        self.events_from = events
        self.control_step_ms = float(control_step_ms)
        self.robot = RobotProfile.builtin("seed")
        self.wheel_speeds = (WHEEL_SPEED_FRACTIONS * self.robot.max_wheel_speed).astype(np.float32)
        self.batch = BatchSimulator(
            [self.worlds[i] for i in self.world_of_env],
            robot="seed",
            seeds=0,
            noise=noise,
            control_step_ms=control_step_ms,
            threads=threads,
        )
        width = self.batch.observation_width
        self.distance_width = self.batch.distance_width
        self.observations = np.zeros((count, width), dtype=np.float32)
        self.poses = np.zeros((count, 3), dtype=np.float32)
        self.colliding = np.zeros(count, dtype=bool)
        self.crossings = np.zeros(count, dtype=np.int32)
        self.episode = np.full(count, -1, dtype=np.int64)
        self.episode_steps = np.zeros(count, dtype=np.int64)
        self.contact_steps = np.zeros(count, dtype=np.int64)
        self.events = np.zeros(count, dtype=np.int64)
        self._reader = None
        self._encoders = None
        if events == "robust":
            from mazesim.barcode import BatchBarcodeReader, CodeBook, RobustDecoder
            from mazesim.barcode.odometry import WheelEncoders

            # A world without checkpoints paints no codes: any book does, none is ever read.
            books = [
                CodeBook.from_world(world) if world.checkpoints() else CodeBook.default()
                for world in self.worlds
            ]
            decoders = [RobustDecoder(books[i]) for i in self.world_of_env]
            self._reader = BatchBarcodeReader(decoders, self.robot)
            self._encoders = WheelEncoders(self.robot, count, control_step_ms)

    def start(self, envs: npt.ArrayLike, episodes: npt.ArrayLike) -> None:
        """Starts episode ``episodes[j]`` on robot ``envs[j]`` (jittered start, fresh noise seed).

        The buffers hold the new robots' first observations afterwards.
        """
        robots = np.asarray(envs, dtype=np.int64).ravel()
        numbers = np.asarray(episodes, dtype=np.int64).ravel()
        for env, episode in zip(robots, numbers):
            rng = np.random.default_rng([self.seed, int(episode)])
            world = self.worlds[self.world_of_env[env]]
            x, y, yaw = world.start
            x += rng.uniform(-self.jitter.position, self.jitter.position)
            y += rng.uniform(-self.jitter.position, self.jitter.position)
            yaw += rng.uniform(-self.jitter.yaw, self.jitter.yaw)
            self.batch.set_world(
                int(env), world_with_start(world, x, y, yaw), int(rng.integers(2**63))
            )
            self.episode[env] = episode
        self.episode_steps[robots] = 0
        self.contact_steps[robots] = 0
        self.events[robots] = 0
        mask = np.zeros(self.num_envs, dtype=bool)
        mask[robots] = True
        if self._reader is not None and self._encoders is not None:
            self._reader.reset(mask)
            self._encoders.reset(mask)
        self.batch.observe(self.observations, self.poses, self.colliding, self.crossings)

    def step(self, actions: npt.ArrayLike) -> tuple[npt.NDArray[np.bool_], npt.NDArray[np.bool_]]:
        """Steps every robot with discrete actions (indices into the action table).

        Returns:
            ``(arrived, out_of_time)``: (N,) bool, robots now inside their goal disc, and robots
            whose episode used up ``max_steps`` without arriving. :attr:`events` holds the
            checkpoint event of the step.
        """
        speeds = self.wheel_speeds[np.asarray(actions, dtype=np.int64)]
        self.batch.step(speeds, self.observations, self.poses, self.colliding, self.crossings)
        self.episode_steps += 1
        self.contact_steps += self.colliding
        if self._reader is not None and self._encoders is not None:
            self._encoders.step(speeds)
            self.events[:] = 0
            ground = self.observations[:, self.distance_width]
            for env, reading in self._reader.update(ground, self._encoders.values):
                self.events[env] = reading.signed_id
        else:
            self.events[:] = self.crossings
        goal = self.goals[self.world_of_env]
        distance = np.hypot(self.poses[:, 0] - goal[:, 0], self.poses[:, 1] - goal[:, 1])
        arrived = distance <= goal[:, 2]
        out_of_time = ~arrived & (self.episode_steps >= self.max_steps)
        return arrived, out_of_time

    def bumps(self) -> npt.NDArray[np.int64]:
        """(N,) wall bumps of each robot's episode so far (the simulator's collision counter)."""
        return self.batch.collisions().astype(np.int64)
