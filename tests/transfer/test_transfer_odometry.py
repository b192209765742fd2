"""The study's wheel-encoder odometry: it follows the nominal robot, and each perturbation of the
wheels misleads it as a real robot's would be misled (or not)."""

from __future__ import annotations

import json
import math

import numpy as np
import numpy.typing as npt
import pytest

from mazesim import RobotProfile, load_world
from mazesim.actions import action_index
from mazesim.errors import InvalidArgumentError, UnknownNameError
from mazesim.learn.tables import load_policy
from mazesim.odometry import advance, wrap_angle
from mazesim.transfer import StudyOptions, check_study_json, parse_axes, run_study
from mazesim.transfer.axes import Setting
from mazesim.transfer.cells import CellRun
from mazesim.transfer.odometry import EncoderOdometryNavigator

FORWARD = action_index("00")
SPIN = action_index("aa")  # on the spot


class Scripted:
    """A navigator that plays one action for every robot and remembers the poses it was given."""

    def __init__(self, action: int) -> None:
        self.action = action
        self.started: npt.NDArray[np.float64] | None = None
        self.seen: list[npt.NDArray[np.float64]] = []

    def reset(self, envs: npt.ArrayLike, poses: npt.ArrayLike) -> None:
        self.started = np.array(poses, dtype=np.float64)[np.asarray(envs)]

    def act(
        self, observations: npt.ArrayLike, poses: npt.ArrayLike, events: npt.ArrayLike
    ) -> npt.NDArray[np.int64]:
        rows = np.array(poses, dtype=np.float64)
        self.seen.append(rows)
        return np.full(rows.shape[0], self.action, dtype=np.int64)


