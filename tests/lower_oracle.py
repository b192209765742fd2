"""The lower level's training round stepped in numpy, one control step at a time: the plain,
slow reference that the core's round (:func:`mazesim._core.train_lower_round`, which
:meth:`mazesim.learn.lower.LowerTrainer.run_round` calls) is checked against bit for bit.

The core follows it operation for operation: the sub-tasks' odometry of
:class:`navigator_oracle.SubTaskTracker` (the core's ``navigator::door``), the Table 4.1 states
of ``lower_level_states``, the batch updates of :func:`mazesim.learn.qlearning.batch_update`
for each decision and its mirror image, and, for a fleet, each group stepped in its own batch
and read through its map into the seed robot's volts.
"""

from __future__ import annotations

from typing import Any, Union

import numpy as np
import numpy.typing as npt

from mazesim._core import lower_level_states
from mazesim.batch import RobotBatch
from mazesim.learn import qlearning
from mazesim.learn.fleet import FleetBatch
from mazesim.learn.lower import (
    _FORWARD,
    DOOR_PATH_EXIT,
    SUCCESS_ACROSS,
    SUCCESS_PAST_CENTRE,
    EpisodeStarts,
    Exploration,
    LowerTrainer,
    RoundStats,
)
from mazesim.learn.subtasks import (
    BLIND_STATE,
    COLLISION_PENALTY,
    CORRIDOR_STEP_REWARD,
    DOOR_FAILURE_REWARD,
    DOOR_STEP_REWARD,
    DOOR_SUCCESS_REWARD,
    HEADING_REWARD,
    NUM_SUBTASKS,
    PROGRESS_REWARD,
    SUBTASK_ACTIONS,
    SubTask,
)
from navigator_oracle import (
    MIRRORED_ACTION,
    MIRRORED_SUBTASK,
    SubTaskTracker,
    hold_actions,
    mirrored_states,
)

NUM_SENSORS = 6


def move_to_world(batch: RobotBatch, env: int, world: int) -> None:
    """Puts robot ``env`` of ``batch`` into ``batch.worlds[world]`` (placed at that world's start
    until ``place`` moves it); nothing happens when it is there already."""
    if int(batch.world_of_env[env]) != int(world):
        batch.simulator.set_world(int(env), batch.worlds[int(world)], 0)
        batch.world_of_env[env] = int(world)


class SteppedFleet:
    """A :class:`FleetBatch` stepped as one batch of seed-robot observations: (N, 6) float32
    volts of each robot's distance sensors, its pose and its contact flag."""

    def __init__(self, fleet: FleetBatch) -> None:
        self.fleet = fleet
        count = fleet.num_envs
        self.group = np.zeros(count, dtype=np.int64)
        self.row = np.zeros(count, dtype=np.int64)
        for index, envs in enumerate(fleet.members):
            self.group[envs] = index
            self.row[envs] = np.arange(envs.size)
        self.observations = np.zeros((count, NUM_SENSORS), dtype=np.float32)
        self.poses = np.zeros((count, 3), dtype=np.float32)
        self.colliding = np.zeros(count, dtype=bool)

    def _gather(self) -> None:
        fleet = self.fleet
        for envs, batch, readings in zip(fleet.members, fleet.batches, fleet.readings):
            if batch is None:
                continue
            distances = batch.observations[:, : batch.distance_width]
            volts = distances[:, :NUM_SENSORS] if readings is None else readings.volts(distances)
            self.observations[envs] = np.asarray(volts, dtype=np.float32)
            self.poses[envs] = batch.poses
            self.colliding[envs] = batch.colliding

    def step(self, actions: npt.NDArray[np.int64]) -> None:
        """Steps every group's robots with their actions."""
        for envs, batch in zip(self.fleet.members, self.fleet.batches):
            if batch is not None:
                batch.step(actions[envs])
        self._gather()

    def move_to_world(self, env: int, world: int) -> None:
        """Puts robot ``env`` into world ``world``."""
        batch = self.fleet.batches[int(self.group[env])]
        assert batch is not None
        move_to_world(batch, int(self.row[env]), world)

    def place(
        self, envs: npt.NDArray[np.int64], poses: npt.NDArray[np.float64], seeds: npt.NDArray[Any]
    ) -> None:
        """Starts robots ``envs`` afresh at ``poses`` with noise ``seeds``."""
        for index, batch in enumerate(self.fleet.batches):
            mine = self.group[envs] == index
            if batch is not None and mine.any():
                batch.place(self.row[envs[mine]], poses[mine], seeds[mine])
        self._gather()


