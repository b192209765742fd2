"""An eighth set of multi-robot Webots worlds written as users write them, each run whole and
checked against what Webots documents: a pursuer steering by getEmitterDirection after a fleeing
emitter, two wingmen keeping a formation on a leader's signal, robots that stop on a parked
neighbour's infra-red reading, a referee counting collisions with getContactPoints, a platoon of
e-puck2s on their ToF sensors, twenty e-pucks in a corridor, binary structs between a C and a
Python controller, Receiver.setChannel(-1) and Emitter.setChannel(-1), a controller field a
supervisor changes at run time, and e-pucks a supervisor places with importMFNodeFromString in a
loop, e-pucks that are their own supervisors reading each other's positions, and a bumper
another e-puck carries in its bodySlot, which rays and bodies meet (#33)."""

from __future__ import annotations

import functools
import itertools
import math
from pathlib import Path

import pytest

from epuck2_tof import tof_reading
from swarm_project import BODY_RADIUS, run_project

PROJECT = Path(__file__).resolve().parent.parent / "data" / "webots-swarm-eighth"
#: The e-puck's wheel radius (m).
WHEEL_RADIUS = 0.02
#: How far ahead of an e-puck's centre the ToF sensor sits (m).
TOF_AHEAD = 0.034

run = functools.partial(run_project, PROJECT)


def _track(robot: object) -> list[tuple[float, float]]:
    return list(zip(robot.xs, robot.ys))  # type: ignore[attr-defined]


def _closest(a: object, b: object) -> float:
    return min(math.dist(p, q) for p, q in zip(_track(a), _track(b)))


def test_a_pursuer_steering_by_the_emitter_direction_closes_on_the_evader(tmp_path: Path) -> None:
    """The signal strength is 1 / r^2 of the robots' distance and grows as the pursuer closes
    in; the pursuer ends behind the evader, dead ahead of it, without touching it."""
    done, logs = run("pursuit", tmp_path, 8.5)
    evader, pursuer = done.robots
    log = logs["pursuer"]
    strengths = log["strengths"]
    assert strengths[0] == pytest.approx(1 / math.dist((0, 0), (-0.4, 0.1)) ** 2, rel=0.03)
    assert log["caught"] is not None and strengths[-1] > 1 / 0.12**2
    gap = math.dist(evader.final_pose[:2], pursuer.final_pose[:2])
    assert strengths[-1] == pytest.approx(1 / gap**2, rel=0.05)
    assert abs(log["bearings"][-1]) < 0.2
    assert _closest(evader, pursuer) > 2 * BODY_RADIUS


def test_wingmen_hold_their_bearings_on_the_leader_from_its_signal(tmp_path: Path) -> None:
    """Each wingman's last bearing to the leader is the one it keeps (0.6 rad left of its
    heading, 0.6 rad right), and the range it takes from the signal strength is the robots'
    distance."""
    done, logs = run("formation", tmp_path, 10.0)
    leader, left, right = done.robots
    for robot, wanted in ((left, 0.6), (right, -0.6)):
        log = logs[robot.name]
        assert log["bearings"][-1] == pytest.approx(wanted, abs=0.1), log["bearings"][-5:]
        gap = math.dist(leader.final_pose[:2], robot.final_pose[:2])
        assert log["ranges"][-1] == pytest.approx(gap, rel=0.05)
        assert _closest(leader, robot) > 2 * BODY_RADIUS
    assert _closest(left, right) > 2 * BODY_RADIUS


def test_robots_stop_on_a_parked_neighbours_infra_red_reading(tmp_path: Path) -> None:
    """Driven at a parked e-puck at 3 rad/s, each stops once ps0 or ps7 reads above 80: short
    of the other's body, within the 2.66 cm an e-puck's shell (reflection factor 0.38) is seen
    from, and both parked robots stay where they are."""
    done, logs = run("ir_stop", tmp_path, 4.0)
    parked, careful, parked2, careful2 = done.robots
    for stopper, target in ((careful, parked), (careful2, parked2)):
        log = logs[stopper.name]
        assert log["stopped"] is not None and max(log["readings"][log["stopped"] - 1]) > 80
        gap = math.dist(stopper.final_pose[:2], target.final_pose[:2]) - 2 * BODY_RADIUS
        assert 0.0 < gap < 0.0266, gap
        assert target.distance_m == 0.0 and stopper.collisions == 0