def _drive(
    run: CellRun,
    settings: list[Setting],
    action: int,
    steps: int,
    yaw: float | None = None,
    robot: str = "seed",
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Drives each cell's robots (of profile ``robot``) with one action for ``steps`` steps (from
    the world's start, turned to ``yaw`` if given), the navigator behind encoder odometry with
    that profile's nominal numbers; returns each cell's first robot's (start, true end, believed
    end) poses."""
    nav = run.batch(robot, settings)
    robots = np.arange(nav.num_envs)
    nav.start(robots, np.zeros(nav.num_envs, dtype=np.int64))
    if yaw is not None:
        x, y, _ = run.world.start
        nav.batch.place(robots, np.tile([x, y, yaw], (nav.num_envs, 1)), np.zeros(nav.num_envs))
    start = nav.poses.astype(np.float64).copy()
    nominal = RobotProfile.builtin(robot)
    scripted = Scripted(action)
    odometry = EncoderOdometryNavigator(
        scripted, nav.batch.simulator.encoders, nominal.wheel_radius, nominal.axle_length
    )
    odometry.reset(np.arange(nav.num_envs), nav.poses)
    assert scripted.started is not None
    np.testing.assert_allclose(scripted.started, start)  # it starts from the true pose
    events = np.zeros(nav.num_envs, dtype=np.int64)
    for _ in range(steps):
        nav.step(odometry.act(nav.observations, nav.poses, events))
    odometry.act(nav.observations, nav.poses, events)  # takes in the last step's rotation
    first = np.searchsorted(nav.world_of_env, np.arange(len(settings)))
    believed = scripted.seen[-1]
    return start[first], nav.poses.astype(np.float64)[first], believed[first]


def test_advance_drives_straight_turns_on_the_spot_and_closes_a_circle() -> None:
    pose = np.array([[0.0, 0.0, 0.0], [1.0, 2.0, math.pi / 2], [0.0, 0.0, 0.0]])
    advance(pose, [0.1, 0.05, -0.02], [0.1, 0.05, 0.02], axle_length=0.08)
    np.testing.assert_allclose(pose[0], [0.1, 0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(pose[1], [1.0, 2.05, math.pi / 2], atol=1e-12)
    np.testing.assert_allclose(pose[2], [0.0, 0.0, 0.5], atol=1e-12)
    # An arc of wheel travels (l, r) driven in 400 small steps comes round to where it began.
    circle = np.zeros((1, 3))
    axle, left, right = 0.1, 0.3, 0.5
    turns = (right - left) / axle / (2.0 * math.pi)
    steps = 400
    for _ in range(steps):
        advance(circle, [left / turns / steps], [right / turns / steps], axle)
    np.testing.assert_allclose(circle[0], [0.0, 0.0, 0.0], atol=1e-9)
    assert wrap_angle(math.pi) == pytest.approx(-math.pi)


@pytest.mark.parametrize(
    ("left", "right", "axle", "words"),
    [
        (math.nan, 0.01, 0.05, "finite wheel travels in metres, found nan"),
        (math.inf, math.inf, 0.05, "finite wheel travels in metres, found inf"),
        (0.01, 0.02, 0.0, "an axle length of more than 0 m, found 0.0"),
    ],
)
def test_advance_refuses_a_travel_that_is_not_finite_before_any_pose_moves(
    left: float, right: float, axle: float, words: str
) -> None:
    pose = np.array([[0.1, 0.2, 0.3], [0.4, 0.5, 0.6]])
    with pytest.raises(InvalidArgumentError, match=words):
        advance(pose, [0.01, left], [0.01, right], axle)
    # Once, x and y of every robot had moved (to NaN for the bad one) before the yaw refused.
    assert pose.tolist() == [[0.1, 0.2, 0.3], [0.4, 0.5, 0.6]]


@pytest.mark.parametrize("robot", ["seed", "e-puck", "e-puck2", "alphabot2"])
def test_on_a_nominal_robot_the_encoders_follow_the_true_pose(run: CellRun, robot: str) -> None:
    # Each profile's own wheels, axle and encoder resolution (the e-puck's steps of 2 pi / 1000).
    cell = [Setting() if robot == "seed" else Setting.of({"robot": robot})]
    for action, steps in ((FORWARD, 25), (SPIN, 15), (action_index("11"), 25)):
        start, true, believed = _drive(run, cell, action, steps, robot=robot)
        assert np.hypot(*(true[0, :2] - start[0, :2])) + abs(true[0, 2] - start[0, 2]) > 0.02
        assert np.hypot(*(believed[0, :2] - true[0, :2])) < 0.002
        assert abs(wrap_angle(believed[0, 2] - true[0, 2])) < math.radians(0.5)


def test_a_wheel_five_percent_larger_drives_five_percent_further_than_believed(
    run: CellRun,
) -> None:
    cells = [Setting.of({"wheel_radius": 1.05}), Setting.of({"wheel_radius": 0.95})]
    start, true, believed = _drive(run, cells, FORWARD, 20)
    travelled = np.hypot(*(true[:, :2] - start[:, :2]).T)
    thought = np.hypot(*(believed[:, :2] - start[:, :2]).T)
    assert travelled[0] > 0.03
    assert thought / travelled == pytest.approx([1 / 1.05, 1 / 0.95], rel=0.01)


def test_an_axle_five_percent_wider_turns_less_than_believed_on_the_spot(run: CellRun) -> None:
    cells = [Setting.of({"axle_length": 1.05}), Setting.of({"axle_length": 0.95})]
    start, true, believed = _drive(run, cells, SPIN, 10)
    turned = wrap_angle(true[:, 2] - start[:, 2])
    thought = wrap_angle(believed[:, 2] - start[:, 2])
    assert abs(turned[0]) > 0.3
    assert thought / turned == pytest.approx([1.05, 0.95], rel=0.01)


def test_the_encoders_see_a_weaker_motor(run: CellRun) -> None:
    start, true, believed = _drive(run, [Setting.of({"motor_mismatch": -0.1})], FORWARD, 20)
    turned = wrap_angle(true[0, 2] - start[0, 2])
    assert turned > 0.05  # the robot curves left
    assert abs(wrap_angle(believed[0, 2] - true[0, 2])) < 0.1 * turned


def test_a_robot_pushing_on_a_wall_believes_it_went_on_and_slip_adds_to_it(
    run: CellRun,
) -> None:
    # From seed-maze's start, 60 degrees right of the corridor: into its wall (y = 0), then along.
    cells = [Setting(), Setting.of({"slip": 0.5})]
    start, true, believed = _drive(run, cells, FORWARD, 60, yaw=-math.pi / 3)
    assert np.all(true[:, 1] > 0.03)  # the wall holds both robots
    assert np.all(believed[:, 1] < 0.0)  # both odometries drove through it
    along = believed[:, 0] - true[:, 0]
    assert abs(along[0]) < 0.002  # sliding along the wall, the encoders are right
    assert along[1] > 0.01  # a slipping wheel counts motion that never happened


def _rate(result: object, label: str) -> tuple[float, float | None]:
    cell = next(c for c in result.single if c.setting.label() == label)  # type: ignore[attr-defined]
    return cell.measure.success_rate, cell.measure.mean_steps


def test_the_study_records_its_odometry_and_the_encoders_change_a_wheel_cell() -> None:
    policy = load_policy("randomised")
    world = load_world(policy.world_name)
    options = StudyOptions(
        axes=parse_axes("axle_length"), episodes=4, max_steps=900, events="truth", pairs=False
    )
    encoders = run_study(policy, world, options)
    truth = run_study(policy, world, StudyOptions(**{**options.__dict__, "odometry": "truth"}))
    assert StudyOptions().odometry == "encoders"
    assert encoders.as_json()["odometry"] == "encoders"
    assert truth.as_json()["odometry"] == "truth"
    for result in (encoders, truth):
        check_study_json(json.loads(json.dumps(result.as_json())))
    assert [c.measure for c in encoders.single] != [c.measure for c in truth.single]


def test_odometry_is_checked_in_options_and_json() -> None:
    policy = load_policy(None)
    with pytest.raises(UnknownNameError, match="expected odometry to be one of truth, encoders"):
        StudyOptions(axes=parse_axes("latency"), odometry="gyro")
    options = StudyOptions(axes=parse_axes("latency"), episodes=1, max_steps=50, pairs=False)
    document = run_study(policy, load_world(policy.world_name), options).as_json()
    older = {key: value for key, value in document.items() if key != "odometry"}
    check_study_json(older)  # written before the odometry was a choice
    with pytest.raises(InvalidArgumentError, match="odometry"):
        check_study_json({**document, "odometry": "gyro"})