Robots = Union[RobotBatch, SteppedFleet]


def stepwise_round(trainer: LowerTrainer, round_index: int) -> RoundStats:
    """Runs ``trainer``'s round ``round_index`` one control step at a time (the tables, counts and
    robots of :meth:`LowerTrainer.run_round`, from the same draws)."""
    batch = trainer.batch
    robots: Robots = batch if isinstance(batch, RobotBatch) else SteppedFleet(batch)
    epsilon = trainer.settings.epsilon(round_index)
    starts, exploration = trainer.draws(round_index)
    counts = _round(trainer, robots, starts, exploration, epsilon)
    return trainer.round_stats(round_index, counts)


def _round(
    self: LowerTrainer,
    robots: Robots,
    starts: EpisodeStarts,
    exploration: Exploration,
    epsilon: float,
) -> dict[str, Any]:
    """The round one control step at a time; the core's round follows it operation for
    operation."""
    settings = self.settings
    count = settings.num_envs
    q = self.tables.q
    role = self.role
    door = role != SubTask.CORRIDOR
    episode = _Episodes(self, robots, starts)
    tracker = episode.tracker
    everyone = np.arange(count)

    episode.start(everyone)
    progress = episode.progress()
    previous_error = np.zeros(count)
    state = tracker.states(lower_level_states(robots.observations))
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

    for step in range(settings.round_steps):
        explore = exploration.uniform[step] < epsilon
        greedy = qlearning.best_allowed(q[role, state], SUBTASK_ACTIONS[role])
        chosen = np.where(explore, exploration.action[step], greedy)
        if settings.blind_forward or settings.hold_heading:
            blind = (role == SubTask.CORRIDOR) & (state == BLIND_STATE)
            if settings.hold_heading:
                rule = hold_actions(robots.poses[:, 2], action)
            else:
                rule = np.full(count, _FORWARD)
            chosen = np.where(blind, rule, chosen)
        action = np.where(deciding, chosen, action)
        decided_reward[deciding] = 0.0
        decided_discount[deciding] = 1.0
        decided_steps[deciding] = 0

        before = robots.poses.astype(np.float64)
        robots.step(action)
        positions = robots.poses.astype(np.float64)
        episode.steps += 1
        done, gave_up = tracker.update(positions)
        out_of_steps = gave_up & tracker.out_of_steps
        next_state = tracker.states(lower_level_states(robots.observations))

        heading = np.stack([np.cos(before[:, 2]), np.sin(before[:, 2])], axis=1)
        forward = _along(positions, before, heading)
        new_progress = episode.progress()
        reward = np.where(
            door,
            PROGRESS_REWARD * (new_progress - progress) + DOOR_STEP_REWARD,
            PROGRESS_REWARD * forward + CORRIDOR_STEP_REWARD,
        )
        reward += COLLISION_PENALTY * robots.colliding
        progress = new_progress
        heading_error = np.abs(tracker.heading_change)
        reward += np.where(
            role == SubTask.FORWARD, HEADING_REWARD * (previous_error - heading_error), 0.0
        )
        previous_error = heading_error
        entered = episode.entered_opening()
        ended = door & (done | (gave_up & ~out_of_steps))
        good = ended & done & entered
        reward += np.where(ended, np.where(good, DOOR_SUCCESS_REWARD, DOOR_FAILURE_REWARD), 0.0)
        cut_short = door & out_of_steps
        corridor_over = ~door & (episode.steps >= settings.corridor_episode_steps)

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
        _learn(self, deciding, state, action, decided_reward, next_state, bootstrap)

        for subtask in (SubTask.RIGHT, SubTask.LEFT, SubTask.FORWARD):
            mine = role == subtask
            success[subtask] += int(np.count_nonzero(mine & good))
            failure[subtask] += int(np.count_nonzero(mine & ended & ~good))
            cut[subtask] += int(np.count_nonzero(mine & cut_short))
        if np.any(~door):
            # Summed in robot order, as the core sums it.
            corridor_metres += float(np.cumsum(forward[~door])[-1])
        contact_steps += int(np.count_nonzero(robots.colliding))

        state = next_state
        restart = np.flatnonzero(ended | cut_short | corridor_over)
        if restart.size:
            episode.start(restart)
            fresh = np.zeros(count, dtype=bool)
            fresh[restart] = True
            progress[fresh] = episode.progress()[fresh]
            previous_error[fresh] = 0.0
            state[fresh] = tracker.states(lower_level_states(robots.observations))[fresh]

    return {
        "success": success,
        "failure": failure,
        "cut": cut,
        "corridor_metres": corridor_metres,
        "contact_steps": contact_steps,
    }


