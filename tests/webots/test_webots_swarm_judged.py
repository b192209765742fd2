"""A second set of multi-robot Webots worlds in the patterns swarm projects use, each run whole
and checked against what Webots documents: a beacon on a turret Emitter whose range shrinks, a
supervisor importing e-pucks into a Group with their controllerArgs, robots without a controller
beside a running one, an unsynchronized robot stepping by its own period, one controller whose
copies take their number from Webots' "e-puck(1)" names and write their customData for a
supervisor, an e-puck2's time-of-flight sensor before a dark wall, robots driven into each
other's side and head-on at unequal speeds, a robot nested three nodes deep reading its GPS and
compass, and a supervisor that sends each robot its pose over an Emitter (#33, #32)."""

from __future__ import annotations

import functools
import math
from pathlib import Path

import pytest

from epuck2_tof import tof_reading
from swarm_project import BODY_RADIUS, run_project

PROJECT = Path(__file__).resolve().parent.parent / "data" / "webots-swarm-judged"


run = functools.partial(run_project, PROJECT)


def test_a_turret_beacon_reaches_the_receivers_within_its_range_until_it_shrinks(
    tmp_path: Path,
) -> None:
    """A turret Emitter on channel 7 with a range of 0.4 m: the followers 0.3 m away hear each
    packet one step after it was sent, at a strength of 1 / 0.3^2, from ahead or from the left;
    the one 0.8 m away hears nothing; once the range is 0.2 m (the packet of step 30 on) nobody
    does."""
    done, logs = run("follow_beacon", tmp_path, 2.0)
    assert logs["leader"]["range"] == 0.4 and logs["leader"]["range_after"] == 0.2
    for name, direction in (("near", [1.0, 0.0, 0.0]), ("side", [0.0, 1.0, 0.0])):
        heard = logs[name]["heard"]
        assert [(step, number) for step, number, _, _ in heard] == [
            (n + 1, n) for n in range(1, 30)
        ]
        assert all(s == pytest.approx(1 / 0.3**2, rel=1e-5) for _, _, s, _ in heard)
        assert heard[0][3] == pytest.approx(direction, abs=1e-6)
        assert logs[name]["channel"] == 7
    assert logs["far"]["heard"] == []
    assert [r.exit_status for r in done.robots] == [0, 0, 0, 0]


def test_a_supervisor_imports_e_pucks_into_a_group_with_their_arguments(tmp_path: Path) -> None:
    done, logs = run("spawn_into_group", tmp_path, 3.0)
    hive = logs["hive"]
    assert (hive["count_before"], hive["count_with"], hive["count_after"]) == (0, 3, 2)
    assert hive["order"] == ["B2", "B1", "B0"] and hive["parent"] == "SWARM"
    assert hive["b0_gone"]
    # Each bee drives at its first argument's speed from its first step on.
    for index in range(3):
        x, y, _ = hive["start"][f"B{index}"]
        assert (x, y) == pytest.approx((0.3 * index + 0.02 * (index + 1) * 0.032, 0.5), abs=1e-5)
        assert logs[f"bee_{index}"]["argv"] == [str(index + 1), f"tag {index}"]
    assert hive["moved"][:2] == pytest.approx([0.6 + 0.06 * 0.032, -0.5], abs=1e-5)
    assert logs["bee_0"]["time"] == pytest.approx(30 * 0.032)
    assert logs["bee_1"]["steps"] == logs["bee_2"]["steps"] > logs["bee_0"]["steps"]
    assert [r.name for r in done.robots] == ["hive", "bee_0", "bee_1", "bee_2"]


def test_robots_without_a_controller_stand_still_beside_a_running_one(tmp_path: Path) -> None:
    """``<none>``, the older ``void``, an empty field and an ``<extern>`` controller not given:
    each robot stands still (an obstacle), the one with a controller runs its second."""
    done, logs = run("idle_mix", tmp_path, 3.0)
    assert set(logs) == {"runner"} and logs["runner"]["steps"] == 32
    runner, *idle = done.robots
    assert runner.distance_m == pytest.approx(2.0 * 0.02 * 1.024, rel=0.02)
    assert [r.distance_m for r in idle] == [0.0, 0.0, 0.0, 0.0]
    assert all(r.exit_status == 0 for r in done.robots)


def test_an_unsynchronized_robot_steps_by_its_own_period(tmp_path: Path) -> None:
    _, logs = run("async_pacer", tmp_path, 3.0)
    free, locked = logs["free"], logs["locked"]
    assert free["synchronization"] is False and locked["synchronization"] is True
    assert free["times"] == pytest.approx([0.064, 0.128, 0.192])
    assert locked["times"] == pytest.approx([0.016, 0.032, 0.048])
    assert (free["steps"], locked["steps"]) == (16, 63)


