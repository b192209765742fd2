"""The lower level's Q-learning runs in the core, one call per round, and gives the tables of the
round stepped from Python bit for bit, whatever the thread count: for robots of one batch and
for fleets of several sensor sets alike."""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
import pytest

from lower_oracle import stepwise_round
from mazesim import (
    BatchSimulator,
    DrivePerturbation,
    RobotProfile,
    SensingPerturbation,
    World,
)
from mazesim._core import LowerRoundSettings, train_lower_round
from mazesim.batch import RobotBatch
from mazesim.errors import InvalidArgumentError, MazesimError
from mazesim.learn.fleet import FleetBatch
from mazesim.learn.lower import (
    STARTS_PER_ROUND,
    LowerSettings,
    LowerTrainer,
    draw_exploration,
    draw_starts,
)
from mazesim.learn.subtasks import BLIND_STATE
from mazesim.transfer.randomise import parse_spec, robot_draw

SMALL = LowerSettings(num_envs=120, total_steps=120 * 200 * 2, round_steps=200, maze_pool=12)


def _rounds(trainer: LowerTrainer, stepwise: bool) -> list[object]:
    rounds = range(trainer.settings.rounds)
    if stepwise:
        return [stepwise_round(trainer, k) for k in rounds]
    return [trainer.run_round(k) for k in rounds]


def _same_trainers(first: LowerTrainer, second: LowerTrainer) -> None:
    assert np.array_equal(first.tables.q, second.tables.q)
    assert np.array_equal(first.tables.visits, second.tables.visits)
    assert isinstance(first.batch, RobotBatch) and isinstance(second.batch, RobotBatch)
    assert np.array_equal(first.batch.poses, second.batch.poses)
    assert np.array_equal(first.batch.observations, second.batch.observations)
    assert np.array_equal(first.batch.world_of_env, second.batch.world_of_env)


def _same_fleets(first: LowerTrainer, second: LowerTrainer) -> None:
    assert np.array_equal(first.tables.q, second.tables.q)
    assert np.array_equal(first.tables.visits, second.tables.visits)
    assert isinstance(first.batch, FleetBatch) and isinstance(second.batch, FleetBatch)
    for (one, members, _), (other, again, _) in zip(first.batch.crews(), second.batch.crews()):
        assert np.array_equal(members, again)
        assert np.array_equal(one.poses, other.poses)
        assert np.array_equal(one.observations, other.observations)
        assert np.array_equal(one.world_of_env, other.world_of_env)


@pytest.mark.parametrize("threads", [1, 2])
def test_a_round_in_the_core_is_the_round_stepped_from_python(threads: int) -> None:
    stepwise = LowerTrainer(SMALL, threads=1)
    in_core = LowerTrainer(SMALL, threads=threads)
    assert _rounds(stepwise, True) == _rounds(in_core, False)
    _same_trainers(stepwise, in_core)
    # The round learned something, and Corridors and Corners never tried its forbidden action.
    assert in_core.tables.visits.sum() > 0
    assert in_core.tables.visits[0, :, 11].sum() == 0


def test_randomised_robots_learn_in_the_core_as_stepped_from_python() -> None:
    spec = parse_spec("wheel_radius=0.9:1.1,ir_angle=-10:10,wall_reflectance=0.3:1,slip=0:0.5")
    draw = robot_draw(spec, 3)
    stepwise = LowerTrainer(SMALL, threads=2, robot=draw(0, SMALL.num_envs))
    in_core = LowerTrainer(SMALL, threads=2, robot=draw(0, SMALL.num_envs))
    assert stepwise_round(stepwise, 0) == in_core.run_round(0)
    _same_trainers(stepwise, in_core)


def _robots_of_two_motor_limits(count: int) -> list[RobotProfile]:
    """Seed robots, a third of them slower, and half of the others at dark walls (blind in many
    places)."""
    seed = RobotProfile.builtin("seed")
    slower = RobotProfile.from_toml(
        seed.to_toml().replace("max_wheel_speed = 6.28", "max_wheel_speed = 5.0")
    )
    dark = seed.perturbed(
        drive=DrivePerturbation(motor_gains=(0.95, 1.0)),
        sensing=SensingPerturbation(wall_reflectance=0.2),
    )
    return [slower if i % 3 == 1 else dark if i % 2 else seed for i in range(count)]


@pytest.mark.parametrize(
    "options",
    [
        {"door_distance": True},
        {"blind_forward": True},
        {"door_distance": True, "blind_forward": True, "hold_heading": True},
    ],
)
def test_the_navigator_options_learn_in_the_core_as_stepped_from_python(
    options: dict[str, bool],
) -> None:
    # The randomised navigator's options, with robots of two motor limits.
    settings = dataclasses.replace(SMALL, **options)
    robots = _robots_of_two_motor_limits(SMALL.num_envs)
    stepwise = LowerTrainer(settings, threads=1, robot=robots)
    in_core = LowerTrainer(settings, threads=2, robot=robots)
    assert len({robot.max_wheel_speed for robot in robots}) == 2
    assert stepwise_round(stepwise, 0) == in_core.run_round(0)
    _same_trainers(stepwise, in_core)
    assert in_core.tables.visits[0, BLIND_STATE].sum() > 0
    if settings.door_distance:
        # Door sub-tasks learned in phases past the first distance bin (phase 3 and beyond).
        assert in_core.tables.visits[1:, 3 * 4096 :].sum() > 0


