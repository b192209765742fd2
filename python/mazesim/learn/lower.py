"""Training the four lower-level sub-tasks on generated mazes, thousands of robots at a time.

A :class:`LowerTrainer` steps one :class:`mazesim.BatchSimulator` of ``num_envs`` robots. Each
robot practises one sub-task (30% Corridors and Corners, 20% each turn, 30% Going forward), in
episodes drawn from a pool of generated 5 x 5 mazes (perfect ones and ones with loops, so that
every kind of door occurs):

- Corridors and Corners starts at a random cell centre, half the time facing a random opening
  (up to 5 cm and 40 degrees off), half the time facing any way at all, so that it learns to
  recover from poor poses and to turn round in dead ends; it drives for
  :attr:`LowerSettings.corridor_episode_steps` steps.
- A door sub-task starts in a straight corridor cell next to a door that has the opening it needs
  (on the right, the left or straight ahead), between 3 cm short of and 5 cm past the cell's
  centre (where a checkpoint's code ends), up to 3 cm off the centre line and 11 degrees off the
  corridor's heading; it runs until its sub-task ends (:mod:`mazesim.learn.subtasks`).

**Decisions.** The discretised state changes only every few control steps, so a decision holds
its action until the state changes (or for at most ``decision_steps`` steps) and is learned as
one SMDP transition: the rewards along the way discounted, then ``gamma ** tau`` times the value
of the state it led to. A greedy policy repeats its action while the state stays, so this is the
same policy, learned from fewer, more informative updates. Exploration is epsilon-greedy at each
decision (among the sub-task's :data:`mazesim.learn.subtasks.SUBTASK_ACTIONS`), epsilon falling
linearly from ``epsilon_start`` to 0 over the rounds but the last
``greedy_share`` of them, which are greedy: the tables then learn from their own mistakes, so a
greedy policy that loops between two states loses the value of the loop.

**Updates.** Every transition and its left-right mirror image (the core's
``navigator::symmetry``) update the tables with the core's Q update.

**Rounds.** Training runs in rounds of ``round_steps`` control steps; every robot starts a fresh
episode at the start of a round (episodes still running at its end are cut short, not failed).
A round's randomness is drawn before it from the stream of ``(seed, round)``: each robot's queue
of episode starts (:func:`draw_starts`), then every step's exploration draws
(:func:`draw_exploration`). The simulator is deterministic, so the tables after round k depend on
the settings alone: a run resumed from a checkpoint after round k ends with the same tables as one
never stopped.

**In the core.** A round runs in one call of :func:`mazesim._core.train_lower_round`, with every
option of the navigator handed in as data: the phases the door sub-tasks count (``"heading"`` or
``"heading_and_distance"``), what Corridors and Corners does in the blind state (``"table"``,
``"forward"`` or ``"hold_heading"``), each batch's wheel speeds (robots of several motor limits)
and, for a :class:`~mazesim.learn.fleet.Fleet` of several sensor sets, each group's map of its
readings into the seed robot's volts. ``tests/lower_oracle.py`` keeps the same round
stepped in numpy, the reference the core's is checked against bit for bit.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._core import LowerRoundSettings, World, generate_maze, train_lower_round
from mazesim._seeding import stream, stream_seeds
from mazesim._settings import MAX_COUNT, MAX_SEED, bounded, check_settings
from mazesim.actions import ACTION_CODES
from mazesim.batch import RobotBatch, RobotChoice
from mazesim.errors import InvalidArgumentError
from mazesim.learn import qlearning
from mazesim.learn.discretise import NUM_STATES
from mazesim.learn.fleet import Fleet, FleetBatch
from mazesim.learn.subtasks import (
    BLIND_STATE,
    COLLISION_PENALTY,
    CONTROL_STEP_MS,
    CORRIDOR_STEP_REWARD,
    DOOR_FAILURE_REWARD,
    DOOR_STEP_REWARD,
    DOOR_SUCCESS_REWARD,
    HEADING_REWARD,
    NUM_SUBTASKS,
    PROGRESS_REWARD,
    SUBTASK_ACTIONS,
    SubTask,
    cruise_step_length,
    phase_counts,
)
from mazesim.maze import CellMaze

__all__ = [
    "LowerSettings",
    "LowerTables",
    "LowerTrainer",
    "RoundStats",
    "drive_on_when_blind",
    "lower_table_shape",
    "training_mazes",
]

#: Sub-task of each robot, by index modulo 10: 3 x CC, 2 x R, 2 x L, 3 x F.
ROLE_PATTERN = (0, 1, 3, 2, 0, 3, 1, 0, 2, 3)
#: Loops of the mazes of the pool, in turn (0 = a perfect maze).
POOL_LOOPS = (0.0, 0.1, 0.2, 0.3)
#: Along, across (metres) and heading (radians) spread of door-sub-task starts.
DOOR_START_ALONG = (-0.03, 0.05)
DOOR_START_ACROSS = 0.03
DOOR_START_YAW = 0.2
#: Position (metres, each axis) and heading (radians) spread of Corridors-and-Corners starts.
CORRIDOR_START_SPREAD = 0.05
CORRIDOR_START_YAW = 0.7
#: Share of Corridors-and-Corners starts facing any way at all (into a wall, a dead end's end).
CORRIDOR_ANY_HEADING = 0.5
#: How far into the opening the door path runs, and the success test at the end.
DOOR_PATH_EXIT = 0.25
SUCCESS_PAST_CENTRE = 0.04
SUCCESS_ACROSS = 0.08

NUM_ACTIONS = len(ACTION_CODES)
#: The forward action, which ``blind_forward`` takes in the blind state.
_FORWARD = ACTION_CODES.index("00")
#: The actions Corridors and Corners explores, drawn uniformly (the door sub-tasks may take, and
#: explore, all 12).
_CORRIDOR_ACTIONS = np.flatnonzero(SUBTASK_ACTIONS[SubTask.CORRIDOR])
#: Episode starts drawn per robot for a round. A robot's episodes take its starts in turn, and
#: begin again from its first if it ever used them all (a door episode lasts 10 steps at the
#: least, so 64 cover a round of up to 640 steps).
STARTS_PER_ROUND = 64
#: Exact unit vectors of the four grid directions (east, north, west, south).
_UNIT = np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]])


def lower_table_shape(door_distance: bool = False) -> tuple[int, int, int]:
    """Shape of the stacked lower-level tables: (sub-task, state with phase, action); with
    ``door_distance`` the door sub-tasks' phases count the distance too
    (:data:`mazesim.learn.subtasks.DISTANCE_PHASES`)."""
    return (NUM_SUBTASKS, max(phase_counts(door_distance)) * NUM_STATES, NUM_ACTIONS)


def drive_on_when_blind(q: npt.NDArray[np.float64]) -> None:
    """Makes forward (``00``) the best action of Corridors and Corners in the blind state
    (:data:`mazesim.learn.subtasks.BLIND_STATE`), in place: every other action's value there
    is put below forward's where it was not already. Training with ``blind_forward`` never tries
    them there, so their values are the untried ones; after this every reader of the tables (the
    core's too) drives forward there, as the training did."""
    row = q[SubTask.CORRIDOR, BLIND_STATE]
    forward = row[_FORWARD]
    others = np.arange(row.size) != _FORWARD
    row[others & (row >= forward)] = forward - 1.0


#: The most env-steps a training run takes (``mazesim train --steps``).
MAX_TRAINING_STEPS = 10**12


@dataclass(frozen=True)
class LowerSettings:
    """What a lower-level training run does (all of it goes into the saved metadata)."""

    num_envs: int = bounded(2048, least=1, most=MAX_COUNT)
    total_steps: int = bounded(36_000_000, least=1, most=MAX_TRAINING_STEPS)
    round_steps: int = bounded(500, least=1, most=MAX_COUNT)
    seed: int = bounded(0, least=0, most=MAX_SEED)
    maze_pool: int = bounded(200, least=1, most=MAX_COUNT)
    gamma: float = bounded(0.99, least=0.0, most=1.0)
    epsilon_start: float = bounded(0.3, least=0.0, most=1.0)
    greedy_share: float = bounded(0.2, least=0.0, most=1.0)
    decision_steps: int = bounded(10, least=1, most=MAX_COUNT)
    corridor_episode_steps: int = bounded(350, least=1, most=MAX_COUNT)
    control_step_ms: float = bounded(CONTROL_STEP_MS, above=0.0)
    rate: qlearning.LearningRate = field(default_factory=qlearning.LearningRate)
    #: The door sub-tasks' phases also count the distance driven (``mazesim train
    #: --door-distance``, :data:`mazesim.learn.subtasks.DISTANCE_PHASES`).
    door_distance: bool = False
    #: Corridors and Corners drives forward in the blind state, in training (exploring too) and
    #: after it (``mazesim train --blind-forward``, :func:`drive_on_when_blind`).
    blind_forward: bool = False
    #: There, it holds its heading on the maze's grid instead of driving straight on (``mazesim
    #: train --hold-heading``, the core's ``navigator::heading_hold``); set with ``blind_forward``.
    hold_heading: bool = False

    def __post_init__(self) -> None:
        check_settings(self)

    @property
    def rounds(self) -> int:
        """Number of rounds: enough for ``total_steps`` env-steps, at least one."""
        return max(1, math.ceil(self.total_steps / (self.num_envs * self.round_steps)))

    def epsilon(self, round_index: int) -> float:
        """Exploration rate of a round."""
        exploring = max(1, round(self.rounds * (1.0 - self.greedy_share)))
        return max(0.0, self.epsilon_start * (1.0 - round_index / exploring))

    def as_dict(self) -> dict[str, object]:
        """The settings as plain JSON values (``door_distance``, ``blind_forward`` and
        ``hold_heading`` only when set, as before they existed)."""
        values = asdict(self)
        for name in ("door_distance", "blind_forward", "hold_heading"):
            if not values[name]:
                values.pop(name)
        values["rounds"] = self.rounds
        return values


@dataclass
class LowerTables:
    """The four sub-task tables stacked, with their update counts.

    ``q[k, s, a]`` is sub-task ``k``'s value of action ``a`` in state ``s`` (Corridors and
    Corners uses the first 4096 states only).
    """

    q: npt.NDArray[np.float64]
    visits: npt.NDArray[np.int64]

    @classmethod
    def zeros(cls, door_distance: bool = False) -> LowerTables:
        """Fresh tables (:func:`lower_table_shape`): all values 0 (so untried states drive
        forward), no visits."""
        shape = lower_table_shape(door_distance)
        return cls(np.zeros(shape, dtype=np.float64), np.zeros(shape, dtype=np.int64))


@dataclass
class RoundStats:
    """What happened in one round."""

    round_index: int
    epsilon: float
    env_steps: int
    door_success: list[int]
    door_failure: list[int]
    door_cut: list[int]
    corridor_speed: float
    contact_share: float

    def door_success_rate(self, subtask: int | None = None) -> float:
        """Share of the door episodes that ended in their opening (of one sub-task, or all)."""
        picks = [1, 2, 3] if subtask is None else [subtask]
        done = sum(self.door_success[k] for k in picks)
        total = done + sum(self.door_failure[k] + self.door_cut[k] for k in picks)
        return done / total if total else 0.0


def training_mazes(seed: int, count: int) -> list[World]:
    """The pool of generated 5 x 5 mazes a run trains on; their seeds derive from ``seed``.

    A draw that is a single corridor stays in the pool (``junction=False``), as when the shipped
    navigator was trained: the pool, and so training from scratch, gives its tables bit for bit."""
    maze_seeds = stream_seeds(seed, "lower/mazes", count)
    return [
        generate_maze(
            5,
            5,
            seed=int(maze_seed),
            loops=POOL_LOOPS[index % len(POOL_LOOPS)],
            junction=False,
        )
        for index, maze_seed in enumerate(maze_seeds)
    ]


#: Quarter turns from the heading into a door to the opening each sub-task takes.
_TURN_QUARTERS = {SubTask.RIGHT: 3, SubTask.LEFT: 1, SubTask.FORWARD: 0}


@dataclass
class EpisodeStarts:
    """Each robot's queue of episode starts for one round, ``(N, K)`` rows: robot i's k-th
    episode of the round starts from row ``k % K`` of its queue.

    Attributes:
        world: Index of the start's maze in the pool.
        pose: x, y, yaw.
        seed: The sensor-noise seed.
        path: A door sub-task's path (zeros for Corridors and Corners): start (2), door centre
            (2), heading in (2), heading out (2), length of the first leg.
    """

    world: npt.NDArray[np.int64]
    pose: npt.NDArray[np.float64]
    seed: npt.NDArray[np.uint64]
    path: npt.NDArray[np.float64]

    def as_dict(self) -> dict[str, npt.NDArray[Any]]:
        """The arrays by name, as the core's round takes them."""
        return {"world": self.world, "pose": self.pose, "seed": self.seed, "path": self.path}


@dataclass
class Exploration:
    """A round's exploration draws, ``(steps, N)``: a deciding robot explores when its uniform
    draw is below the round's epsilon, and then takes its random action (among its sub-task's
    :data:`~mazesim.learn.subtasks.SUBTASK_ACTIONS`)."""

    uniform: npt.NDArray[np.float64]
    action: npt.NDArray[np.int64]


class _StartTables:
    """The pool's possible starts as arrays, to draw many at once."""

    def __init__(self, cells: list[CellMaze]) -> None:
        most_cells = max(maze.rows * maze.cols for maze in cells)
        self.cell_count = np.array([maze.rows * maze.cols for maze in cells], dtype=np.int64)
        self.cell_centre = np.zeros((len(cells), most_cells, 2))
        self.openings = np.zeros((len(cells), most_cells, 4), dtype=np.int64)
        self.opening_count = np.ones((len(cells), most_cells), dtype=np.int64)
        for m, maze in enumerate(cells):
            for c, cell in enumerate(maze.cells()):
                self.cell_centre[m, c] = maze.center(cell)
                open_sides = maze.openings(cell)
                self.openings[m, c, : len(open_sides)] = open_sides
                self.opening_count[m, c] = max(1, len(open_sides))
        # Door starts of each door sub-task: maze, cell centre, door centre, heading.
        self.door: dict[int, tuple[npt.NDArray[Any], ...]] = {}
        for subtask, quarters in _TURN_QUARTERS.items():
            picks = [
                (m, maze.center(a.cell), maze.center(a.door), a.heading)
                for m, maze in enumerate(cells)
                for a in maze.door_approaches()
                if a.straight and maze.is_open(a.door, (a.heading + quarters) % 4)
            ]
            if not picks:
                raise InvalidArgumentError(
                    f"expected the training mazes to hold a door for sub-task {subtask.name}, "
                    "found none"
                )
            self.door[int(subtask)] = (
                np.array([p[0] for p in picks], dtype=np.int64),
                np.array([p[1] for p in picks], dtype=np.float64),
                np.array([p[2] for p in picks], dtype=np.float64),
                np.array([p[3] for p in picks], dtype=np.int64),
            )


def _index_below(
    rng: np.random.Generator, count: npt.NDArray[np.int64], shape: tuple[int, ...]
) -> npt.NDArray[np.int64]:
    """Uniform indices below ``count`` (broadcast to ``shape``)."""
    drawn = np.floor(rng.random(shape) * count).astype(np.int64)
    return np.minimum(drawn, count - 1)


def draw_starts(
    rng: np.random.Generator,
    role: npt.NDArray[np.int64],
    tables: _StartTables,
    per_env: int = STARTS_PER_ROUND,
) -> EpisodeStarts:
    """Draws ``per_env`` episode starts for each robot of sub-task ``role`` (see the module)."""
    shape = (role.size, per_env)
    door_env = np.broadcast_to((role != SubTask.CORRIDOR)[:, None], shape)
    # Corridors and Corners: a random cell of a random maze, facing one of its openings or any way.
    maze = rng.integers(len(tables.cell_count), size=shape)
    cell = _index_below(rng, tables.cell_count[maze], shape)
    side = _index_below(rng, tables.opening_count[maze, cell], shape)
    direction = tables.openings[maze, cell, side]
    position = tables.cell_centre[maze, cell] + rng.uniform(
        -CORRIDOR_START_SPREAD, CORRIDOR_START_SPREAD, (*shape, 2)
    )
    yaw = direction * (math.pi / 2.0) + rng.uniform(-CORRIDOR_START_YAW, CORRIDOR_START_YAW, shape)
    any_way = rng.random(shape) < CORRIDOR_ANY_HEADING
    yaw = np.where(any_way, rng.uniform(-math.pi, math.pi, shape), yaw)
    # A door sub-task: a straight corridor cell next to a door with the opening it needs.
    along = rng.uniform(*DOOR_START_ALONG, shape)
    across = rng.uniform(-DOOR_START_ACROSS, DOOR_START_ACROSS, shape)
    yaw_error = rng.uniform(-DOOR_START_YAW, DOOR_START_YAW, shape)
    pick = rng.random(shape)
    path = np.zeros((*shape, 9))
    for subtask, (door_maze, cell_centre, door_centre, heading) in tables.door.items():
        mine = np.broadcast_to((role == subtask)[:, None], shape)
        if not mine.any():
            continue
        k = np.minimum(np.floor(pick * heading.size).astype(np.int64), heading.size - 1)[mine]
        heading_in = _UNIT[heading[k]]
        sideways = np.stack([-heading_in[:, 1], heading_in[:, 0]], axis=1)
        start = (
            cell_centre[k] + heading_in * along[mine][:, None] + sideways * across[mine][:, None]
        )
        door = door_centre[k]
        maze[mine] = door_maze[k]
        position[mine] = start
        yaw[mine] = heading[k] * (math.pi / 2.0) + yaw_error[mine]
        to_door = door - start
        path[mine] = np.column_stack(
            [
                start,
                door,
                heading_in,
                _UNIT[(heading[k] + _TURN_QUARTERS[SubTask(subtask)]) % 4],
                to_door[:, 0] * heading_in[:, 0] + to_door[:, 1] * heading_in[:, 1],
            ]
        )
    seeds = rng.integers(2**63, size=shape).astype(np.uint64)
    path[~door_env] = 0.0
    pose = np.concatenate([position, yaw[..., None]], axis=-1)
    return EpisodeStarts(world=maze.astype(np.int64), pose=pose, seed=seeds, path=path)


def draw_exploration(
    rng: np.random.Generator, role: npt.NDArray[np.int64], steps: int
) -> Exploration:
    """A round's exploration draws for robots of sub-task ``role`` (see :class:`Exploration`)."""
    count = role.size
    uniform = rng.random((steps, count))
    door_action = rng.integers(0, NUM_ACTIONS, (steps, count))
    corridor_action = _CORRIDOR_ACTIONS[rng.integers(0, _CORRIDOR_ACTIONS.size, (steps, count))]
    door = (role != SubTask.CORRIDOR)[None, :]
    return Exploration(uniform, np.where(door, door_action, corridor_action).astype(np.int64))


class LowerTrainer:
    """Trains the lower-level tables round by round.

    Each round runs in the core (:func:`mazesim._core.train_lower_round`), whatever the robots:
    one :class:`~mazesim.batch.RobotBatch`, or a :class:`~mazesim.learn.fleet.Fleet` of several
    sensor sets, a batch per group.

    Args:
        settings: The run's settings.
        tables: Tables to continue from; fresh ones by default.
        threads: Worker threads of the batch (0: one per core); results do not depend on it.
        robot: The robots (:data:`mazesim.batch.RobotChoice`), handed to the batch as given, or
            a :class:`~mazesim.learn.fleet.Fleet` of several base profiles.
    """

    def __init__(
        self,
        settings: LowerSettings,
        tables: LowerTables | None = None,
        threads: int = 0,
        robot: RobotChoice | Fleet = "seed",
    ) -> None:
        self.settings = settings
        self.tables = tables if tables is not None else LowerTables.zeros(settings.door_distance)
        if self.tables.q.shape != lower_table_shape(settings.door_distance):
            raise InvalidArgumentError(
                f"expected lower-level tables of shape {lower_table_shape(settings.door_distance)}"
                f" (door_distance={settings.door_distance}), found {self.tables.q.shape}"
            )
        self.mazes = training_mazes(settings.seed, settings.maze_pool)
        self.start_tables = _StartTables([CellMaze(world) for world in self.mazes])
        count = settings.num_envs
        self.threads = threads
        # The batch first: it refuses a number of envs the machine cannot hold.
        self.use_robots(robot)
        self.role = np.resize(np.array(ROLE_PATTERN, dtype=np.int64), count)
        self.cruise_step = cruise_step_length(self.batch.profile, settings.control_step_ms)

    def use_robots(self, robot: RobotChoice | Fleet) -> None:
        """Drives the next rounds with ``robot``: a fresh batch of those robots (every robot starts
        a fresh episode at a round's start, so nothing of the last round's batch is lost)."""
        self.batch: RobotBatch | FleetBatch
        if isinstance(robot, Fleet):
            self.batch = FleetBatch(
                self.mazes, robot, self.settings.control_step_ms, threads=self.threads
            )
        else:
            self.batch = RobotBatch(
                self.mazes,
                np.zeros(self.settings.num_envs, dtype=np.int64),
                robot=robot,
                control_step_ms=self.settings.control_step_ms,
                threads=self.threads,
            )

    def draws(self, round_index: int) -> tuple[EpisodeStarts, Exploration]:
        """Round ``round_index``'s random draws: the episode starts, then the exploration, from
        the stream ``lower/round`` of the round."""
        rng = stream(self.settings.seed, "lower/round", round_index)
        starts = draw_starts(rng, self.role, self.start_tables)
        return starts, draw_exploration(rng, self.role, self.settings.round_steps)

    # -- one round --------------------------------------------------------------------------

    def run_round(self, round_index: int) -> RoundStats:
        """Runs round ``round_index`` (0-based) in the core and returns what happened in it."""
        epsilon = self.settings.epsilon(round_index)
        starts, exploration = self.draws(round_index)
        settings = LowerRoundSettings(
            self._core_settings(epsilon), self.mazes, self.role, SUBTASK_ACTIONS
        )
        counts = train_lower_round(
            self._crews(),
            settings,
            starts.as_dict(),
            exploration.uniform,
            exploration.action,
            self.tables.q,
            self.tables.visits,
        )
        return self.round_stats(round_index, counts)

    def round_stats(self, round_index: int, counts: dict[str, Any]) -> RoundStats:
        """The stats of round ``round_index`` from the counts of its round."""
        settings = self.settings
        count = settings.num_envs
        door = self.role != SubTask.CORRIDOR
        corridor_robot_steps = int(np.count_nonzero(~door)) * settings.round_steps
        return RoundStats(
            round_index=round_index,
            epsilon=settings.epsilon(round_index),
            env_steps=count * settings.round_steps,
            door_success=[int(v) for v in counts["success"]],
            door_failure=[int(v) for v in counts["failure"]],
            door_cut=[int(v) for v in counts["cut"]],
            corridor_speed=float(counts["corridor_metres"])
            / max(1, corridor_robot_steps)
            / self.cruise_step,
            contact_share=int(counts["contact_steps"]) / (count * settings.round_steps),
        )

    def _core_settings(self, epsilon: float) -> dict[str, float | str]:
        settings = self.settings
        if settings.hold_heading:
            blind = "hold_heading"
        elif settings.blind_forward:
            blind = "forward"
        else:
            blind = "table"
        return {
            "phases": "heading_and_distance" if settings.door_distance else "heading",
            "blind": blind,
            "gamma": settings.gamma,
            "epsilon": epsilon,
            "decision_steps": settings.decision_steps,
            "corridor_episode_steps": settings.corridor_episode_steps,
            "rate_initial": settings.rate.initial,
            "rate_floor": settings.rate.floor,
            "rate_power": settings.rate.power,
            "progress_reward": PROGRESS_REWARD,
            "collision_penalty": COLLISION_PENALTY,
            "corridor_step_reward": CORRIDOR_STEP_REWARD,
            "door_step_reward": DOOR_STEP_REWARD,
            "heading_reward": HEADING_REWARD,
            "door_success_reward": DOOR_SUCCESS_REWARD,
            "door_failure_reward": DOOR_FAILURE_REWARD,
            "door_path_exit": DOOR_PATH_EXIT,
            "success_past_centre": SUCCESS_PAST_CENTRE,
            "success_across": SUCCESS_ACROSS,
        }

    def _crews(self) -> list[dict[str, Any]]:
        """The batches of the round's robots, as the core's round takes them."""
        batch = self.batch
        parts: list[tuple[RobotBatch, npt.NDArray[np.int64], dict[str, Any] | None]]
        if isinstance(batch, RobotBatch):
            parts = [(batch, np.arange(batch.world_of_env.size, dtype=np.int64), None)]
        else:
            parts = batch.crews()
        return [
            {
                "simulator": part.simulator,
                "observations": part.observations,
                "poses": part.poses,
                "colliding": part.colliding,
                "crossings": part.crossings,
                "world_of_env": part.world_of_env,
                "wheel_speeds": part.wheel_speeds,
                "members": members,
                "readings": readings,
            }
            for part, members, readings in parts
        ]