def test_a_supervisor_reads_the_custom_data_each_robot_writes_itself(tmp_path: Path) -> None:
    """Each copy of one controller takes its number from its name ("e-puck", "e-puck(1)", ...)
    and writes ``number:role:step`` with ``setCustomData`` after each step; Webots puts it in
    the robot node's ``customData`` field, which a supervisor reads after the next step."""
    _, logs = run("numbered", tmp_path, 2.0)
    assert [logs[f"robot{i}"]["role"] for i in range(4)] == ["worker", "worker", "guard", "worker"]
    assert [logs[f"robot{i}"]["heard"] for i in (1, 2, 3)] == [19, 19, 19]
    assert logs["robot1"]["first"] == "from 0 at 1"
    seen = logs["roll_call"]
    assert list(seen) == ["e-puck", "e-puck(1)", "e-puck(2)", "e-puck(3)"]
    for number, (name, values) in enumerate(seen.items()):
        role = "guard" if number == 2 else "worker"
        assert values[0] == ("guard" if number == 2 else ""), name
        assert values[1:] == [f"{number}:{role}:{step}" for step in range(1, 10)], name


def test_an_e_puck2_time_of_flight_sensor_is_generic_and_sees_a_dark_wall(tmp_path: Path) -> None:
    """The ToF reads the distance to a dark wall (red 0.1) through its table, as Webots'
    "generic" sensor does, where the infra-red ps0 and ps7 see nothing of it; ``getType`` says
    ``GENERIC``. Its peer, behind it, reads the distance to its back."""
    _, logs = run("tof_dark_wall", tmp_path, 2.0)
    probe, peer = logs["probe"], logs["peer"]
    assert probe["type"] == peer["type"] == 0 and probe["generic"]
    # The wall's face at 0.29 m; the sensor 0.034 m ahead of the centre at 0.2 m.
    assert probe["still"][0] == pytest.approx(tof_reading(0.29 - 0.234), rel=0.05)
    assert probe["backed"][0] == pytest.approx(tof_reading(0.29 - 0.234 + 0.0256), rel=0.05)
    # f = 0.2 + 0.8 * 0.1 * 0.5 = 0.24: the wall within 7 cm * 0.24 only; here 6.3 cm away.
    assert max(probe["still"][1:]) < 80
    assert peer["still"][0] == pytest.approx(tof_reading(0.4 - BODY_RADIUS - 0.034), rel=0.05)


def test_robots_driven_into_each_other_stop_at_contact_without_pushing(tmp_path: Path) -> None:
    """C controllers: one e-puck rams a still one's side, two meet head-on at 5 and 3 rad/s;
    each pair stops touching (no overlap), nobody pushes the other, the still one stays put."""
    done, logs = run("tbone", tmp_path, 4.0)
    target, rammer, pusher_a, pusher_b = done.robots
    assert target.distance_m < 1e-6 and target.final_pose[:2] == pytest.approx([0, 0], abs=1e-6)
    assert math.dist(target.final_pose[:2], rammer.final_pose[:2]) == pytest.approx(
        2 * BODY_RADIUS, abs=1e-3
    )
    assert math.dist(pusher_a.final_pose[:2], pusher_b.final_pose[:2]) == pytest.approx(
        2 * BODY_RADIUS, abs=1e-3
    )
    assert pusher_a.final_pose[0] == pusher_b.final_pose[0] == pytest.approx(0.5, abs=1e-6)
    # The faster one covered more before they met.
    assert pusher_a.distance_m > pusher_b.distance_m
    assert all(r.collisions >= 1 for r in done.robots)
    assert logs["rammer"]["front_max"] > 200 and logs["rammer"]["steps"] == 218


def test_a_robot_nested_three_deep_reads_its_world_pose_on_gps_and_compass(
    tmp_path: Path,
) -> None:
    """An e-puck in a Pose in a Group in a Transform turned a quarter turn at (0.5, 0.2)
    stands at (0.5, 0.3) facing +y; its GPS and compass read that, and it drives along +y."""
    done, logs = run("nested_gps", tmp_path, 2.0)
    deep, top = logs["deep"], logs["top"]
    step = 4.0 * 0.02 * 0.032
    back = 0.0095  # the GPS sits in the turret slot, 9.5 mm behind the robot's centre
    assert deep["first"][:2] == pytest.approx([0.5, 0.3 + step - back], abs=1e-4)
    assert deep["first"][3] == pytest.approx(math.pi / 2, abs=1e-3)
    assert deep["last"][:2] == pytest.approx([0.5, 0.3 + 40 * step - back], abs=1e-3)
    assert top["last"][:2] == pytest.approx([-0.5 - 40 * step + back, 0.0], abs=1e-3)
    assert abs(top["last"][3]) == pytest.approx(math.pi, abs=1e-3)
    x, y, _ = done.robots[0].final_pose
    assert [x, y - back] == pytest.approx(deep["last"][:2], abs=1e-6)


def test_robots_steered_by_the_poses_a_supervisor_sends_reach_their_goals(
    tmp_path: Path,
) -> None:
    """A supervisor reads each robot's ``getPosition`` and ``getOrientation`` every step and
    sends them on the robot's channel; C controllers steer by them to their goals."""
    done, logs = run("localised_goals", tmp_path, 17.0)
    goals = {"r1": (-0.4, 0.3), "r2": (0.4, 0.3), "r3": (0.0, -0.2)}
    for index, (name, goal) in enumerate(goals.items()):
        log = logs[name]
        assert log["heard"] == 499 and log["arrived"] > 0, log
        robot = done.robots[index]
        assert math.dist(robot.final_pose[:2], goal) < 0.025
        # The pose heard last is where the robot was one step before it ended.
        assert math.dist((log["x"], log["y"]), robot.final_pose[:2]) < 0.01