@pytest.mark.parametrize(
    ("robots", "options"),
    [
        ("seed|e-puck2", {}),
        ("seed|e-puck|alphabot2", {"door_distance": True, "blind_forward": True}),
        ("e-puck|seed|e-puck-hardware", {"blind_forward": True, "hold_heading": True}),
    ],
)
def test_fleets_of_other_sensors_learn_in_the_core_as_stepped_from_python(
    robots: str, options: dict[str, bool]
) -> None:
    # Each group's readings reach the tables through the core's map into seed volts.
    settings = dataclasses.replace(SMALL, **options)
    draw = robot_draw(parse_spec(f"robot={robots},wheel_radius=0.95:1.05"), 1)
    stepwise = LowerTrainer(settings, threads=1, robot=draw(0, SMALL.num_envs))
    in_core = LowerTrainer(settings, threads=2, robot=draw(0, SMALL.num_envs))
    assert isinstance(in_core.batch, FleetBatch) and len(in_core.batch.crews()) == 3 - (
        robots == "seed|e-puck2"
    )
    assert stepwise_round(stepwise, 0) == in_core.run_round(0)
    _same_fleets(stepwise, in_core)
    assert in_core.tables.visits.sum() > 0


def test_a_round_draws_only_from_its_own_stream() -> None:
    trainer = LowerTrainer(SMALL, threads=1)
    starts, exploration = trainer.draws(1)
    again_starts, again_exploration = trainer.draws(1)
    assert np.array_equal(starts.pose, again_starts.pose)
    assert np.array_equal(exploration.uniform, again_exploration.uniform)
    other, _ = trainer.draws(2)
    assert not np.array_equal(starts.pose, other.pose)


def test_episode_starts_are_where_their_sub_task_begins() -> None:
    trainer = LowerTrainer(SMALL, threads=1)
    rng = np.random.default_rng(4)
    starts = draw_starts(rng, trainer.role, trainer.start_tables)
    assert starts.world.shape == (SMALL.num_envs, STARTS_PER_ROUND)
    door = trainer.role != 0
    # Door sub-tasks start on their path's first leg, facing along it, short of the door.
    path = starts.path[door]
    heading_in = path[..., 4:6]
    facing = np.stack([np.cos(starts.pose[door][..., 2]), np.sin(starts.pose[door][..., 2])], -1)
    assert np.all(np.einsum("...i,...i->...", heading_in, facing) > np.cos(0.21))
    assert np.allclose(path[..., 0:2], starts.pose[door][..., :2])
    assert np.all((path[..., 8] > 0.15) & (path[..., 8] < 0.3))
    # Corridors and Corners carries no path; every start lies inside its maze.
    assert np.all(starts.path[~door] == 0.0)
    assert np.all((starts.pose[..., :2] > 0.0) & (starts.pose[..., :2] < 1.3))
    assert starts.world.min() >= 0 and starts.world.max() < SMALL.maze_pool
    actions = draw_exploration(rng, trainer.role, 50).action
    assert actions[:, trainer.role == 0].max() < 11 and actions[:, door].max() == 11


def _round_arguments(trainer: LowerTrainer) -> dict[str, object]:
    starts, exploration = trainer.draws(0)
    batch = trainer.batch
    core_settings = trainer._core_settings(0.1)
    from mazesim.learn.subtasks import SUBTASK_ACTIONS

    return {
        "worlds": batch.worlds,  # type: ignore[union-attr]
        "role": trainer.role,
        "starts": starts.as_dict(),
        "explore": exploration.uniform[:5],
        "random_action": exploration.action[:5],
        "q": trainer.tables.q,
        "visits": trainer.tables.visits,
        "allowed": SUBTASK_ACTIONS,
        "settings": core_settings,
    }


