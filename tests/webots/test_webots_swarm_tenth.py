"""A tenth set of multi-robot Webots worlds written as users write them, each run whole and
checked against what Webots gives: a relay over Emitters and Receivers on two channels, a
supervisor moving and turning robots by their DEF names, robots of two controllers, an e-puck2
stopping on its time-of-flight sensor before another e-puck, two e-pucks driving into each
other, e-pucks stopping before robots whose controller is "<none>" or "void", robots nested in
a Group, a Pose and a Solid, DEF robots read by a supervisor beside a USE'd bounding object, and
a five-robot roll call (#33)."""

from __future__ import annotations

import functools
import math
from pathlib import Path

import pytest

from swarm_project import BODY_RADIUS, run_project

PROJECT = Path(__file__).resolve().parent.parent / "data" / "webots-swarm-tenth"
#: The e-puck's wheel radius (m) and wheel distance (m) as Webots simulates them.
WHEEL_RADIUS = 0.02
AXLE = 0.05685
STEP_S = 0.032

run = functools.partial(run_project, PROJECT)


def _travel(speed: float, steps: int) -> float:
    """Metres an e-puck drives straight in ``steps`` control steps at ``speed`` rad/s."""
    return speed * WHEEL_RADIUS * steps * STEP_S


def test_a_relay_forwards_one_step_later_on_each_channel(tmp_path: Path) -> None:
    """A packet sent after step K is in the receiver's queue when its step K + 1 ends: the
    first robot's 1 (sent after its first step, on channel 1) reaches the second at step 2,
    whose 2 (channel 2) reaches the third at step 3; the first, listening on channel 0, hears
    nothing."""
    _, logs = run("relay_chain", tmp_path, 0.5)
    assert logs["first"]["heard"] == []
    assert logs["second"]["heard"] == [[2, 1]]
    assert logs["third"]["heard"] == [[3, 2]]


def test_a_supervisor_moves_a_robot_which_drives_on_from_there(tmp_path: Path) -> None:
    """Moved to (0.5, 0.5) facing +y after the supervisor's 10th step, the runner drives on
    from there: the supervisor's 31st step finds it 21 steps' travel up the y axis."""
    done, logs = run("teleport", tmp_path, 1.0)
    before, after = logs["mover"]["before"], logs["mover"]["after"]
    assert before[:2] == pytest.approx([-0.5 + _travel(2.0, 10), 0.0], abs=1e-6)
    assert after[:2] == pytest.approx([0.5, 0.5 + _travel(2.0, 21)], abs=1e-6)
    assert done.robots[0].final_pose[2] == pytest.approx(math.pi / 2, abs=1e-6)


def test_robots_of_two_controllers_each_run_their_own(tmp_path: Path) -> None:
    """Two cruisers drive straight at 3 rad/s; two spinners turn on the spot at the rate
    their wheels give (2 * 2 rad/s * r / wheel distance), staying where they are."""
    done, _ = run("two_kinds", tmp_path, 1.0)
    steps = round(done.robots[0].distance_m / _travel(3.0, 1))
    assert steps in (31, 32)
    for robot, (x, y) in zip(done.robots[:2], ((-0.5, -0.3), (-0.5, 0.3))):
        assert robot.final_pose[:2] == pytest.approx([x + _travel(3.0, steps), y], abs=1e-6)
    turn = 2 * 2.0 * WHEEL_RADIUS / AXLE * steps * STEP_S
    for robot, (x, y) in zip(done.robots[2:], ((0.5, -0.3), (0.5, 0.3))):
        assert robot.final_pose[:2] == pytest.approx([x, y], abs=1e-6)
        assert robot.final_pose[2] == pytest.approx(turn, abs=1e-3)


def test_an_e_puck2_stops_on_its_tof_before_another_e_puck(tmp_path: Path) -> None:
    """Webots' e-puck2 time-of-flight sensor reads millimetres; the e-puck2 stops once it reads
    under 100 mm, short of the parked e-puck (a controller of "<none>"), which does not move."""
    done, logs = run("epuck2_pair", tmp_path, 8.0)
    new_one, old_one = done.robots
    assert logs["new_one"]["stopped"] is not None
    assert logs["new_one"]["last"] < 100.0
    gap = old_one.final_pose[0] - new_one.final_pose[0] - 2 * BODY_RADIUS
    assert 0.05 < gap < 0.1, gap
    assert old_one.final_pose[:2] == pytest.approx([0.3, 0.0], abs=1e-6)


