"""``BatchSimulator.run(..., subtasks=...)``: the tabular controller runs the navigator's door
sub-tasks in the core, following each robot's odometry as ``SubTaskTracker.update`` does.

A call of k steps equals, bit for bit, k steps of the navigator's lower level in Python (its
actions, poses and the tracker's arrays), whatever the threads or the batch size; bad sub-task
arrays are refused with the package's own errors before anything moves.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import numpy.typing as npt
import pytest

import mazesim
from mazesim.actions import ACTION_CODES
from mazesim.batch import RobotBatch
from mazesim.learn.discretise import NUM_STATES, observation_states
from mazesim.learn.qlearning import best_allowed
from mazesim.learn.subtasks import MAX_PHASES, NUM_SUBTASKS, SUBTASK_ACTIONS, SubTask
from mazesim.learn.tables import load_policy
from navigator_oracle import SubTaskTracker, hold_spins

STEPS = 260
LOWER_Q = load_policy(None).lower_q
assert LOWER_Q is not None
TABLES = np.ascontiguousarray(
    LOWER_Q.reshape(NUM_SUBTASKS * MAX_PHASES, NUM_STATES, len(ACTION_CODES))
)
ALLOWED = np.ascontiguousarray(np.repeat(SUBTASK_ACTIONS, MAX_PHASES, axis=0))


def robots_in_doors(worlds: list[int], threads: int = 1) -> tuple[RobotBatch, SubTaskTracker]:
    """Robots in generated mazes, each beginning a sub-task (all four kinds) where it starts,
    the robot of world w with sensor-noise seed w (whatever the batch it is in)."""
    mazes = [mazesim.generate_maze(5, 5, seed=150 + w) for w in worlds]
    batch = RobotBatch(mazes, np.arange(len(worlds)), threads=threads)
    batch.reset(seeds=np.array(worlds, dtype=np.uint64))
    tracker = SubTaskTracker(batch.num_envs)
    kinds = np.array(worlds) % NUM_SUBTASKS
    tracker.begin(np.ones(batch.num_envs, dtype=bool), kinds, batch.poses)
    return batch, tracker


def run_in_core(
    batch: RobotBatch, tracker: SubTaskTracker, steps: int = STEPS, **options: Any
) -> tuple[dict[str, npt.NDArray[Any]], dict[str, npt.NDArray[np.uint64]]]:
    n = batch.num_envs
    trace = {
        "actions": np.zeros((steps, n), dtype=np.int32),
        "poses": np.zeros((steps, n, 3), dtype=np.float32),
    }
    tabular: dict[str, Any] = {"table": TABLES, "allowed_actions": ALLOWED, "hold_spins": True}
    tabular |= {key: value for key, value in options.items() if key != "subtasks"}
    subtasks = options.get("subtasks", tracker.arrays())
    counters = batch.simulator.run(
        steps,
        mazesim.TabularSettings(**tabular),
        batch.observations,
        batch.poses,
        batch.colliding,
        batch.crossings,
        settings=mazesim.RunSettings(subtasks=subtasks, trace=trace),
    )
    return trace, counters


def run_in_python(
    batch: RobotBatch, tracker: SubTaskTracker, steps: int = STEPS
) -> tuple[dict[str, npt.NDArray[Any]], int]:
    """The lower level of ``HierarchicalPolicy.act`` step by step (no checkpoint events)."""
    n = batch.num_envs
    actions = np.zeros((steps, n), dtype=np.int32)
    poses = np.zeros((steps, n, 3), dtype=np.float32)
    previous = np.full(n, -1, dtype=np.int64)
    ends = 0
    for step in range(steps):
        if step > 0:
            done, gave_up = tracker.update(batch.poses)
            ends += int(np.count_nonzero(done | gave_up))
            tracker.begin(done | gave_up, SubTask.CORRIDOR, batch.poses)
        subtask = tracker.subtask
        state = tracker.states(observation_states(batch.observations))
        action = best_allowed(LOWER_Q[subtask, state], SUBTASK_ACTIONS[subtask])
        action = hold_spins(action, previous, subtask == SubTask.CORRIDOR)
        previous = action
        batch.step(action)
        actions[step] = action
        poses[step] = batch.poses
    return {"actions": actions, "poses": poses}, ends


def assert_same_tracker(mine: SubTaskTracker, theirs: SubTaskTracker) -> None:
    for (name, a), b in zip(mine.arrays().items(), theirs.arrays().values()):
        np.testing.assert_array_equal(a, b, err_msg=name, strict=True)


def test_door_sub_tasks_in_the_core_equal_the_lower_level_in_python() -> None:
    worlds = list(range(12))
    fast_batch, fast = robots_in_doors(worlds, threads=2)
    start = fast.subtask.copy()
    trace, counters = run_in_core(fast_batch, fast)
    slow_batch, slow = robots_in_doors(worlds)
    stepped, ends = run_in_python(slow_batch, slow)
    np.testing.assert_array_equal(trace["actions"], stepped["actions"])
    np.testing.assert_array_equal(trace["poses"], stepped["poses"])
    assert_same_tracker(fast, slow)
    ended = counters["subtasks_done"] + counters["subtasks_given_up"]
    assert int(ended.sum()) == ends
    # Every door sub-task ended within the one call (it gives up after 200 steps), some done,
    # some given up, and Corridors and Corners took over.
    assert set(start.tolist()) == {0, 1, 2, 3}
    assert np.all(ended[start != SubTask.CORRIDOR] >= 1)
    assert np.all(ended[start == SubTask.CORRIDOR] == 0)
    assert counters["subtasks_done"].sum() > 0 and counters["subtasks_given_up"].sum() > 0
    assert np.all(fast.subtask == SubTask.CORRIDOR)
    assert counters["steps"].tolist() == [STEPS] * len(worlds)


def test_a_robot_alone_or_in_calls_split_goes_as_in_the_batch() -> None:
    worlds = list(range(6))
    together, tracker = robots_in_doors(worlds, threads=2)
    trace, _ = run_in_core(together, tracker)
    alone, alone_tracker = robots_in_doors([3])
    first, _ = run_in_core(alone, alone_tracker, steps=100)
    # The navigator follows the last step of a call before the next (``act`` does).
    done, gave_up = alone_tracker.update(alone.poses)
    alone_tracker.begin(done | gave_up, SubTask.CORRIDOR, alone.poses)
    second, _ = run_in_core(alone, alone_tracker, steps=STEPS - 100)
    poses = np.concatenate([first["poses"], second["poses"]])
    np.testing.assert_array_equal(poses[:, 0], trace["poses"][:, 3])
    for (name, mine), theirs in zip(alone_tracker.arrays().items(), tracker.arrays().values()):
        np.testing.assert_array_equal(mine[0], theirs[3], err_msg=name)


def corrupt(name: str, value: Any) -> Any:
    def change(arrays: dict[str, Any]) -> None:
        arrays[name] = value(arrays[name])

    return change


@pytest.mark.parametrize(
    ("change", "match"),
    [
        (corrupt("subtask", lambda a: a.astype(np.int32)), "subtask.*int64"),
        (corrupt("start", lambda a: a[:, :2].copy()), "start.*shape"),
        (
            corrupt("heading_change", lambda a: np.full_like(a, np.nan)),
            "heading_change, found NaN for environment 0",
        ),
        (corrupt("phase", lambda a: np.full_like(a, 5)), "phases in 0"),
        (corrupt("subtask", lambda a: np.full_like(a, 7)), "sub-task numbers"),
        (corrupt("steps", lambda a: np.full_like(a, -1)), "at least 0"),
        (lambda arrays: arrays.pop("turn_point"), 'no "turn_point"'),
        (lambda arrays: arrays.update(odometer=np.zeros(2)), "keys"),
    ],
)
def test_bad_sub_task_arrays_are_refused_before_anything_moves(change: Any, match: str) -> None:
    batch, tracker = robots_in_doors([0, 1])
    arrays = tracker.arrays()
    change(arrays)
    start = batch.poses.copy()
    with pytest.raises(mazesim.InvalidArgumentError, match=match):
        run_in_core(batch, tracker, 5, subtasks=arrays)
    np.testing.assert_array_equal(batch.poses, start)


def test_a_step_count_at_its_largest_stays_there() -> None:
    batch, tracker = robots_in_doors([0, 1])
    largest = np.iinfo(np.int64).max
    tracker.subtask[0] = SubTask.CORRIDOR  # counts on without an end
    tracker.steps[:] = largest
    _, counters = run_in_core(batch, tracker, 3)
    assert int(counters["subtasks_given_up"].sum()) == 1  # the door sub-task is out of steps
    assert tracker.steps[0] == largest


@pytest.mark.parametrize(
    ("options", "match"),
    [
        ({"table": TABLES[0], "allowed_actions": ALLOWED[0]}, "stacked tables"),
        ({"table": TABLES[:4], "allowed_actions": ALLOWED[:4]}, "found 4 tables"),
        ({"table_index": np.zeros(2, dtype=np.int64)}, "table_index"),
        ({"subtasks": [1, 2]}, "dict"),
    ],
)
def test_sub_tasks_need_the_stacked_tables(options: dict[str, Any], match: str) -> None:
    batch, tracker = robots_in_doors([0, 1])
    with pytest.raises(mazesim.MazesimError, match=match):
        run_in_core(batch, tracker, **options)
    with pytest.raises(mazesim.InvalidArgumentError, match="tabular controller with subtasks"):
        batch.simulator.run(
            5,
            "random",
            batch.observations,
            batch.poses,
            batch.colliding,
            batch.crossings,
            settings=mazesim.RunSettings(subtasks=tracker.arrays()),
        )
