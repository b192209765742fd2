"""A ninth set of multi-robot Webots worlds written as users write them, each run whole and
checked against what Webots documents: an e-puck a supervisor imports carrying a bumper as a
world file's e-puck carries one, controllers stepping with stepBegin / stepEnd in Python and C,
a receiver turned off and on again, a robot with two emitters on two channels, heading
alignment over InertialUnits, controllers sharing code through runtime.ini and a Makefile, an
e-puck a supervisor moves round another every step, two e-pucks pushing a WoodenBox, Alg. 1 in
a CircleArena, a C supervisor reading robots' velocities and leader election by signal strength
(#33)."""

from __future__ import annotations

import functools
import itertools
import math
from pathlib import Path

import pytest

from swarm_project import BODY_RADIUS, run_project

PROJECT = Path(__file__).resolve().parent.parent / "data" / "webots-swarm-ninth"
#: The e-puck's wheel radius (m) and wheel distance (m) as Webots simulates them.
WHEEL_RADIUS = 0.02
AXLE = 0.05685
STEP_S = 0.032

run = functools.partial(run_project, PROJECT)


def _turn(angle: float) -> float:
    """``angle`` in (-pi, pi]."""
    return math.atan2(math.sin(angle), math.cos(angle))


def test_an_imported_e_puck_carries_its_bumper_as_a_world_files_does(tmp_path: Path) -> None:
    """A supervisor imports the twin of the world file's parked e-puck, bumper and all: the
    rammer driving at it stops at the bumper's face, as the one driving at the file's e-puck
    does, and both see the bumper coming on their front sensors."""
    done, logs = run("imported_bumper", tmp_path, 4.0)
    by_name = {r.name: r for r in done.robots}
    face = -0.06 - 0.01
    for name, y in (("rammer_file", 0.4), ("rammer_imported", -0.4)):
        robot = by_name[name]
        assert robot.final_pose[0] + BODY_RADIUS == pytest.approx(face, abs=2e-3), name
        assert robot.final_pose[1] == pytest.approx(y, abs=2e-3), name
    near = [
        next(k for k, v in enumerate(logs[name]["readings"]) if v > 300)
        for name in ("rammer_file", "rammer_imported")
    ]
    assert abs(near[0] - near[1]) <= 1, near
    assert logs["placer"]["twin"][:2] == pytest.approx([0.0, -0.4], abs=1e-3)


def test_step_begin_and_step_end_step_as_step_does_in_python_and_c(tmp_path: Path) -> None:
    """Packet K, sent before a controller's step K + 1 begins, is in the listener's queue when
    its step K + 1 ends, whether that step was taken whole or in two halves; the wheel speeds
    set before a step's beginning move the robot during it."""
    done, logs = run("step_halves", tmp_path, 2.5)
    assert logs["half_py"] == {"done": 50, "results": [0], "time": pytest.approx(51 * STEP_S)}
    assert logs["half_c"] == {"done": 50, "bad": 0, "time": pytest.approx(51 * STEP_S)}
    heard = sorted(map(tuple, logs["ear"]["heard"]))
    expected = sorted((k + 1, f"{who}:{k}") for k in range(50) for who in ("py", "c"))
    assert heard == expected
    for robot in done.robots[:2]:
        travelled = 50 * STEP_S * 2.0 * WHEEL_RADIUS
        assert robot.final_pose[0] == pytest.approx(-0.5 + travelled, abs=1e-4), robot.name
        assert robot.exit_status == 0, robot.error


def test_a_receiver_turned_off_hears_nothing_until_turned_on_again(tmp_path: Path) -> None:
    """Disabled after its 10th step, the receiver's sampling period is 0 and the packets sent
    meanwhile are lost; enabled again after its 20th, it hears what is sent from then on."""
    _, logs = run("deaf_spell", tmp_path, 1.5)
    log = logs["toggler"]
    heard = [(k + 1, k) for k in range(1, 10)] + [(k + 1, k) for k in range(20, 40)]
    assert list(map(tuple, log["heard"])) == heard
    assert log["periods"] == [32] * 9 + [0] * 10 + [32] * 21


