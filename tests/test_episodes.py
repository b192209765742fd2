"""The episode layer: jittered starts from named streams, the step limit, the goal test."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt
import pytest

import mazesim
from mazesim.episodes import MAX_STEPS, EpisodeBatch, StartJitter, run_episodes


class _Forward:
    """A navigator that always drives straight on (action 0)."""

    def reset(self, envs: npt.ArrayLike, poses: npt.ArrayLike) -> None:
        pass

    def act(
        self, observations: npt.ArrayLike, poses: npt.ArrayLike, events: npt.ArrayLike
    ) -> npt.NDArray[np.int64]:
        return np.zeros(np.asarray(observations).shape[0], dtype=np.int64)


def _starts(stream: str, robots: int, episodes: list[int]) -> npt.NDArray[np.float32]:
    nav = EpisodeBatch([mazesim.load_world("seed-maze")], num_envs=robots, stream=stream)
    nav.start(np.arange(len(episodes)), episodes)
    return nav.poses[: len(episodes)].copy()


def test_an_episode_starts_alike_whatever_its_company() -> None:
    alone = _starts("evaluate/episode", 1, [5])
    together = _starts("evaluate/episode", 4, [3, 4, 5, 6])
    assert np.array_equal(alone[0], together[2])
    assert not np.array_equal(together[0], together[1])


def test_training_and_evaluation_episodes_start_differently() -> None:
    assert not np.array_equal(
        _starts("higher/episode", 2, [0, 1]), _starts("evaluate/episode", 2, [0, 1])
    )


def test_the_step_limit_ends_an_episode_unfinished() -> None:
    assert MAX_STEPS == 4000
    world = mazesim.load_world("seed-maze")
    nav = EpisodeBatch([world], num_envs=2, max_steps=30, jitter=StartJitter(0.0, 0.0))
    results = run_episodes(nav, _Forward(), 3)
    assert [r.episode for r in results] == [0, 1, 2]
    assert all(not r.arrived and r.steps == 30 for r in results)
    assert all(r.contact_steps <= r.steps for r in results)


def test_the_goal_test_ends_an_episode_on_arrival() -> None:
    world = mazesim.load_world("seed-maze")
    goal_x, goal_y, _ = world.goal
    nav = EpisodeBatch([world], num_envs=1, jitter=StartJitter(0.0, 0.0))
    nav.start([0], [0])
    nav.batch.place([0], [(goal_x, goal_y, 0.0)], [1])
    arrived, out_of_time = nav.step([0])
    assert arrived[0] and not out_of_time[0]


def test_episodes_run_on_the_robot_given() -> None:
    world = mazesim.load_world("seed-maze")
    smaller = mazesim.RobotProfile.builtin("seed").perturbed(
        drive=mazesim.DrivePerturbation(wheel_radius_scale=0.9)
    )
    travelled = []
    for robot in ("seed", smaller):
        nav = EpisodeBatch([world], num_envs=1, jitter=StartJitter(0.0, 0.0), robot=robot)
        assert nav.robot.name == (robot if isinstance(robot, str) else robot.name)
        nav.start([0], [0])
        x, y, _ = nav.poses[0].copy()
        for _ in range(5):
            nav.step([0])
        travelled.append(float(np.hypot(nav.poses[0, 0] - x, nav.poses[0, 1] - y)))
    assert travelled[1] / travelled[0] == pytest.approx(0.9, rel=1e-3)