def test_a_referee_counts_robot_collisions_with_get_contact_points(tmp_path: Path) -> None:
    """Another robot's node answers getContactPoints with that robot's contacts: the two rammers
    from their first touch on, at the point where their bodies meet, each on its own node; the
    robot that stands alone has none."""
    done, logs = run("contact_count", tmp_path, 3.0)
    a, b, c, _ = done.robots
    referee = logs["referee"]
    touch = next(
        k for k, (p, q) in enumerate(zip(_track(a), _track(b))) if math.dist(p, q) < 0.0742
    )
    assert referee["A"]["first"] == referee["B"]["first"] == touch
    for name in ("A", "B"):
        entry = referee[name]
        assert entry["steps_in_contact"] >= 1
        ((x, y, z),) = entry["points"]
        assert math.dist((x, y), entry["at"][:2]) == pytest.approx(BODY_RADIUS, abs=1e-3)
        assert (x, y, z) == pytest.approx((0.0, 0.0, 0.0), abs=1e-3)
    assert referee["C"] == {"steps_in_contact": 0, "first": None, "points": []}
    assert c.distance_m == 0.0


def test_a_platoon_of_e_puck2s_follows_on_its_time_of_flight_sensors(tmp_path: Path) -> None:
    """Each follower's first ToF reading is the gap to the body ahead through the e-puck2's
    table; the platoon closes up to its followers' set range without a touch."""
    done, logs = run("tof_platoon", tmp_path, 6.5)
    starts = {"second": (0.3, 0.1), "third": (0.1, -0.1), "fourth": (-0.1, -0.35)}
    for name, (ahead, at) in starts.items():
        first = logs[name]["tof"][0] * 1000.0
        assert first == pytest.approx(tof_reading(ahead - at - BODY_RADIUS - TOF_AHEAD), rel=0.05)
        assert 0.08 < logs[name]["tof"][-1] < 0.14
    for one, other in itertools.pairwise(done.robots):
        assert _closest(one, other) > 2 * BODY_RADIUS
        assert one.final_pose[0] > other.final_pose[0]


def test_twenty_e_pucks_in_a_corridor_all_run_and_none_passes_through_another(
    tmp_path: Path,
) -> None:
    """Twenty Braitenberg e-pucks, face to face in pairs, in a corridor 19 cm wide: every
    controller runs its 200 steps; at no step do two bodies overlap or a body cross a wall."""
    done, logs = run("corridor20", tmp_path, 6.5)
    assert len(done.robots) == 20 and [r.exit_status for r in done.robots] == [0] * 20
    assert all(logs[f"e{i}"] == {"steps": 200} for i in range(20))
    for one, other in itertools.combinations(done.robots, 2):
        assert _closest(one, other) > 2 * BODY_RADIUS - 1e-3, (one.name, other.name)
    inner = 0.095 - BODY_RADIUS
    assert all(abs(y) < inner + 1e-3 for robot in done.robots for y in robot.ys)
    assert all(robot.distance_m > 0.01 for robot in done.robots)


def test_a_c_and_a_python_controller_exchange_binary_structs(tmp_path: Path) -> None:
    """The C robot's 16-byte struct (int32, float, double) arrives whole, unpacked by Python's
    ``struct.unpack("<ifd")``; the Python robot's ``struct.pack("<iff")`` arrives as 12 bytes
    the C robot copies into its struct, one packet a step, a step after it was sent."""
    _, logs = run("structs", tmp_path, 1.0)
    python = logs["py_reporter"]
    assert python["sizes"] == [16] * 19
    assert python["reports"] == [
        [k, pytest.approx(0.5 * k), pytest.approx(0.032 * k)] for k in range(1, 20)
    ]
    assert logs["c_reporter"] == {
        "size": 16,
        "heard": 19,
        "last_step": 19,
        "bad_size": 0,
        "sum_x": pytest.approx(sum(range(1, 20)) / 10, abs=1e-3),
    }


def test_a_receiver_on_channel_minus_one_hears_every_channel(tmp_path: Path) -> None:
    """Receiver.setChannel(-1) hears the emitters of channels 1 and 2 and the one sending on
    -1; a receiver left on channel 7 hears only the emitter sending on every channel."""
    _, logs = run("broadcast", tmp_path, 1.0)
    assert logs["all_ears"] == {"channel": -1, "heard": {"ch1": 9, "ch2": 9, "shout": 9}}
    assert logs["on7"] == {"channel": 7, "heard": {"shout": 9}}
    assert logs["shout"]["channel"] == -1


