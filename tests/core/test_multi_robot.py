"""Several robots in one world: the world file, the Simulator's robot index, contacts and infra-red
rays between robots, the batch's robot axis and its determinism."""

from __future__ import annotations

import copy
import math
import pickle
from pathlib import Path

import numpy as np
import pytest

import mazesim
from mazesim.controllers import AvoidCollision

#: Reflection factor of a robot's body for the infra-red sensors (docs/multi-robot.md).
ROBOT_REFLECTANCE = 0.38
RADIUS = 0.037


def corridor(gap: float, *, robots: int = 2, extra: str = "") -> mazesim.World:
    """Two e-pucks facing each other across ``gap`` (between their bodies) in a corridor 0.2 m
    wide; with ``robots`` > 2, the others parked along it behind the west one."""
    half = RADIUS + gap / 2
    lines = [
        'format = "mazesim-world"',
        "version = 1",
        "[[walls]]\ncenter = [0.0, 0.105]\nsize = [4.0, 0.01]",
        "[[walls]]\ncenter = [0.0, -0.105]\nsize = [4.0, 0.01]",
        f'[[robots]]\nname = "west"\nx = {-half}\ny = 0.0',
        f'[[robots]]\nname = "east"\nx = {half}\ny = 0.0\nyaw = {math.pi}',
    ]
    for k in range(robots - 2):
        lines.append(f'[[robots]]\nname = "parked{k}"\nx = {-half - 0.1 * (k + 1)}\ny = 0.0')
    return mazesim.World.from_toml("\n".join(lines) + "\n" + extra)


def ray_to_disc(origin: np.ndarray, direction: np.ndarray, centre: np.ndarray) -> float:
    """Distance along a unit ray from ``origin`` to a disc of ``RADIUS`` at ``centre``."""
    m = origin - centre
    b = float(m @ direction)
    c = float(m @ m) - RADIUS**2
    return -b - math.sqrt(b * b - c)


def test_front_sensors_read_the_other_robot_as_the_reflectance_predicts() -> None:
    profile = mazesim.RobotProfile.builtin("e-puck")
    poses = profile.distance_sensor_poses()
    for gap in (0.004, 0.008, 0.012):
        sim = mazesim.Simulator(corridor(gap), noise=False)
        for robot, other in ((0, 1), (1, 0)):
            x, y, yaw = sim.robot_state(robot)["pose"]
            ox, oy, _ = sim.robot_state(other)["pose"]
            readings = sim.distance_sensors(robot_index=robot)
            for sensor in (0, 7):  # ps0 and ps7, the two front sensors
                px, py, heading = poses[sensor]
                c, s = math.cos(yaw), math.sin(yaw)
                origin = np.array([x + c * px - s * py, y + s * px + c * py])
                direction = np.array([math.cos(yaw + heading), math.sin(yaw + heading)])
                expected = ray_to_disc(origin, direction, np.array([ox, oy]))
                # The table read at d / f: a white wall at 1 / 0.38 times the distance.
                seen = ROBOT_REFLECTANCE * profile.distance_from_reading(
                    sensor, float(readings[sensor])
                )
                assert seen == pytest.approx(expected, abs=2e-4), (gap, robot, sensor)
            # The rear sensors see nothing (the last row of the table).
            assert readings[3] == readings[4] == pytest.approx(67.19, abs=0.01)
        # Ground sensors see the floor only: as far from any robot.
        alone = mazesim.Simulator(mazesim.World.builtin("arena"), noise=False)
        assert np.array_equal(sim.ground_sensors(1), alone.ground_sensors())