def test_two_emitters_of_one_robot_send_on_their_own_channels(tmp_path: Path) -> None:
    """The hub's "low" emitter (channel 1, moved to 2 before its 21st send) and "high"
    (channel 2): the channel-1 e-puck hears low's first 20 packets, the channel-2 one every
    high packet and low's from the 21st, and a receiver on every channel (-1) hears both."""
    _, logs = run("two_mouths", tmp_path, 1.6)
    assert logs["hub"]["channels"] == [2, 2]
    low = [[k + 1, f"low:{k}"] for k in range(1, 41)]
    high = [[k + 1, f"high:{k}"] for k in range(1, 41)]
    assert logs["one"] == {"channel": 1, "heard": low[:20]}
    assert logs["two"]["channel"] == 2
    both = [packet for k in range(40) for packet in (low[k], high[k])]
    assert logs["two"]["heard"] == [p for p in both if p in high or p in low[20:]]
    assert logs["any"] == {"channel": -1, "heard": both}


def test_e_pucks_align_their_headings_over_their_inertial_units(tmp_path: Path) -> None:
    """Four e-pucks (three Python, one C) that start facing four ways end facing one way
    within 0.1 rad, each InertialUnit's last yaw the robot's final heading."""
    done, logs = run("heading_flock", tmp_path, 200 * STEP_S)
    last = [logs[f"f{i}"]["yaws"][-1] for i in range(3)] + [logs["f3"]["last_yaw"]]
    assert logs["f3"]["steps"] == 200 and all(len(logs[f"f{i}"]["yaws"]) == 200 for i in range(3))
    for yaw, robot in zip(last, done.robots):
        assert _turn(yaw - robot.final_pose[2]) == pytest.approx(0.0, abs=1e-6), robot.name
    for a, b in itertools.combinations(last, 2):
        assert abs(_turn(a - b)) < 0.1, last
    for a, b in itertools.combinations(done.robots, 2):
        assert math.dist(a.final_pose[:2], b.final_pose[:2]) > 2 * BODY_RADIUS


def test_controllers_share_the_projects_code_through_runtime_ini_and_a_makefile(
    tmp_path: Path,
) -> None:
    """Two Python scouts import a module beside them and the project's library that their
    runtime.ini puts on the path; a C scout is built from its Makefile's two sources, one in
    the project's library: each drives at the speed its argument names."""
    done, logs = run("shared_code", tmp_path, 1.5)
    for robot, speed in zip(done.robots, (5.0, 2.0, 5.0)):
        assert robot.exit_status == 0, robot.error
        assert logs[robot.name]["speed"] == speed
        assert robot.distance_m == pytest.approx(32 * STEP_S * speed * WHEEL_RADIUS, abs=1e-4)


def test_a_robot_a_supervisor_moves_every_step_is_seen_where_it_was_put(tmp_path: Path) -> None:
    """The moon, put at angle 2 pi K / 80 of an 8.5 cm circle after the orbiter's step K, is
    there during step K + 1: its position reads so, and the centre robot's strongest
    proximity sensor at the end of that step looks its way whenever one sees it (the e-puck's
    shell, 1.6 cm from the sensors, reads above 100 in front of one)."""
    _, logs = run("orbit", tmp_path, 85 * STEP_S)
    headings = [-0.3008, -0.8008, -math.pi / 2, -2.6440, 2.6392, math.pi / 2, 0.7992, 0.2992]
    for k, (x, y, _) in enumerate(logs["orbiter"]["placed"]):
        angle = 2 * math.pi * k / 80
        assert [x, y] == pytest.approx([0.085 * math.cos(angle), 0.085 * math.sin(angle)], abs=1e-6)
    strong = 0
    for k, readings in enumerate(logs["centre"]["readings"]):
        best = max(range(8), key=lambda i: readings[i])
        if readings[best] > 100:
            strong += 1
            assert abs(_turn(headings[best] - 2 * math.pi * k / 80)) < 0.6, (k, readings)
    assert strong > 40