def _two_robots_batch() -> BatchSimulator:
    """A batch of worlds of two robots, whose robots no crew drives."""
    world = World.from_toml(
        'format = "mazesim-world"\nversion = 1\n[[robots]]\nname = "a"\nx = 0.0\ny = 0.0\n'
        '[[robots]]\nname = "b"\nx = 0.3\ny = 0.0\n'
    )
    return BatchSimulator(world, num_envs=SMALL.num_envs)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda a: a.update(q=np.zeros((4, 10, 12))), "q"),
        (lambda a: a.update(q=np.full_like(a["q"], np.inf)), "finite Q"),
        (lambda a: a.update(visits=np.full_like(a["visits"], -1)), "visit counts"),
        (lambda a: a.update(explore=np.full_like(a["explore"], np.nan)), "finite"),
        (lambda a: a.update(random_action=np.full_like(a["random_action"], 12)), "exploring"),
        # Corridors and Corners (robot 0) may not explore `99` (action 11).
        (lambda a: a["random_action"].__setitem__((2, 0), 11), "robot 0 .*step 2"),
        (lambda a: a["starts"].update(world=np.full_like(a["starts"]["world"], 99)), "world"),
        (lambda a: a["starts"].update(pose=a["starts"]["pose"][:, :3]), "pose"),
        (lambda a: a["starts"].update(world=a["starts"]["world"][:, :0]), r"K\) int64 .*K >= 1"),
        (lambda a: a.update(explore=a["explore"][:, :3]), r"explore to be a \(steps, N="),
        (lambda a: a["settings"].pop("gamma"), "gamma"),
        (lambda a: a["settings"].update(gamma=1.5), "gamma"),
        (lambda a: a["settings"].update(decision_steps=0), "decision_steps"),
        (lambda a: a["settings"].update(extra=1.0), "extra"),
        (lambda a: a.update(worlds=[1, 2]), "World"),
        (lambda a: a.update(role=np.full(SMALL.num_envs, 7)), "sub-tasks"),
        (lambda a: a["crews"][0].update(members=np.zeros(SMALL.num_envs, np.int64)), "increasing"),
        (lambda a: a["crews"][0].update(members=np.full(SMALL.num_envs, 999)), "members"),
        (
            lambda a: a["crews"][0].update(wheel_speeds=np.full((12, 2), np.nan, np.float32)),
            "wheel",
        ),
        (lambda a: a["crews"].append(dict(a["crews"][0])), "crew 1's twice"),
        (lambda a: a["crews"][0].update(readings={"far": 0.4}), "directions"),
        (lambda a: a["crews"][0].update(extra=1), "each of crews to hold only"),
        (lambda a: a["crews"][0].update(world_of_env=np.full(SMALL.num_envs, 99)), "world"),
        (lambda a: a["crews"][0].update(simulator=_two_robots_batch()), "with one robot each"),
    ],
)
def test_bad_round_arguments_are_refused_before_anything_moves(change, message) -> None:
    trainer = LowerTrainer(SMALL, threads=1)
    arguments = _round_arguments(trainer)
    q_before = trainer.tables.q.copy()
    arguments["crews"] = trainer._crews()
    change(arguments)
    with pytest.raises(InvalidArgumentError, match=message) as raised:
        _train_round(arguments)
    assert isinstance(raised.value, MazesimError)
    assert np.array_equal(trainer.tables.q, q_before)


def _train_round(arguments: dict[str, Any]) -> dict[str, Any]:
    """``train_lower_round`` of ``_round_arguments`` (with crews), its settings made first."""
    settings = LowerRoundSettings(
        arguments["settings"],
        arguments["worlds"],
        arguments["role"],
        arguments["allowed"],
    )
    return train_lower_round(
        arguments["crews"],
        settings,
        arguments["starts"],
        arguments["explore"],
        arguments["random_action"],
        arguments["q"],
        arguments["visits"],
    )


def test_former_keywords_warn_and_train_as_the_settings_do() -> None:
    runs = []
    for former in (False, True):
        trainer = LowerTrainer(SMALL, threads=1)
        arguments = _round_arguments(trainer)
        arguments["crews"] = trainer._crews()
        if former:
            with pytest.warns(DeprecationWarning, match="train_lower_round's keyword .* is dep"):
                counts = train_lower_round(**arguments)  # type: ignore[call-arg]
        else:
            counts = _train_round(arguments)
        runs.append((counts, trainer.tables.q.copy(), trainer.tables.visits.copy()))
    (counts, q, visits), (old_counts, old_q, old_visits) = runs
    assert counts == old_counts
    np.testing.assert_array_equal(q, old_q)
    np.testing.assert_array_equal(visits, old_visits)
    assert visits.sum() > 0
    settings = LowerRoundSettings(
        *(arguments[k] for k in ("settings", "worlds", "role", "allowed"))
    )
    assert repr(settings) == (
        f"LowerRoundSettings(robots={SMALL.num_envs}, worlds={len(arguments['worlds'])}, "
        f"gamma={arguments['settings']['gamma']!r}, epsilon=0.1)"
    )
    assert settings.role is arguments["role"] and settings.learning is arguments["settings"]
    with pytest.raises(InvalidArgumentError, match="either a LowerRoundSettings or"):
        train_lower_round(arguments["crews"], settings, worlds=arguments["worlds"])  # type: ignore[call-arg]
    with pytest.raises(InvalidArgumentError, match="missing required argument: 'q'"):
        train_lower_round(arguments["crews"], settings, {}, 0, 0)  # type: ignore[call-arg]
    with pytest.raises(InvalidArgumentError, match="expected settings to be a LowerRoundSettings"):
        train_lower_round(arguments["crews"], arguments["settings"], {}, 0, 0, 0, 0)  # type: ignore[arg-type]