def test_the_avoid_collision_rule_turns_both_away_before_contact() -> None:
    """Each robot's front sensors see the other in time for the report's rule to start turning
    away while a gap is left; with the shell's reflectance of 0.38 the turn then grazes the other
    robot (docs/multi-robot.md), and the two leave each other behind."""
    sim = mazesim.Simulator(corridor(0.1), noise=False)
    rule = AvoidCollision()
    gap_at_turn: list[float | None] = [None, None]
    touched = 0
    for _ in range(120):
        poses = sim.poses()
        gap = float(np.hypot(*(poses[0, :2] - poses[1, :2]))) - 2 * RADIUS
        commands = np.array([rule(sim.distance_sensors(robot_index=i)) for i in range(2)])
        for i in range(2):
            if commands[i, 0] != commands[i, 1] and gap_at_turn[i] is None:
                gap_at_turn[i] = gap
        sim.step_robots(commands)
        touched += sim.robot_state(0)["touching_robot"]
    assert all(g is not None and g > 0.005 for g in gap_at_turn), gap_at_turn
    assert touched < 20, "a graze, not a push"
    poses = sim.poses()
    assert float(np.hypot(*(poses[0, :2] - poses[1, :2]))) > 2 * RADIUS + 0.01
    # Both turned away from the other: neither heads at it any more.
    assert math.cos(poses[0, 2]) < 0.9 and math.cos(poses[1, 2] - math.pi) < 0.9


def test_no_threshold_of_the_rule_clears_a_head_on_e_puck() -> None:
    """Why the rule grazes (docs/multi-robot.md): ps0 and ps7 meet a head-on e-puck obliquely and
    read nothing of it beyond a gap of about 1.35 cm, less than the 4.4 cm two pivoting e-pucks
    need to clear each other, so the rule touches whatever its threshold."""
    no_hit = 67.19
    near = mazesim.Simulator(corridor(0.013), noise=False).distance_sensors()
    far = mazesim.Simulator(corridor(0.014), noise=False).distance_sensors()
    assert near[0] > no_hit and near[7] > no_hit
    assert far[0] == far[7] == pytest.approx(no_hit, abs=0.01)
    for threshold in (67.5, 70.0, 80.0, 100.0):
        sim = mazesim.Simulator(corridor(0.1), noise=False)
        rule = AvoidCollision(threshold=threshold)
        touched = 0
        for _ in range(120):
            commands = [rule(sim.distance_sensors(robot_index=i)) for i in range(2)]
            sim.step_robots(np.array(commands))
            touched += sim.robot_state(0)["touching_robot"]
        assert 0 < touched < 20, threshold


def head_on_with_the_rule(turn_in_place: bool) -> tuple[float, int, float]:
    """The gap at which the rule first turns, the control steps robot 0 touches robot 1 and the
    smallest gap, for two e-pucks driven at each other by the rule; with ``turn_in_place`` the
    rule's turns (a pivot on the inner wheel) are made as spins on the spot to the same side."""
    sim = mazesim.Simulator(corridor(0.1), noise=False)
    rule = AvoidCollision()
    half = 0.5 * rule.max_speed
    turned_at, touched, closest = math.inf, 0, math.inf
    for _ in range(120):
        poses = sim.poses()
        gap = float(np.hypot(*(poses[0, :2] - poses[1, :2]))) - 2 * RADIUS
        closest = min(closest, gap)
        commands = []
        for i in range(2):
            left, right = rule(sim.distance_sensors(robot_index=i))
            if left != right:
                turned_at = gap if turned_at == math.inf else turned_at
                if turn_in_place:
                    left, right = (half, -half) if left > right else (-half, half)
            commands.append((left, right))
        sim.step_robots(np.array(commands))
        touched += sim.robot_state(0)["touching_robot"]
    return turned_at, touched, closest


