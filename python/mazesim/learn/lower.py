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
  corridor's heading; it runs until :class:`mazesim.learn.subtasks.SubTaskTracker` says it ended.

**Decisions.** The discretised state changes only every few control steps, so a decision holds
its action until the state changes (or for at most ``decision_steps`` steps) and is learned as
one SMDP transition: the rewards along the way discounted, then ``gamma ** tau`` times the value
of the state it led to. A greedy policy repeats its action while the state stays, so this is the
same policy, learned from fewer, more informative updates. Exploration is epsilon-greedy at each
decision (among the sub-task's :data:`mazesim.learn.subtasks.SUBTASK_ACTIONS`), epsilon falling
linearly from ``epsilon_start`` to 0 over the rounds but the last
``greedy_share`` of them, which are greedy: the tables then learn from their own mistakes, so a
greedy policy that loops between two states loses the value of the loop.

**Updates.** Every transition and its mirror image (:mod:`mazesim.learn.symmetry`) update the tables
with :func:`mazesim.learn.qlearning.batch_update`.

**Rounds.** Training runs in rounds of ``round_steps`` control steps; every robot starts a fresh
episode at the start of a round (episodes still running at its end are cut short, not failed).
A round's randomness comes from ``(seed, round)`` only, and the simulator is deterministic, so the
tables after round k depend on the settings alone: a run resumed from a checkpoint after round k
ends with the same tables as one never stopped.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

import numpy as np
import numpy.typing as npt

from mazesim._core import World, generate_maze
from mazesim._seeding import stream, stream_seeds
from mazesim.actions import ACTION_CODES
from mazesim.batch import RobotBatch, RobotChoice
from mazesim.learn import qlearning
from mazesim.learn.discretise import NUM_STATES, observation_states
from mazesim.learn.fleet import Fleet, FleetBatch
from mazesim.learn.subtasks import (
    COLLISION_PENALTY,
    CONTROL_STEP_MS,
    CORRIDOR_STEP_REWARD,
    DOOR_FAILURE_REWARD,
    DOOR_STEP_REWARD,
    DOOR_SUCCESS_REWARD,
    HEADING_REWARD,
    MAX_PHASES,
    NUM_SUBTASKS,
    PROGRESS_REWARD,
    SUBTASK_ACTIONS,
    SubTask,
    SubTaskTracker,
    cruise_step_length,
)
from mazesim.learn.symmetry import MIRRORED_ACTION, MIRRORED_SUBTASK, mirrored_states
from mazesim.maze import CellMaze, DoorApproach

__all__ = [
    "LowerSettings",
    "LowerTables",
    "LowerTrainer",
    "RoundStats",
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
#: The actions Corridors and Corners explores, drawn uniformly (the door sub-tasks may take, and
#: explore, all 12).
_CORRIDOR_ACTIONS = np.flatnonzero(SUBTASK_ACTIONS[SubTask.CORRIDOR])


def lower_table_shape() -> tuple[int, int, int]:
    """Shape of the stacked lower-level tables: (sub-task, state with phase, action)."""
    return (NUM_SUBTASKS, MAX_PHASES * NUM_STATES, NUM_ACTIONS)


@dataclass(frozen=True)
class LowerSettings:
    """What a lower-level training run does (all of it goes into the saved metadata)."""

    num_envs: int = 2048
    total_steps: int = 36_000_000
    round_steps: int = 500
    seed: int = 0
    maze_pool: int = 200
    gamma: float = 0.99
    epsilon_start: float = 0.3
    greedy_share: float = 0.2
    decision_steps: int = 10
    corridor_episode_steps: int = 350
    control_step_ms: float = CONTROL_STEP_MS
    rate: qlearning.LearningRate = field(default_factory=qlearning.LearningRate)

    @property
    def rounds(self) -> int:
        """Number of rounds: enough for ``total_steps`` env-steps, at least one."""
        return max(1, math.ceil(self.total_steps / (self.num_envs * self.round_steps)))

    def epsilon(self, round_index: int) -> float:
        """Exploration rate of a round."""
        exploring = max(1, round(self.rounds * (1.0 - self.greedy_share)))
        return max(0.0, self.epsilon_start * (1.0 - round_index / exploring))

    def as_dict(self) -> dict[str, object]:
        """The settings as plain JSON values."""
        values = asdict(self)
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
    def zeros(cls) -> LowerTables:
        """Fresh tables: all values 0 (so untried states drive forward), no visits."""
        shape = lower_table_shape()
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
    """The pool of generated 5 x 5 mazes a run trains on; their seeds derive from ``seed``."""
    maze_seeds = stream_seeds(seed, "lower/mazes", count)
    return [
        generate_maze(5, 5, seed=int(maze_seed), loops=POOL_LOOPS[index % len(POOL_LOOPS)])
        for index, maze_seed in enumerate(maze_seeds)
    ]


#: Quarter turns from the heading into a door to the opening each sub-task takes.
_TURN_QUARTERS = {SubTask.RIGHT: 3, SubTask.LEFT: 1, SubTask.FORWARD: 0}


def _unit(direction: int) -> npt.NDArray[np.float64]:
    angle = direction * math.pi / 2.0
    return np.array([math.cos(angle), math.sin(angle)])


class LowerTrainer:
    """Trains the lower-level tables round by round.

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
        self.tables = tables if tables is not None else LowerTables.zeros()
        self.mazes = training_mazes(settings.seed, settings.maze_pool)
        self.cells = [CellMaze(world) for world in self.mazes]
        self.door_starts: dict[int, list[tuple[int, DoorApproach]]] = {}
        for subtask, quarters in _TURN_QUARTERS.items():
            self.door_starts[int(subtask)] = [
                (index, approach)
                for index, maze in enumerate(self.cells)
                for approach in maze.door_approaches()
                if approach.straight
                and maze.is_open(approach.door, (approach.heading + quarters) % 4)
            ]
        count = settings.num_envs
        self.threads = threads
        # The batch first: it refuses a number of envs the machine cannot hold.
        self.use_robots(robot)
        self.role = np.resize(np.array(ROLE_PATTERN, dtype=np.int64), count)
        self.cruise_step = cruise_step_length(self.batch.profile, settings.control_step_ms)
        self.tracker = SubTaskTracker(count)
        # The door path of each robot's episode: start, door centre, directions, first leg.
        self.path_start = np.zeros((count, 2))
        self.door_centre = np.zeros((count, 2))
        self.heading_in = np.zeros((count, 2))
        self.heading_out = np.zeros((count, 2))
        self.first_leg = np.zeros(count)
        self.episode_steps = np.zeros(count, dtype=np.int64)

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
        self.observations = self.batch.observations
        self.poses = self.batch.poses
        self.colliding = self.batch.colliding

    # -- episodes ---------------------------------------------------------------------------

    def _start_episodes(self, envs: npt.NDArray[np.int64], rng: np.random.Generator) -> None:
        poses = np.zeros((envs.size, 3))
        seeds = np.zeros(envs.size, dtype=np.uint64)
        for row, env in enumerate(envs):
            role = int(self.role[env])
            if role == SubTask.CORRIDOR:
                maze_index = int(rng.integers(len(self.mazes)))
                maze = self.cells[maze_index]
                cell = maze.cells()[int(rng.integers(maze.rows * maze.cols))]
                openings = maze.openings(cell)
                direction = openings[int(rng.integers(len(openings)))]
                centre = np.array(maze.center(cell))
                offset = rng.uniform(-CORRIDOR_START_SPREAD, CORRIDOR_START_SPREAD, 2)
                x, y = centre + offset
                yaw = direction * math.pi / 2.0 + rng.uniform(
                    -CORRIDOR_START_YAW, CORRIDOR_START_YAW
                )
                if rng.random() < CORRIDOR_ANY_HEADING:
                    yaw = rng.uniform(-math.pi, math.pi)
            else:
                starts = self.door_starts[role]
                maze_index, approach = starts[int(rng.integers(len(starts)))]
                maze = self.cells[maze_index]
                heading_in = _unit(approach.heading)
                across = np.array([-heading_in[1], heading_in[0]])
                start = (
                    np.array(maze.center(approach.cell))
                    + heading_in * rng.uniform(*DOOR_START_ALONG)
                    + across * rng.uniform(-DOOR_START_ACROSS, DOOR_START_ACROSS)
                )
                x, y = start
                yaw = approach.heading * math.pi / 2.0 + rng.uniform(
                    -DOOR_START_YAW, DOOR_START_YAW
                )
                door = np.array(maze.center(approach.door))
                self.path_start[env] = start
                self.door_centre[env] = door
                self.heading_in[env] = heading_in
                self.heading_out[env] = _unit(
                    (approach.heading + _TURN_QUARTERS[SubTask(role)]) % 4
                )
                self.first_leg[env] = float((door - start) @ heading_in)
            self.batch.move_to_world(int(env), maze_index)
            poses[row] = x, y, yaw
            seeds[row] = rng.integers(2**63)
            self.episode_steps[env] = 0
        self.batch.place(envs, poses, seeds)

    def _path_progress(self, positions: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        """Metres along each robot's door path (first leg clipped to its length)."""
        first = np.einsum("ij,ij->i", positions - self.path_start, self.heading_in)
        second = np.einsum("ij,ij->i", positions - self.door_centre, self.heading_out)
        return np.minimum(first, self.first_leg) + np.clip(second, 0.0, DOOR_PATH_EXIT)

    def _entered_opening(self, positions: npt.NDArray[np.float64]) -> npt.NDArray[np.bool_]:
        relative = positions - self.door_centre
        along = np.einsum("ij,ij->i", relative, self.heading_out)
        across = np.abs(
            relative[:, 0] * self.heading_out[:, 1] - relative[:, 1] * self.heading_out[:, 0]
        )
        return (along >= SUCCESS_PAST_CENTRE) & (across <= SUCCESS_ACROSS)

    # -- one round --------------------------------------------------------------------------

    def run_round(self, round_index: int) -> RoundStats:
        """Runs round ``round_index`` (0-based) and returns what happened in it."""
        settings = self.settings
        rng = stream(settings.seed, "lower/round", round_index)
        epsilon = settings.epsilon(round_index)
        count = settings.num_envs
        everyone = np.arange(count)
        q = self.tables.q
        role = self.role
        door = role != SubTask.CORRIDOR

        self._start_episodes(everyone, rng)
        positions = self.poses.astype(np.float64)
        self.tracker.begin(np.ones(count, dtype=bool), role, positions)
        progress = self._path_progress(positions[:, :2])
        previous_error = np.zeros(count)
        state = self.tracker.states(observation_states(self.observations))
        action = np.zeros(count, dtype=np.int64)
        decided_reward = np.zeros(count)
        decided_discount = np.ones(count)
        decided_steps = np.zeros(count, dtype=np.int64)
        deciding = np.ones(count, dtype=bool)

        success = [0] * NUM_SUBTASKS
        failure = [0] * NUM_SUBTASKS
        cut = [0] * NUM_SUBTASKS
        corridor_metres = 0.0
        contact_steps = 0

        for _ in range(settings.round_steps):
            explore = rng.random(count) < epsilon
            random_action = np.where(
                door,
                rng.integers(0, NUM_ACTIONS, count),
                _CORRIDOR_ACTIONS[rng.integers(0, _CORRIDOR_ACTIONS.size, count)],
            )
            greedy = qlearning.best_allowed(q[role, state], SUBTASK_ACTIONS[role])
            chosen = np.where(explore, random_action, greedy)
            action = np.where(deciding, chosen, action)
            decided_reward[deciding] = 0.0
            decided_discount[deciding] = 1.0
            decided_steps[deciding] = 0

            before = self.poses.astype(np.float64)
            self.batch.step(action)
            positions = self.poses.astype(np.float64)
            self.episode_steps += 1
            done, gave_up = self.tracker.update(positions)
            out_of_steps = gave_up & self.tracker.out_of_steps
            next_state = self.tracker.states(observation_states(self.observations))

            forward = (positions[:, 0] - before[:, 0]) * np.cos(before[:, 2]) + (
                positions[:, 1] - before[:, 1]
            ) * np.sin(before[:, 2])
            new_progress = self._path_progress(positions[:, :2])
            reward = np.where(
                door,
                PROGRESS_REWARD * (new_progress - progress) + DOOR_STEP_REWARD,
                PROGRESS_REWARD * forward + CORRIDOR_STEP_REWARD,
            )
            reward += COLLISION_PENALTY * self.colliding
            progress = new_progress
            heading_error = np.abs(self.tracker.heading_change)
            reward += np.where(
                role == SubTask.FORWARD, HEADING_REWARD * (previous_error - heading_error), 0.0
            )
            previous_error = heading_error
            entered = self._entered_opening(positions[:, :2])
            ended = door & (done | (gave_up & ~out_of_steps))
            good = ended & done & entered
            reward += np.where(ended, np.where(good, DOOR_SUCCESS_REWARD, DOOR_FAILURE_REWARD), 0.0)
            cut_short = door & out_of_steps
            corridor_over = ~door & (self.episode_steps >= settings.corridor_episode_steps)

            decided_reward += decided_discount * reward
            decided_discount *= settings.gamma
            decided_steps += 1
            deciding = (
                ended
                | cut_short
                | corridor_over
                | (next_state != state)
                | (decided_steps >= settings.decision_steps)
            )
            bootstrap = np.where(ended, 0.0, decided_discount)
            self._learn(deciding, state, action, decided_reward, next_state, bootstrap)

            for subtask in (SubTask.RIGHT, SubTask.LEFT, SubTask.FORWARD):
                mine = role == subtask
                success[subtask] += int(np.count_nonzero(mine & good))
                failure[subtask] += int(np.count_nonzero(mine & ended & ~good))
                cut[subtask] += int(np.count_nonzero(mine & cut_short))
            corridor_metres += float(forward[~door].sum())
            contact_steps += int(np.count_nonzero(self.colliding))

            state = next_state
            restart = np.flatnonzero(ended | cut_short | corridor_over)
            if restart.size:
                self._start_episodes(restart, rng)
                fresh = np.zeros(count, dtype=bool)
                fresh[restart] = True
                positions = self.poses.astype(np.float64)
                self.tracker.begin(fresh, role, positions)
                progress[fresh] = self._path_progress(positions[:, :2])[fresh]
                previous_error[fresh] = 0.0
                state[fresh] = self.tracker.states(observation_states(self.observations))[fresh]

        corridor_robot_steps = int(np.count_nonzero(~door)) * settings.round_steps
        return RoundStats(
            round_index=round_index,
            epsilon=epsilon,
            env_steps=count * settings.round_steps,
            door_success=success,
            door_failure=failure,
            door_cut=cut,
            corridor_speed=corridor_metres / max(1, corridor_robot_steps) / self.cruise_step,
            contact_share=contact_steps / (count * settings.round_steps),
        )

    def _learn(
        self,
        deciding: npt.NDArray[np.bool_],
        state: npt.NDArray[np.int64],
        action: npt.NDArray[np.int64],
        reward: npt.NDArray[np.float64],
        next_state: npt.NDArray[np.int64],
        bootstrap: npt.NDArray[np.float64],
    ) -> None:
        """Feeds the finished decisions and their mirror images to the tables."""
        envs = np.flatnonzero(deciding)
        if envs.size == 0:
            return
        table = self.role[envs]
        table = np.concatenate([table, MIRRORED_SUBTASK[table]])
        states = np.concatenate([state[envs], mirrored_states(state[envs], self.role[envs])])
        actions = np.concatenate([action[envs], MIRRORED_ACTION[action[envs]]])
        rewards = np.concatenate([reward[envs], reward[envs]])
        following = np.concatenate(
            [next_state[envs], mirrored_states(next_state[envs], self.role[envs])]
        )
        factors = np.concatenate([bootstrap[envs], bootstrap[envs]])
        for subtask in range(NUM_SUBTASKS):
            mine = table == subtask
            if np.any(mine):
                qlearning.batch_update(
                    self.tables.q[subtask],
                    self.tables.visits[subtask],
                    states[mine],
                    actions[mine],
                    rewards[mine],
                    following[mine],
                    factors[mine],
                    self.settings.rate,
                    SUBTASK_ACTIONS[subtask],
                )
