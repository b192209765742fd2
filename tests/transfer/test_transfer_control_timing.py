"""The transfer study's control wrappers do what they claim: a latency-k navigator's commands are
the plain one's shifted by k steps, and an unsynchronised node acts only when it wakes."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt
import pytest

from mazesim.barcode.link import UnsyncedLink
from mazesim.errors import InvalidArgumentError
from mazesim.transfer.control_timing import DelayedNavigator, LinkedNavigator


class Scripted:
    """A navigator whose command is a function of its inputs: the step's observation row's first
    value, plus 100 times the event it was handed (so a delivered event shows)."""

    def __init__(self) -> None:
        self.resets: list[list[int]] = []
        self.events: list[npt.NDArray[np.int64]] = []

    def reset(self, envs: npt.ArrayLike, poses: npt.ArrayLike) -> None:
        self.resets.append([int(e) for e in np.asarray(envs)])

    def act(
        self, observations: npt.ArrayLike, poses: npt.ArrayLike, events: npt.ArrayLike
    ) -> npt.NDArray[np.int64]:
        event = np.asarray(events, dtype=np.int64)
        self.events.append(event.copy())
        return np.asarray(observations)[:, 0].astype(np.int64) + 100 * event


def _observations(step: int, robots: int) -> npt.NDArray[np.float32]:
    """Step ``step``'s observations: a distinct command per step and robot."""
    return np.full((robots, 7), 1 + step + 10 * np.arange(robots)[:, None], dtype=np.float32)


def _run(navigator: object, steps: int, robots: int) -> npt.NDArray[np.int64]:
    poses = np.zeros((robots, 3))
    events = np.zeros(robots, dtype=np.int64)
    rows = [navigator.act(_observations(t, robots), poses, events) for t in range(steps)]  # type: ignore[attr-defined]
    return np.array(rows)


@pytest.mark.parametrize("k", [0, 1, 2, 3])
def test_a_latency_k_navigator_acts_as_the_plain_one_k_steps_late(k: int) -> None:
    plain = _run(Scripted(), 12, 2)
    delayed = _run(DelayedNavigator(Scripted(), [k, k]), 12, 2)
    assert np.array_equal(delayed[k:], plain[: 12 - k])
    # Before its first command arrives the robot runs that first command.
    assert np.array_equal(delayed[:k], np.repeat(plain[:1], k, axis=0))


def test_latency_is_per_robot_and_restarts_with_an_episode() -> None:
    navigator = DelayedNavigator(Scripted(), [0, 2])
    plain = _run(Scripted(), 6, 2)
    delayed = _run(navigator, 6, 2)
    assert np.array_equal(delayed[:, 0], plain[:, 0])
    assert np.array_equal(delayed[2:, 1], plain[:4, 1])
    navigator.reset([1], np.zeros((2, 3)))
    after = navigator.act(_observations(50, 2), np.zeros((2, 3)), np.zeros(2, dtype=np.int64))
    # Robot 1 starts afresh: its old commands are gone, it runs its first new one.
    assert after[1] == _observations(50, 2)[1, 0]
    assert navigator.navigator.resets == [[1]]


def test_a_negative_latency_is_refused() -> None:
    refused = "delays as whole numbers from 0 to 4000, found -1"
    with pytest.raises(InvalidArgumentError, match=refused):
        DelayedNavigator(Scripted(), [0, -1])


def test_an_unsynced_robot_changes_command_only_when_its_node_wakes() -> None:
    robots, steps, seed = 4, 40, 3
    linked = np.array([True, True, True, False])
    navigator = LinkedNavigator(Scripted(), linked, seed)
    commands = _run(navigator, steps, robots)
    schedule = UnsyncedLink(robots, seed=seed)
    awake = np.array([schedule.tick() for _ in range(steps)])
    plain = _run(Scripted(), steps, robots)
    for robot in range(robots):
        last = None
        for t in range(steps):
            if not linked[robot] or awake[t, robot] or t == 0:
                assert commands[t, robot] == plain[t, robot]
                last = plain[t, robot]
            else:
                assert commands[t, robot] == last
    # Linked nodes did sleep through some steps, so the model changed something.
    assert (commands[:, :3] != plain[:, :3]).any()
    assert np.array_equal(commands[:, 3], plain[:, 3])


def test_an_event_while_the_node_sleeps_arrives_at_its_wake_up() -> None:
    inner = Scripted()
    navigator = LinkedNavigator(inner, [True], seed=5)
    schedule = UnsyncedLink(1, seed=5)
    awake = [bool(schedule.tick()[0]) for _ in range(30)]
    asleep = next(t for t in range(1, 30) if not awake[t])
    poses = np.zeros((1, 3))
    for t in range(30):
        event = np.array([7 if t == asleep else 0])
        navigator.act(_observations(t, 1), poses, event)
    handed = [int(e[0]) for e in inner.events]
    woke = next(t for t in range(asleep, 30) if awake[t])
    assert handed[asleep] == 0
    assert handed[woke] == 7
    assert handed.count(7) == 1