def test_a_supervisor_changes_a_robots_controller_field_and_restarts_it(tmp_path: Path) -> None:
    """Setting the worker's controller field to "phase_two" and restarting its controller in
    the same step ends "phase_one" and starts "phase_two" once, on the running clock, on the
    robot where it stands."""
    done, logs = run("swap_controller", tmp_path, 2.0)
    worker = done.robots[0]
    assert logs["phase_one"] == {"steps": 20, "start": 0.0, "end": pytest.approx(0.64)}
    assert logs["phase_two"]["starts"] == [pytest.approx(0.64)]
    assert logs["phase_two"]["name"] == "worker"
    switcher = logs["switcher"]
    assert (switcher["before"], switcher["after"]) == ("phase_one", "phase_two")
    assert switcher["at_switch"][0] == pytest.approx(20 * 2.0 * WHEEL_RADIUS * 0.032, abs=1e-6)
    assert switcher["end"] == pytest.approx(switcher["at_switch"], abs=1e-6)
    assert worker.restarts_s == [pytest.approx(0.64)]


def test_e_pucks_placed_in_a_loop_by_import_mf_node_from_string_all_run(tmp_path: Path) -> None:
    """Six e-pucks imported in a loop before the placer's first step: each is a child of the
    root, runs its controller from time 0 and drives 31 steps towards the ring's centre."""
    done, logs = run("import_loop", tmp_path, 1.5)
    placer = logs["placer"]
    assert (placer["before"], placer["after"]) == (3, 9)
    assert placer["names"] == [f"bot{i}" for i in range(6)]
    assert [r.name for r in done.robots] == ["placer"] + placer["names"]
    travelled = 31 * 2.0 * WHEEL_RADIUS * 0.032
    for i, position in enumerate(placer["positions"]):
        assert logs[f"bot{i}"] == {"steps": 30, "start": 0.0}
        angle = i * math.pi / 3
        expected = [(0.4 - travelled) * math.cos(angle), (0.4 - travelled) * math.sin(angle)]
        assert position == pytest.approx(expected, abs=1e-4)


def test_e_pucks_that_are_their_own_supervisors_see_each_other_moved(tmp_path: Path) -> None:
    """Three e-pucks with ``supervisor TRUE`` read their own position (getSelf) and each
    other's (getFromDef) alike, step by step; a fourth robot's supervisor turns R1 and moves R2
    after its 20th step, and from their 21st step on they drive on from there."""
    _, logs = run("self_aware", tmp_path, 1.5)
    step = 2.0 * WHEEL_RADIUS * 0.032
    for name, (x, y, yaw) in {
        "r0": (0, 0, 0),
        "r1": (0.3, 0.1, 1.5708),
        "r2": (-0.2, -0.3, math.pi),
    }.items():
        log = logs[name]
        for k in range(40):
            assert log["seen"][k][name.upper()] == pytest.approx(log["self"][k], abs=1e-9)
        for k in range(20):
            expected = (x + (k + 1) * step * math.cos(yaw), y + (k + 1) * step * math.sin(yaw))
            assert log["self"][k] == pytest.approx(expected, abs=1e-4)
        assert all(seen == logs["r0"]["seen"][k] for k, seen in enumerate(log["seen"]))
    assert logs["r1"]["heading"][20] == pytest.approx(math.pi, abs=1e-4)
    assert logs["r1"]["self"][20] == pytest.approx([0.3 - step, 0.1 + 20 * step], abs=1e-4)
    assert logs["r2"]["self"][20] == pytest.approx([0.5 - step, 0.5], abs=1e-4)
    assert logs["turner"]["r1_rotation"] == pytest.approx([0, 0, 1, 3.14159], abs=1e-5)


def test_a_bumper_another_e_puck_carries_stops_rays_and_bodies(tmp_path: Path) -> None:
    """A parked e-puck carries a white bumper (a Box, roughness 1: reflection factor 0.6) in
    its bodySlot, 6 cm behind its centre: the careful robot's ps0 and ps7 read it above 80
    from about 4 cm (2.66 cm for the e-puck's shell) and it stops short of the bumper, not of
    the body behind it. A robot that drives blind at a dark bumper stops at its face."""
    done, logs = run("bumper", tmp_path, 5.0)
    parked, careful, parked2, blind = done.robots
    face = -0.06 - 0.01
    log = logs["careful"]
    assert log["stopped"] is not None and max(log["readings"][log["stopped"] - 1]) > 80
    short = face - (careful.final_pose[0] + BODY_RADIUS)
    assert 0.02 < short < 0.04, short
    assert careful.collisions == 0 and parked.distance_m == 0.0
    assert blind.final_pose[0] + BODY_RADIUS == pytest.approx(face, abs=1e-3)
    assert blind.final_pose[1] == pytest.approx(0.4, abs=1e-3)
    assert parked2.distance_m == 0.0