def test_two_e_pucks_push_a_wooden_box_together(tmp_path: Path) -> None:
    """Side by side at 4 rad/s, they meet the WoodenBox's back face after 1.41 s and push it
    straight on (slower than they drove, its 0.2 kg held back by the floor), their fronts on
    its back face to the end: the referee's getPosition and the robots agree."""
    done, logs = run("crate", tmp_path, 4.0)
    track = logs["referee"]["track"]
    touch = (0.2 - BODY_RADIUS - 0.05) / (4.0 * WHEEL_RADIUS)
    assert track[int(touch / STEP_S) - 2][0] == pytest.approx(0.0, abs=1e-6)
    x, y, _ = track[-1]
    assert 0.08 < x < 0.25 and y == pytest.approx(0.0, abs=0.02)
    for robot in done.robots[:2]:
        assert robot.final_pose[0] + BODY_RADIUS == pytest.approx(x - 0.05, abs=3e-3)
        side = 0.045 if robot.name == "left_pusher" else -0.045
        assert robot.final_pose[1] == pytest.approx(side, abs=1e-3)


def test_alg_1_keeps_six_e_pucks_inside_a_circle_arena(tmp_path: Path) -> None:
    """Six e-pucks avoiding what they see for 15 s stay inside the CircleArena's wall (radius
    0.5 m) and end apart, none on another."""
    done, _ = run("round_pen", tmp_path, 15.0)
    for robot in done.robots:
        reach = max(math.hypot(x, y) for x, y in zip(robot.xs, robot.ys)) + BODY_RADIUS
        assert reach < 0.5 + 2e-3, (robot.name, reach)
        assert robot.distance_m > 0.3
    for a, b in itertools.combinations(done.robots, 2):
        assert math.dist(a.final_pose[:2], b.final_pose[:2]) > 2 * BODY_RADIUS - 1e-3


def test_a_c_supervisor_reads_each_robots_velocity_and_heading(tmp_path: Path) -> None:
    """After 20 steps: the straight robot moves at 0.08 m/s along x, the spinner turns at
    r (wr - wl) / axle on the spot, the diagonal one moves at 0.06 m/s at 45 degrees; the
    rotation fields and orientation matrices give their headings."""
    _, logs = run("speedometer", tmp_path, 1.0)
    log = logs["speedo"]
    assert log["time"] == pytest.approx(20 * STEP_S)
    assert log["S1"]["velocity"] == pytest.approx([0.08, 0, 0, 0, 0, 0], abs=1e-3)
    spin = WHEEL_RADIUS * 4.0 / AXLE
    assert log["S2"]["velocity"] == pytest.approx([0, 0, 0, 0, 0, spin], abs=2e-3)
    diagonal = 0.06 * math.sqrt(0.5)
    assert log["S3"]["velocity"] == pytest.approx([diagonal, diagonal, 0, 0, 0, 0], abs=1e-3)
    for name, yaw in (("S1", 0.0), ("S2", spin * 20 * STEP_S), ("S3", math.pi / 4)):
        assert log[name]["heading"] == pytest.approx([math.cos(yaw), math.sin(yaw)], abs=1e-3)
        x, y, z, angle = log[name]["rotation"]
        assert abs(_turn(math.copysign(angle, z) - yaw)) < 1e-3, (name, log[name]["rotation"])


def test_e_pucks_elect_the_most_central_one_by_signal_strength(tmp_path: Path) -> None:
    """Each robot's score is the sum of 1 / r^2 over the others; every robot elects the one
    whose score is highest, and hears each neighbour from its direction."""
    _, logs = run("election", tmp_path, 10 * STEP_S)
    places = [(0.05, 0.02), (0.35, 0.0), (-0.3, 0.15), (0.1, 0.45), (-0.05, -0.4)]
    scores = [sum(1 / math.dist(p, q) ** 2 for q in places if q is not p) for p in places]
    winner = f"e{max(range(5), key=lambda i: scores[i])}"
    for i, place in enumerate(places):
        log = logs[f"e{i}"]
        assert log["score"] == pytest.approx(scores[i], rel=0.02)
        assert log["leader"] == winner and log["heard"] == [f"e{j}" for j in range(5)]
        for j, other in enumerate(places):
            if j != i:
                gap = math.dist(place, other)
                bearing = [(other[0] - place[0]) / gap, (other[1] - place[1]) / gap]
                assert log["directions"][f"e{j}"][:2] == pytest.approx(bearing, abs=0.02)
