"""The core's navigator (``mazesim._core.Navigator``, which ``HierarchicalPolicy`` steps) against
the numpy reference of ``tests/navigator_oracle.py``, step for step, bit for bit."""

from __future__ import annotations

import numpy as np
import pytest

from mazesim._core import Navigator
from mazesim.learn.discretise import NUM_STATES, distance_levels
from mazesim.learn.lower import lower_table_shape
from mazesim.learn.qlearning import best_allowed
from mazesim.learn.subtasks import BLIND_STATE, SUBTASK_ACTIONS, SubTask
from navigator_oracle import SubTaskTracker, hold_actions, hold_spins

PLACE = 4 ** np.arange(6)


@pytest.mark.parametrize(("door_distance", "hold_heading"), [(False, False), (True, True)])
def test_the_core_navigator_steps_as_the_numpy_reference(
    door_distance: bool, hold_heading: bool
) -> None:
    rng = np.random.default_rng(3)
    robots, steps = 48, 400
    q = rng.normal(size=lower_table_shape(door_distance))
    navigator = Navigator(q, robots, hold_heading)
    tracker = SubTaskTracker(robots, door_distance)
    previous = np.full(robots, -1)
    poses = np.zeros((robots, 3))
    navigator.reset(np.arange(robots), poses)
    tracker.begin(np.ones(robots, bool), SubTask.CORRIDOR, poses)
    ends = 0
    for _ in range(steps):
        # A random walk of the odometry, sometimes blind, sometimes a sub-task chosen.
        poses[:, :2] += rng.normal(0.0, 0.01, (robots, 2))
        poses[:, 2] += rng.normal(0.0, 0.08, robots)
        distances = np.where(rng.random((robots, 6)) < 0.6, 40.0, rng.uniform(3, 30, (robots, 6)))
        chosen = np.where(rng.random(robots) < 0.03, rng.integers(0, 4, robots), -1)
        got = navigator.decide(distances, poses, chosen)

        levels = distance_levels(distances)
        state = levels @ PLACE
        done, gave_up = tracker.update(poses)
        tracker.begin(done | gave_up, SubTask.CORRIDOR, poses)
        tracker.begin(chosen >= 0, chosen, poses)
        subtask = tracker.subtask
        action = best_allowed(q[subtask, tracker.states(state)], SUBTASK_ACTIONS[subtask])
        action = hold_spins(action, previous, subtask == SubTask.CORRIDOR)
        if hold_heading:
            blind = (subtask == SubTask.CORRIDOR) & (state == BLIND_STATE)
            action = np.where(blind, hold_actions(poses[:, 2], previous), action)
        previous = action
        ends += int(np.count_nonzero(done | gave_up))
        np.testing.assert_array_equal(got["levels"], levels)
        np.testing.assert_array_equal(got["state"], state)
        np.testing.assert_array_equal(got["ended"], done | gave_up)
        np.testing.assert_array_equal(got["subtask"], subtask)
        np.testing.assert_array_equal(got["phase"], tracker.phase)
        np.testing.assert_array_equal(got["action"], action)
        assert got["state"].max() < NUM_STATES
    assert ends > 0, "expected door sub-tasks to end"