def test_two_e_pucks_driven_at_each_other_meet_and_push_to_a_standstill(tmp_path: Path) -> None:
    """Head on at equal speeds, the two e-pucks meet at the middle and push each other to a
    standstill, their bodies touching."""
    done, _ = run("head_on", tmp_path, 4.5)
    west, east = done.robots
    assert west.final_pose[0] == pytest.approx(-BODY_RADIUS, abs=1e-3)
    assert east.final_pose[0] == pytest.approx(BODY_RADIUS, abs=1e-3)
    assert west.final_pose[1] == pytest.approx(0.0, abs=1e-3)


def test_robots_without_a_controller_or_with_void_stand_as_obstacles(tmp_path: Path) -> None:
    """An e-puck of controller "<none>" and one of "void" stand still; each driver sees it on
    ps0/ps7 and stops before touching it (in the infra-red model, an e-puck's body reflects
    0.38 of a white wall's light)."""
    done, logs = run("idle_pair", tmp_path, 10.0)
    by_name = {robot.name: robot for robot in done.robots}
    for driver, parked in (("driver_a", "parked_none"), ("driver_b", "parked_void")):
        assert by_name[parked].final_pose[:2] == pytest.approx(
            [0.0, 0.2 if parked == "parked_none" else -0.2], abs=1e-6
        )
        assert by_name[parked].exit_status == 0
        stopped = logs[driver]["stopped"]
        assert stopped is not None, driver
        gap = -by_name[driver].final_pose[0] - 2 * BODY_RADIUS
        assert 0.0 < gap < 0.02, (driver, gap)
        assert by_name[driver].final_pose[0] == pytest.approx(
            -0.4 + _travel(3.0, stopped), abs=1e-5
        )


def test_robots_nested_in_a_group_a_pose_and_a_solid_start_where_the_frames_put_them(
    tmp_path: Path,
) -> None:
    """A Pose at (0.3, 0) turned a quarter turn holds an e-puck at (0.1, 0) in its frame: it
    starts at (0.3, 0.1) facing +y; a Solid at (-0.5, -0.5) holds one at (0, 0.2): it starts at
    (-0.5, -0.3) facing +x. Each drives 2 rad/s along its heading."""
    done, _ = run("nested_fleet", tmp_path, 1.0)
    in_pose, in_solid = done.robots
    steps = round(in_pose.distance_m / _travel(2.0, 1))
    assert in_pose.final_pose == pytest.approx(
        [0.3, 0.1 + _travel(2.0, steps), math.pi / 2], abs=1e-6
    )
    assert in_solid.final_pose == pytest.approx([-0.5 + _travel(2.0, steps), -0.3, 0.0], abs=1e-6)


def test_a_supervisor_finds_def_named_robots(tmp_path: Path) -> None:
    """getFromDef finds each DEF-named e-puck, its name field and its place after the
    supervisor's 21st step; a Solid whose boundingObject USEs its Shape is imported beside
    them."""
    _, logs = run("def_fleet", tmp_path, 0.7)
    left_name, left_at = logs["watcher"]["LEFT_BOT"]
    right_name, right_at = logs["watcher"]["RIGHT_BOT"]
    assert (left_name, right_name) == ("left_bot", "right_bot")
    assert left_at[:2] == pytest.approx([-0.3 + _travel(2.0, 21), 0.3], abs=1e-6)
    assert right_at[:2] == pytest.approx([0.3 - _travel(2.0, 21), -0.3], abs=1e-6)


def test_five_e_pucks_each_hear_the_four_others_one_step_after_they_send(tmp_path: Path) -> None:
    """Every robot sends its name after each step on channel 0; an e-puck's Emitter has no
    range limit, so each hears the four others, 1.2 m apart at most, from its second step."""
    _, logs = run("roll_call", tmp_path, 0.2)
    names = [f"bee_{i}" for i in range(5)]
    for name in names:
        assert logs[name]["first"] == {other: 2 for other in names if other != name}


def test_a_supervisor_turns_a_robot_in_place_and_it_drives_the_new_way(tmp_path: Path) -> None:
    """Turned to face +y after the supervisor's 15th step, keeping its place, the robot drives
    up the y axis from there; the bystander drives on along x."""
    done, logs = run("turned", tmp_path, 1.0)
    at_turn, end = logs["turner"]["at_turn"], logs["turner"]["end"]
    assert at_turn[:2] == pytest.approx([_travel(3.0, 15), 0.0], abs=1e-6)
    assert end[:2] == pytest.approx([_travel(3.0, 15), _travel(3.0, 16)], abs=1e-6)
    assert done.robots[1].final_pose[1] == pytest.approx(0.5, abs=1e-6)
