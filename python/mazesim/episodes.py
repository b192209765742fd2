"""The one episode layer: N robots driving from a world's start to its goal, in one batch.

An :class:`EpisodeBatch` runs one episode per robot at a time on the ``seed`` robot
(:class:`mazesim.batch.RobotBatch`), with sensor noise and a small random jitter of the start
pose (:class:`StartJitter`: up to 2 cm along each axis and 10 degrees of heading, uniformly); it
holds the one step limit (:data:`MAX_STEPS`), the goal test and the episode counters. Episode
``k`` draws its jitter and its noise seed from its named stream (:mod:`mazesim._seeding`) and
``k`` alone, so a result does not depend on how many robots run side by side.
:func:`run_episodes` drives the batch with any :class:`Navigator` until every world has run its
number of episodes; training, evaluation and the flat learner all run their episodes through it.

Checkpoint events come from the simulator's ground truth of barcode crossings, or, with
``events="robust"``, from :class:`mazesim.barcode.RobustDecoder` reading each robot's ground
sensor (with wheel encoders integrated from the actions); both give ``+id`` for an arrival,
``-id`` for a departure and 0 for nothing.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np
import numpy.typing as npt

from mazesim._core import RobotProfile, World
from mazesim._seeding import seed_sequence
from mazesim._seeding import stream as random_stream
from mazesim._sizes import index_array, whole_array
from mazesim.batch import CONTROL_STEP_MS, RobotBatch, RobotChoice, cruise_step_length
from mazesim.errors import (
    InvalidArgumentError,
    RegisteredName,
    _bounded_number,
    _known_name,
    _shown,
)
from mazesim.maze import CellMaze, navigator_problems

__all__ = [
    "EVENT_SOURCES",
    "MAX_STEPS",
    "EpisodeBatch",
    "EpisodeResult",
    "EpisodeSchedule",
    "Navigator",
    "StartJitter",
    "learning_problems",
    "run_episodes",
    "shortest_path_steps",
]

#: Where checkpoint events come from.
EVENT_SOURCES = ("truth", "robust")
#: Control steps after which an episode ends unfinished (about 4 minutes at 64 ms): the one step
#: limit of training, evaluation and the flat learner.
MAX_STEPS = 4000


@dataclass(frozen=True)
class StartJitter:
    """Uniform jitter of the start pose: up to ``position`` metres along x and y and ``yaw``
    radians of heading, either way."""

    position: float = 0.02
    yaw: float = math.radians(10.0)

    def __post_init__(self) -> None:
        # A NaN or negative jitter would draw NaN starts.
        object.__setattr__(self, "position", _bounded_number("position", self.position, least=0.0))
        object.__setattr__(self, "yaw", _bounded_number("yaw", self.yaw, least=0.0))


def shortest_path_steps(world: World, control_step_ms: float = CONTROL_STEP_MS) -> float:
    """Control steps of the shortest path at cruise speed.

    The path runs from the start cell's centre through the cell centres of a breadth-first
    shortest path to the goal cell's centre, less the goal's radius; turns cost nothing.
    """
    step = _bounded_number("control_step_ms", control_step_ms, above=0.0)
    maze = CellMaze(world)
    goal = world.goal
    radius = 0.0 if goal is None else goal[2]
    length = max(maze.shortest_path_length() - radius, 0.0)
    return length / cruise_step_length(RobotProfile.builtin("seed"), step)


def learning_problems(world: World, *, show_command: str | None = None) -> list[str]:
    """What keeps the navigator from learning ``world``, each said with what to change
    (:func:`mazesim.maze.navigator_problems`), and a goal farther from the start than any episode
    of :data:`MAX_STEPS` can drive at cruise speed; empty when it can learn it."""
    problems = navigator_problems(world, show_command=show_command)
    maze = CellMaze(world)
    if problems or maze.start_cell is None or maze.goal_cell is None:
        return problems
    steps = shortest_path_steps(world)
    if steps > MAX_STEPS:
        reach = MAX_STEPS * cruise_step_length(RobotProfile.builtin("seed"))
        problems.append(
            f"its goal is {maze.shortest_path_length():.2f} m from the start along the cells, "
            f"about {steps:,.0f} control steps of {CONTROL_STEP_MS:g} ms at cruise speed, more "
            f"than the {MAX_STEPS} an episode lasts ({reach:.1f} m), so no episode can reach "
            "it: draw a smaller maze, or put the goal nearer the start"
        )
    return problems


class EpisodeBatch:
    """N robots each driving episodes from a world's start towards its goal.

    Args:
        worlds: The worlds; robot ``i`` drives in ``worlds[world_of_env[i]]``.
        world_of_env: (N,) index of each robot's world; by default all in ``worlds[0]``.
        num_envs: Number of robots (the length of ``world_of_env`` when that is given).
        seed: Seed of the episodes' jitter and noise.
        stream: The named random stream of the episodes (:data:`mazesim._seeding.STREAMS`,
            indexed by episode number).
        jitter: The start jitter; ``StartJitter(0, 0)`` for none.
        noise: Sensor noise on or off.
        max_steps: Control steps after which an episode ends unfinished.
        events: ``"truth"`` or ``"robust"`` (see the module).
        control_step_ms: The control step.
        threads: Worker threads of the batch (0: one per core).
        robot: The robot profile (a name or a :class:`mazesim.RobotProfile`, such as a perturbed
            one), or one per robot (see :data:`mazesim.batch.RobotChoice`).

    Raises:
        InvalidArgumentError: A world has no goal, or a bad argument.
    """

    def __init__(
        self,
        worlds: Sequence[World],
        world_of_env: npt.ArrayLike | None = None,
        num_envs: int = 1,
        seed: int = 0,
        stream: str = "evaluate/episode",
        jitter: StartJitter | None = None,
        noise: bool = True,
        max_steps: int = MAX_STEPS,
        events: RegisteredName = "truth",
        control_step_ms: float = CONTROL_STEP_MS,
        threads: int = 0,
        robot: RobotChoice = "seed",
    ) -> None:
        _known_name(events, "events", tuple(EVENT_SOURCES))
        self.worlds = list(worlds)
        if not self.worlds:
            raise InvalidArgumentError("expected at least one world, found none")
        goals = []
        for world in self.worlds:
            if world.goal is None:
                raise InvalidArgumentError(f"world {_shown(world.name)} has no goal to drive to")
            goals.append(world.goal)
        self.goals = np.array(goals, dtype=np.float64)
        if world_of_env is None:
            world_of_env = np.zeros(num_envs, dtype=np.int64)
        self.batch = RobotBatch(
            self.worlds,
            world_of_env,
            robot=robot,
            noise=noise,
            control_step_ms=control_step_ms,
            threads=threads,
        )
        self.world_of_env = self.batch.world_of_env
        count = self.num_envs = self.batch.num_envs
        self.seed = int(seed)
        self.stream = stream
        seed_sequence(self.seed, stream, 0)  # an unknown stream name fails here
        self.jitter = jitter if jitter is not None else StartJitter()
        self.max_steps = int(max_steps)
        self.events_from = events
        self.control_step_ms = float(control_step_ms)
        self.robot = self.batch.profile
        self.distance_width = self.batch.distance_width
        self.observations = self.batch.observations
        self.poses = self.batch.poses
        self.colliding = self.batch.colliding
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
        robots = index_array(envs, "envs", self.num_envs).ravel()
        numbers = whole_array(episodes, "episodes", low=0).ravel()
        if numbers.size != robots.size:
            raise InvalidArgumentError(
                f"expected one episode number per robot ({robots.size}), found {numbers.size}"
            )
        poses = np.zeros((robots.size, 3))
        seeds = np.zeros(robots.size, dtype=np.uint64)
        for row, (env, episode) in enumerate(zip(robots, numbers)):
            rng = random_stream(self.seed, self.stream, int(episode))
            x, y, yaw = self.worlds[self.world_of_env[env]].start
            x += rng.uniform(-self.jitter.position, self.jitter.position)
            y += rng.uniform(-self.jitter.position, self.jitter.position)
            yaw += rng.uniform(-self.jitter.yaw, self.jitter.yaw)
            poses[row] = x, y, yaw
            seeds[row] = rng.integers(2**63)
            self.episode[env] = episode
        self.batch.place(robots, poses, seeds)
        self.episode_steps[robots] = 0
        self.contact_steps[robots] = 0
        self.events[robots] = 0
        mask = np.zeros(self.num_envs, dtype=bool)
        mask[robots] = True
        if self._reader is not None and self._encoders is not None:
            self._reader.reset(mask)
            self._encoders.reset(mask)

    def step(self, actions: npt.ArrayLike) -> tuple[npt.NDArray[np.bool_], npt.NDArray[np.bool_]]:
        """Steps every robot with discrete actions (indices into the action table).

        Returns:
            ``(arrived, out_of_time)``: (N,) bool, robots now inside their goal disc, and robots
            whose episode used up ``max_steps`` without arriving. :attr:`events` holds the
            checkpoint event of the step.
        """
        speeds = self.batch.speeds_of(actions)
        self.batch.step_speeds(speeds)
        self.episode_steps += 1
        self.contact_steps += self.colliding
        if self._reader is not None and self._encoders is not None:
            self._encoders.step(speeds)
            self.events[:] = 0
            ground = self.observations[:, self.distance_width]
            for env, reading in self._reader.update(ground, self._encoders.values):
                self.events[env] = reading.signed_id
        else:
            self.events[:] = self.batch.crossings
        arrived = self.at_goal()
        out_of_time = ~arrived & (self.episode_steps >= self.max_steps)
        return arrived, out_of_time

    def at_goal(self, poses: npt.NDArray[np.float32] | None = None) -> npt.NDArray[np.bool_]:
        """(N,) bool: robots whose centre (at ``poses``, by default their poses now) is inside
        their world's goal disc.

        The squared distance from the float32 pose to the goal, in float64, against the squared
        radius: the core's own goal test (``BatchSimulator.run``'s ``end_at_goal``), so that an
        episode ends on the same step whichever way it is stepped.
        """
        goal = self.goals[self.world_of_env]
        rows = self.poses if poses is None else poses
        dx = rows[:, 0].astype(np.float64) - goal[:, 0]
        dy = rows[:, 1].astype(np.float64) - goal[:, 1]
        return np.asarray(dx * dx + dy * dy <= goal[:, 2] * goal[:, 2])

    def bumps(self) -> npt.NDArray[np.int64]:
        """(N,) wall bumps of each robot's episode so far (the simulator's collision counter)."""
        return self.batch.collisions()


class Navigator(Protocol):
    """What :func:`run_episodes` drives: N robots' controllers."""

    def reset(self, envs: npt.ArrayLike, poses: npt.ArrayLike) -> None: ...

    def act(
        self, observations: npt.ArrayLike, poses: npt.ArrayLike, events: npt.ArrayLike
    ) -> npt.NDArray[np.int64]: ...