def test_the_contact_comes_from_the_rule_s_pivot_not_from_seeing_late() -> None:
    """The report's rule turns by stopping one wheel and driving the other at full speed: a
    pivot on the stopped wheel, which keeps moving the body forward (at 6.3 cm/s at first). The
    same readings with the turns made on the spot keep the robots apart; two e-pucks pivoting at
    each other need a gap of about 4.4 cm (each centre swings on a circle of half the wheel
    distance, 2.84 cm, round its stopped wheel) where the rule sees the other at 1.16 cm."""
    turned_at, touched, _ = head_on_with_the_rule(turn_in_place=False)
    assert turned_at == pytest.approx(0.0116, abs=5e-4) and touched > 0
    turned_at, touched, closest = head_on_with_the_rule(turn_in_place=True)
    assert turned_at == pytest.approx(0.0116, abs=5e-4)
    assert touched == 0 and closest > 0.009
    for gap, touches in ((0.042, True), (0.048, False)):
        sim = mazesim.Simulator(corridor(gap), noise=False)
        contact = 0
        for _ in range(60):
            sim.step_robots(np.array([[6.28, 0.0], [6.28, 0.0]]))  # both pivot to their right
            contact += sim.robot_state(0)["touching_robot"]
        assert (contact > 0) is touches, gap


def test_robots_driven_into_each_other_stop_in_contact() -> None:
    sim = mazesim.Simulator(corridor(0.02))
    for _ in range(40):
        sim.step_robots(np.full((2, 2), 6.0))
    poses = sim.poses()
    gap = np.hypot(*(poses[0, :2] - poses[1, :2])) - 2 * RADIUS
    assert -1e-3 < gap < 1e-3
    for i in range(2):
        state = sim.robot_state(i)
        assert state["touching_robot"] and state["colliding"] and state["collisions"] == 1


def batch_rows(envs: int, threads: int, steps: int = 30) -> list[np.ndarray]:
    """Every buffer of a batch of corridors whose robots meet and press on each other."""
    world = corridor(0.01, robots=3)
    batch = mazesim.BatchSimulator(world, num_envs=envs, seeds=7, threads=threads)
    assert batch.robots_per_env == 3
    obs = np.zeros((envs, 3, batch.observation_width), np.float32)
    poses = np.zeros((envs, 3, 3), np.float32)
    colliding = np.zeros((envs, 3), bool)
    crossings = np.zeros((envs, 3), np.int32)
    batch.reset(obs, poses, colliding, crossings)
    rng = np.random.default_rng(3)
    seen = []
    touching = 0
    for _ in range(steps):
        # The first three environments' actions do not depend on the batch size.
        actions = np.resize(rng.uniform(2.0, 6.0, (3, 3, 2)), (envs, 3, 2)).astype(np.float32)
        batch.step(actions, obs, poses, colliding, crossings)
        touching += int(colliding[:, :2].sum())
        seen.append(np.concatenate([obs[:3].ravel(), poses[:3].ravel(), colliding[:3].ravel()]))
    assert touching > steps, "the robots press on each other"
    return seen


def test_same_seed_same_run_whatever_the_threads_and_batch_size() -> None:
    reference = batch_rows(3, 1)
    for envs, threads in ((3, 2), (40, 1), (40, 2)):
        for a, b in zip(reference, batch_rows(envs, threads)):
            assert np.array_equal(a.view(np.uint8), b.view(np.uint8)), (envs, threads)


def test_the_batch_steps_each_environment_as_a_simulator_does() -> None:
    world = corridor(0.01, robots=3)
    batch = mazesim.BatchSimulator(world, num_envs=2, seeds=[5, 9])
    obs = np.zeros((2, 3, batch.observation_width), np.float32)
    poses = np.zeros((2, 3, 3), np.float32)
    colliding = np.zeros((2, 3), bool)
    crossings = np.zeros((2, 3), np.int32)
    batch.reset(obs, poses, colliding, crossings)
    sim = mazesim.Simulator(world, seed=9)
    for k in range(20):
        actions = np.full((2, 3, 2), 3.0 + k % 3, np.float32)
        batch.step(actions, obs, poses, colliding, crossings)
        sim.step_robots(actions[1].astype(np.float64))
        assert np.array_equal(poses[1], sim.poses())
        for i in range(3):
            assert np.array_equal(obs[1, i, :8], sim.distance_sensors(robot_index=i))