def _learn(
    self: LowerTrainer,
    deciding: npt.NDArray[np.bool_],
    state: npt.NDArray[np.int64],
    action: npt.NDArray[np.int64],
    reward: npt.NDArray[np.float64],
    next_state: npt.NDArray[np.int64],
    bootstrap: npt.NDArray[np.float64],
) -> None:
    """Feeds the finished decisions, then their mirror images, to the tables."""
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


class _Episodes:
    """The robots' running episodes in a round stepped from Python: where each started, its door
    path and its sub-task's odometry."""

    def __init__(self, trainer: LowerTrainer, robots: Robots, starts: EpisodeStarts) -> None:
        count = trainer.settings.num_envs
        self.trainer = trainer
        self.robots = robots
        self.starts = starts
        self.tracker = SubTaskTracker(count, trainer.settings.door_distance)
        self.taken = np.zeros(count, dtype=np.int64)
        self.steps = np.zeros(count, dtype=np.int64)
        self.path = np.zeros((count, 9))

    def start(self, envs: npt.NDArray[np.int64]) -> None:
        """Starts the next episode of each robot of ``envs`` from its queue."""
        trainer = self.trainer
        per_env = self.starts.world.shape[1]
        rows = self.taken[envs] % per_env
        self.taken[envs] += 1
        for env, world in zip(envs, self.starts.world[envs, rows]):
            if isinstance(self.robots, RobotBatch):
                move_to_world(self.robots, int(env), int(world))
            else:
                self.robots.move_to_world(int(env), int(world))
        self.robots.place(envs, self.starts.pose[envs, rows], self.starts.seed[envs, rows])
        self.path[envs] = self.starts.path[envs, rows]
        self.steps[envs] = 0
        fresh = np.zeros(trainer.settings.num_envs, dtype=bool)
        fresh[envs] = True
        self.tracker.begin(fresh, trainer.role, self.robots.poses.astype(np.float64))

    def progress(self) -> npt.NDArray[np.float64]:
        """Metres along each robot's door path (first leg clipped to its length)."""
        positions = self.robots.poses.astype(np.float64)
        path = self.path
        first = _along(positions, path[:, 0:2], path[:, 4:6])
        second = _along(positions, path[:, 2:4], path[:, 6:8])
        return np.minimum(first, path[:, 8]) + np.clip(second, 0.0, DOOR_PATH_EXIT)

    def entered_opening(self) -> npt.NDArray[np.bool_]:
        """Whether each robot is past its door's centre into the opening, near its centre line."""
        positions = self.robots.poses.astype(np.float64)
        centre, heading_out = self.path[:, 2:4], self.path[:, 6:8]
        along = _along(positions, centre, heading_out)
        relative = positions[:, :2] - centre
        across = np.abs(relative[:, 0] * heading_out[:, 1] - relative[:, 1] * heading_out[:, 0])
        return (along >= SUCCESS_PAST_CENTRE) & (across <= SUCCESS_ACROSS)


def _along(
    points: npt.NDArray[np.float64], origin: npt.NDArray[np.float64], unit: npt.NDArray[np.float64]
) -> npt.NDArray[np.float64]:
    """Each row's ``(point - origin) . unit``, as the core sums it."""
    return (points[:, 0] - origin[:, 0]) * unit[:, 0] + (points[:, 1] - origin[:, 1]) * unit[:, 1]