class NavigatorWrapper:
    """The base of a navigator that drives through another, :attr:`navigator`."""

    navigator: Any

    @property
    def record(self) -> Any:
        """The wrapped navigator's record of its last step (for traces)."""
        return self.navigator.record


@dataclass
class EpisodeResult:
    """One episode: where, which, and how it went."""

    world: int
    episode: int
    arrived: bool
    steps: int
    bumps: int
    contact_steps: int
    decisions: list[tuple[int, int]] = field(default_factory=list)


#: Called after every step with the batch, the actions, ``arrived`` and ``out_of_time``.
Watcher = Callable[
    [EpisodeBatch, npt.NDArray[np.int64], npt.NDArray[np.bool_], npt.NDArray[np.bool_]], None
]


class EpisodeSchedule:
    """Which episode each robot of an :class:`EpisodeBatch` runs, and what the ended ones
    measured: the bookkeeping shared by :func:`run_episodes` and the loops that step robots
    many steps at a time (:mod:`mazesim.learn.core_episodes`).

    Episode ``k`` of world ``w`` is numbered ``w * episodes_per_world + k``; robots of a world
    take its episodes in turn, and a robot whose world has none left is no longer
    :attr:`active`.

    Args:
        nav: The robots and their worlds.
        navigator: Told of every robot that starts an episode (``reset``).
        episodes_per_world: Episodes to run in each world.
    """

    def __init__(self, nav: EpisodeBatch, navigator: Navigator, episodes_per_world: int) -> None:
        self.nav = nav
        self.navigator = navigator
        worlds = len(nav.worlds)
        self.next_episode = np.arange(worlds) * episodes_per_world
        self.last_episode = self.next_episode + episodes_per_world
        self.active = np.zeros(nav.num_envs, dtype=bool)
        self.results: dict[int, EpisodeResult] = {}
        self.decisions: dict[int, list[tuple[int, int]]] = {}

    def start(self, robots: npt.NDArray[np.int64]) -> None:
        """Starts the next episode of their world on ``robots`` (where one is left)."""
        nav = self.nav
        starting = []
        numbers = []
        for env in robots:
            world = nav.world_of_env[env]
            if self.next_episode[world] < self.last_episode[world]:
                starting.append(env)
                numbers.append(self.next_episode[world])
                self.next_episode[world] += 1
        self.active[robots] = False
        if starting:
            chosen = np.array(starting, dtype=np.int64)
            nav.start(chosen, numbers)
            self.navigator.reset(chosen, nav.poses)
            self.active[chosen] = True
            for env in chosen:
                self.decisions[int(env)] = []

    def decide(
        self,
        robots: npt.NDArray[np.int64],
        chosen: npt.NDArray[np.int64],
        events: npt.NDArray[np.int64],
    ) -> None:
        """Logs the sub-tasks ``chosen`` for ``robots`` with the events that caused them."""
        for env, option in zip(robots, chosen):
            if self.active[env]:
                self.decisions[int(env)].append((int(events[env]), int(option)))

    def end(self, ended: npt.NDArray[np.int64], arrived: npt.NDArray[np.bool_]) -> None:
        """Records the episodes of robots ``ended`` (``arrived``: (N,) bool) and starts their
        next ones."""
        nav = self.nav
        bumps = nav.bumps()
        for env in ended:
            number = int(nav.episode[env])
            self.results[number] = EpisodeResult(
                world=int(nav.world_of_env[env]),
                episode=number,
                arrived=bool(arrived[env]),
                steps=int(nav.episode_steps[env]),
                bumps=int(bumps[env]),
                contact_steps=int(nav.contact_steps[env]),
                decisions=self.decisions.pop(int(env)),
            )
        self.start(ended)

    def close(
        self,
        arrived: npt.NDArray[np.bool_],
        out_of_time: npt.NDArray[np.bool_],
        events: npt.NDArray[np.int64],
        on_end: Callable[[npt.NDArray[np.int64], npt.NDArray[np.bool_]], None] | None,
    ) -> None:
        """Ends the episodes of the robots that ``arrived`` or ran ``out_of_time`` ((N,) bool):
        tells ``on_end``, records them (:meth:`end`) and clears their pending ``events``."""
        ended = np.flatnonzero(arrived | out_of_time)
        if ended.size:
            if on_end is not None:
                on_end(ended, arrived[ended])
            self.end(ended, arrived)
            events[ended] = 0

    def ordered_results(self) -> list[EpisodeResult]:
        """The results so far, in order of episode number."""
        return [self.results[number] for number in sorted(self.results)]