def test_the_avoid_collision_controller_runs_per_robot_in_the_batch() -> None:
    batch = mazesim.BatchSimulator(corridor(0.1), num_envs=4, noise=False)
    obs = np.zeros((4, 2, batch.observation_width), np.float32)
    poses = np.zeros((4, 2, 3), np.float32)
    colliding = np.zeros((4, 2), bool)
    crossings = np.zeros((4, 2), np.int32)
    batch.reset(obs, poses, colliding, crossings)
    counts = batch.run(100, "avoid-collision", obs, poses, colliding, crossings)
    assert counts["steps_in_contact"].shape == (4, 2)
    assert (counts["steps_in_contact"] < 20).all(), "grazes at most"
    assert (np.abs(np.cos(poses[:, :, 2])) < 0.999).any(axis=1).all(), "every pair turned"


def test_a_world_file_of_several_robots_round_trips() -> None:
    world = corridor(0.05, robots=3)
    again = mazesim.World.from_toml(world.to_toml())
    assert again.robots == world.robots
    assert [r["name"] for r in again.robots] == ["west", "east", "parked0"]
    assert again.start == world.robots[0]["start"]
    assert mazesim.Simulator(again).robot_names == ["west", "east", "parked0"]
    # A world of one robot still has one, named "robot".
    assert [r["name"] for r in mazesim.World.builtin("arena").robots] == ["robot"]


def test_bad_worlds_and_robot_indices_are_package_errors() -> None:
    with pytest.raises(mazesim.InvalidArgumentError, match="overlapping robot 1"):
        mazesim.Simulator(corridor(-0.01))
    crowd = "\n".join(f'[[robots]]\nname = "r{k}"\nx = {0.1 * k}\ny = 1.0' for k in range(65))
    with pytest.raises(mazesim.MazesimError, match="at most 64 robots"):
        mazesim.World.from_toml(f'format = "mazesim-world"\nversion = 1\n{crowd}\n')
    twice = '[[robots]]\nname = "a"\nx = 0.0\ny = 0.0\n[[robots]]\nname = "a"\nx = 1.0\ny = 0.0\n'
    with pytest.raises(mazesim.MazesimError, match="unique"):
        mazesim.World.from_toml(f'format = "mazesim-world"\nversion = 1\n{twice}')
    sim = mazesim.Simulator(corridor(0.05))
    with pytest.raises(mazesim.InvalidArgumentError, match="robot index from 0 to 1"):
        sim.distance_sensors(robot_index=2)
    with pytest.raises(mazesim.InvalidArgumentError, match="overlapping"):
        sim.set_pose(0.05, 0.0, 0.0, robot_index=0)
    with pytest.raises(
        mazesim.InvalidArgumentError, match="expected overlap_robots to be a bool, found a str"
    ):
        sim.set_pose(0.05, 0.0, 0.0, robot_index=0, overlap_robots="yes")  # type: ignore[arg-type]
    sim.set_pose(0.05, 0.0, 0.0, robot_index=0, overlap_robots=True)  # as a supervisor may
    assert sim.poses()[0, 0] == pytest.approx(0.05)
    with pytest.raises(mazesim.InvalidArgumentError, match="commands"):
        sim.step_robots(np.zeros((3, 2)))
    with pytest.raises(mazesim.InvalidActionError):
        sim.step_robots(np.array([[np.nan, 0.0], [0.0, 0.0]]))


def test_a_world_naming_a_profile_file_is_told_how_to_give_the_file(tmp_path: Path) -> None:
    # A world names built-in profiles only; the message says where a profile file goes instead.
    mine = tmp_path / "my-epuck.toml"
    mine.write_text(mazesim.RobotProfile.builtin("e-puck").to_toml())
    robot = f'[[robots]]\nname = "a"\nx = 0.0\ny = 0.0\nprofile = "{mine}"\n'
    with pytest.raises(mazesim.WorldFormatError) as refused:
        mazesim.World.from_toml(f'format = "mazesim-world"\nversion = 1\n{robot}')
    assert "expected a built-in robot profile" in str(refused.value)
    assert "--robot FILE" in str(refused.value)
    assert "robot_profiles=[RobotProfile.load(FILE)" in str(refused.value)
    # As told: the file as one robot's own profile.
    world = mazesim.World.from_toml(
        'format = "mazesim-world"\nversion = 1\n[[robots]]\nname = "a"\nx = 0.0\ny = 0.0\n'
    )
    sim = mazesim.Simulator(world, robot_profiles=[mazesim.RobotProfile.load(str(mine))])
    assert sim.num_robots == 1