def run_episodes(
    nav: EpisodeBatch,
    navigator: Navigator,
    episodes_per_world: int,
    watch: Watcher | None = None,
    on_end: Callable[[npt.NDArray[np.int64], npt.NDArray[np.bool_]], None] | None = None,
    decisions_of: Callable[[], tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]]] | None = None,
) -> list[EpisodeResult]:
    """Runs ``episodes_per_world`` episodes in each world of ``nav``, one control step at a time.

    Episode ``k`` of world ``w`` is numbered ``w * episodes_per_world + k``; its start jitter and
    noise seed follow from that number (see :class:`EpisodeBatch`). Robots of a world take its
    episodes in turn; a robot whose world has none left waits (its steps are not counted).

    Args:
        nav: The robots and their worlds.
        navigator: The controller of all robots.
        episodes_per_world: Episodes to run in each world.
        watch: Called after every step (see :data:`Watcher`).
        on_end: Called with the robots whose episode ended and whether each arrived, before new
            episodes start on them.
        decisions_of: Returns ``(robots, sub-tasks)`` chosen at the last step, to log them with
            the checkpoint event that caused them.

    Returns:
        The results, in order of episode number.
    """
    schedule = EpisodeSchedule(nav, navigator, episodes_per_world)
    active = schedule.active
    schedule.start(np.arange(nav.num_envs))
    events = np.zeros(nav.num_envs, dtype=np.int64)
    while np.any(active):
        actions = navigator.act(nav.observations, nav.poses, events)
        if decisions_of is not None:
            schedule.decide(*decisions_of(), events)
        arrived, out_of_time = nav.step(actions)
        arrived &= active
        out_of_time &= active
        events = nav.events.copy()
        if watch is not None:
            watch(nav, actions, arrived, out_of_time)
        schedule.close(arrived, out_of_time, events, on_end)
    return schedule.ordered_results()