def test_output_buffers_of_a_batch_of_several_robots_have_the_robot_axis() -> None:
    batch = mazesim.BatchSimulator(corridor(0.1, robots=3), num_envs=4, noise=False)
    obs, poses, colliding, crossings = batch.output_buffers()
    assert obs.shape == (4, 3, batch.observation_width) and obs.dtype == np.float32
    assert poses.shape == (4, 3, 3) and colliding.shape == (4, 3) and crossings.shape == (4, 3)
    batch.reset(obs, poses, colliding, crossings)
    batch.run(5, "braitenberg", obs, poses, colliding, crossings)
    assert np.isfinite(poses).all() and (poses[:, 0, 0] != 0).all()
    single = mazesim.BatchSimulator(mazesim.World.builtin("arena"), num_envs=4)
    assert [b.shape for b in single.output_buffers()] == [
        (4, single.observation_width),
        (4, 3),
        (4,),
        (4,),
    ]


def rising_table_epuck() -> mazesim.RobotProfile:
    """The e-puck whose proximity sensors read through Webots' default DistanceSensor table
    (0 touching, rising to 1000 at 0.1 m): a profile of the e-puck's name."""
    text = mazesim.RobotProfile.builtin("e-puck").to_toml()
    stock = "table = [[0.0, 4095.0, 0.002], "
    start = text.index(stock)
    end = text.index("]]", start) + 2
    return mazesim.RobotProfile.from_toml(
        text[:start] + "table = [[0.0, 0.0, 0.0], [0.1, 1000.0, 0.0]]" + text[end:], "rising"
    )


def test_robot_profiles_give_one_robot_its_own_profile_and_pickle_with_it() -> None:
    world, own = corridor(0.01), rising_table_epuck()
    before = mazesim.Simulator(world, noise=False)
    sim = mazesim.Simulator(world, noise=False, robot_profiles=[None, own])
    # Robot 0 reads as ever; robot 1 reads robot 0, 1 cm off, on the rising table (d / 0.38).
    assert np.array_equal(sim.distance_sensors(), before.distance_sensors())
    front = sim.distance_sensors(robot_index=1)[0]
    assert 0.0 < front < 1000.0 and sim.distance_sensors(robot_index=1)[3] == 1000.0
    assert front != before.distance_sensors(robot_index=1)[0]
    for _ in range(3):
        sim.step_robots(np.array([[1.0, -1.0], [2.0, 1.0]]))
    for duplicate in (lambda s: pickle.loads(pickle.dumps(s)), copy.copy):
        other = duplicate(sim)
        assert other.snapshot() == sim.snapshot()
        assert np.array_equal(other.distance_sensors(robot_index=1), sim.distance_sensors(1))


@pytest.mark.parametrize(
    ("profiles", "message"),
    [
        ([None], "expected no robot profiles or one per robot of world .* \\(2\\), found 1"),
        ([None, 3], r"robot_profiles\[1\] to be a robot profile name, a profile file's path or a"),
        ([None, "no-such-robot"], "no-such-robot"),
        ("e-puck", "expected robot_profiles to be a sequence"),
    ],
)
def test_robot_profiles_of_the_wrong_shape_are_refused(profiles: object, message: str) -> None:
    with pytest.raises(mazesim.MazesimError, match=message):
        mazesim.Simulator(corridor(0.01), robot_profiles=profiles)  # type: ignore[arg-type]
