"""Multi-robot Webots worlds written in the patterns swarm projects use, each run whole (every
robot with its controller, in lockstep) and checked against what Webots documents: orders
passed along a chain over channels and ranges, a supervisor that brings robots in and takes them
out, an ``<extern>`` robot beside a local one, roles picked from ``getName()`` or ``customData``,
e-puck2s stopping on their time-of-flight sensor, four robots meeting head-on, robots nested in
a Transform, a Group and a Pose, a supervisor tracking every robot each step, and a robot whose
``synchronization`` is FALSE (#33, #32)."""

from __future__ import annotations

import functools
import math
from pathlib import Path

import pytest

from epuck2_tof import tof_reading
from swarm_project import BODY_RADIUS, run_project

PROJECT = Path(__file__).resolve().parent.parent / "data" / "webots-swarm-patterns"

#: How far ahead of an e-puck's centre the ToF sensor sits (m).
TOF_AHEAD = 0.034


run = functools.partial(run_project, PROJECT)


def test_orders_pass_along_a_chain_on_their_channels_within_range(tmp_path: Path) -> None:
    """C controllers, their roles from ``controllerArgs``: the head sends on channel 3 with a
    0.5 m range, the middle robot 0.4 m away passes each packet on over channel 4, the tail
    0.4 m beyond hears channel 4 only, and a stray 0.8 m from the head on channel 3 hears
    nothing. Each hop takes one step."""
    done, logs = run("relay_chain", tmp_path, 3.0)
    assert [r.exit_status for r in done.robots] == [0, 0, 0, 0]
    middle, tail, stray = logs["middle"], logs["tail"], logs["stray"]
    assert (middle["first_heard"], middle["first_sequence"], middle["heard"]) == (2, 1, 59)
    assert (tail["first_heard"], tail["first_sequence"], tail["heard"]) == (3, 1, 58)
    assert middle["size"] == tail["size"] == 16  # two doubles, as the head packed them
    assert middle["strength"] == pytest.approx(1 / 0.4**2)
    assert stray["heard"] == 0
    head, mid, end, lost = done.robots
    assert head.distance_m == 0.0 and lost.distance_m == 0.0
    # Told 3 rad/s until the head's step 40, then 0: about 7.5 cm at 6 cm/s.
    assert 0.07 < mid.distance_m < 0.085 and 0.07 < end.distance_m < 0.085


def test_a_supervisor_brings_workers_in_and_takes_two_out(tmp_path: Path) -> None:
    done, logs = run("spawn_and_cull", tmp_path, 5.0)
    queen = logs["queen"]
    assert (queen["count_before"], queen["count_with"], queen["count_after"]) == (3, 7, 5)
    assert queen["gone"] == [False, True, False, True] and queen["last_is_w3"]
    assert queen["imported"][2] == pytest.approx([-0.6, 0.6, 0.0], abs=1e-6)
    # Each worker drives at 1 + its number rad/s from its first step on.
    for index, (before, after) in enumerate(zip(queen["imported"], queen["after_a_step"])):
        assert after[0] - before[0] == pytest.approx(0.02 * (1 + index) * 0.032, rel=0.05)
    # The removed workers' steps returned -1 once they were taken out; the others ran on.
    assert logs["w1"]["steps"] == logs["w3"]["steps"] < logs["w0"]["steps"] == logs["w2"]["steps"]
    assert logs["w1"]["time"] == pytest.approx(40 * 0.032)
    assert [r.name for r in done.robots] == ["queen", "w0", "w1", "w2", "w3"]
    assert done.robots[2].removed_s == pytest.approx(40 * 0.032)


def test_an_extern_robot_stands_still_unless_its_controller_is_given(tmp_path: Path) -> None:
    alone, logs = run("extern_mix", tmp_path / "alone", 3.0)
    assert set(logs) == {"local"} and alone.robots[1].distance_m == 0.0
    assert "<extern>" in alone.robots[1].note
    given = PROJECT / "controllers" / "remote_driver" / "remote_driver.py"
    both, logs = run("extern_mix", tmp_path / "both", 3.0, remote=str(given))
    assert logs["remote"] == {"name": "remote", "steps": 50, "file": "remote_driver.py"}
    assert both.robots[1].final_pose[0] < -0.05, "driven backwards by the extern controller"
    assert logs["local"]["steps"] == 50 and both.robots[0].final_pose[0] > 0.08


def test_one_controller_plays_the_role_its_name_or_custom_data_gives(tmp_path: Path) -> None:
    done, logs = run("named_roles", tmp_path, 3.0)
    roles = {name: log["role"] for name, log in logs.items()}
    assert roles == {
        "leader": "leader",
        "worker_1": "worker",
        "worker_2": "worker",
        "e-puck": "scout",
    }
    assert logs["worker_1"]["first"] == ["leader 1"] and logs["worker_1"]["heard"] == 39
    leader, one, two, scout = done.robots
    assert leader.distance_m == 0.0 and scout.distance_m < 1e-3, "the scout turns on the spot"
    assert one.distance_m > 0.05 and two.distance_m > 0.05
    assert abs(scout.final_pose[2]) > 0.5


def test_e_pucks_stop_short_of_each_other_on_their_time_of_flight_sensors(tmp_path: Path) -> None:
    """Two e-puck2s 0.4 m apart, face to face: Webots' ToF is a DistanceSensor of type
    "generic", which reads the distance its ray runs whatever colour it meets, so each reads the
    other's body at 0.4 - 0.037 - 0.034 m through the table (not 2.6 times as far, as an
    infra-red sensor sees an e-puck's grey shell), and each stops when it reads under 100 mm,
    about 9 cm from the other."""
    done, logs = run("tof_pair", tmp_path, 5.0)
    expected = tof_reading(0.4 - BODY_RADIUS - TOF_AHEAD)
    for name in ("west", "east"):
        assert logs[name]["first"] == pytest.approx(expected, rel=0.05), logs[name]
        assert logs[name]["max_speed"] == pytest.approx(7.536)
    west, east = done.robots
    gap = math.dist(west.final_pose[:2], east.final_pose[:2]) - 2 * BODY_RADIUS
    # The reading under 100 mm (the table's 0.089 m) less the sensor's 3 mm inside the body,
    # less at most a step's travel of both robots (2 x 3 mm).
    assert 0.075 < gap < 0.09, gap
    assert west.collisions == east.collisions == 0


def test_four_robots_meeting_head_on_stop_at_contact(tmp_path: Path) -> None:
    done, _ = run("crossing", tmp_path, 4.0)
    poses = [r.final_pose for r in done.robots]
    distances = [math.dist(a[:2], b[:2]) for i, a in enumerate(poses) for b in poses[i + 1 :]]
    assert min(distances) >= 2 * BODY_RADIUS - 1e-3, distances
    assert all(math.hypot(x, y) < 0.06 for x, y, _ in poses), "each reached the crossing"
    assert all(r.collisions >= 1 for r in done.robots)
    # Nobody pushes anybody: the four stop the same way round the centre.
    assert (
        max(math.hypot(x, y) for x, y, _ in poses) - min(math.hypot(x, y) for x, y, _ in poses)
        < 1e-3
    )


def test_robots_nested_in_a_transform_group_and_pose_read_fields_in_their_parents_frame(
    tmp_path: Path,
) -> None:
    """Webots gives a node's ``translation`` and ``rotation`` in its parent's frame: an
    e-puck 0.1 m ahead in a Transform turned a quarter turn at (0.5, 0.2) stands at (0.5, 0.3)
    in the world (``getPosition``) but reads its field as (0.1, 0, 0) plus the way it drove
    along its own x; a write of (0, 0, 0) puts it at the Transform's origin."""
    _, logs = run("nested", tmp_path, 2.0)
    start, end, back = (logs["census"][k] for k in ("start", "end", "put_back"))
    front = start["FRONT"]
    assert front["parent"] == "Transform" and start["BACK"]["parent"] == "Group"
    assert front["position"][:2] == pytest.approx([0.5, 0.304], abs=1e-3)
    assert front["translation"] == pytest.approx([0.104, 0.0, 0.0], abs=1e-3)
    assert front["rotation"][3] == pytest.approx(0.0, abs=1e-3)
    assert start["BACK"]["translation"] == pytest.approx([-0.096, 0.0, 0.0], abs=1e-3)
    assert end["LONER"]["translation"][0] == pytest.approx(-0.205, abs=2e-3)
    assert end["LONER"]["rotation"][3] == pytest.approx(math.pi, abs=1e-3)
    # Put back at their parents' origins, and one step on along their headings.
    assert back["FRONT"]["position"][:2] == pytest.approx([0.5, 0.203], abs=3e-3)
    assert back["LONER"]["position"][:2] == pytest.approx([-0.503, -0.5], abs=3e-3)
    assert back["FRONT"]["heading"] == pytest.approx(front["heading"], abs=1e-6)


def test_a_supervisor_tracks_every_robot_each_step(tmp_path: Path) -> None:
    """``getPosition`` of another robot's node reads where that robot is after the step, as the
    run's own track has it; ``getVelocity`` reads how it moved over that step."""
    done, logs = run("tracker", tmp_path, 2.5)
    tracker = logs["tracker"]
    for index, name, speed in ((1, "SLOW", 0.05), (2, "FAST", 0.11)):
        robot = done.robots[index]
        track, speeds = tracker["track"][name], tracker["speeds"][name]
        for step, ((x, y), (vx, vy, _)) in enumerate(zip(track, speeds), start=1):
            assert (x, y) == pytest.approx((robot.xs[step], robot.ys[step]), abs=1e-5)
            assert vx == pytest.approx((robot.xs[step] - robot.xs[step - 1]) / 0.032, abs=1e-3)
            assert vy == pytest.approx((robot.ys[step] - robot.ys[step - 1]) / 0.032, abs=1e-3)
        # Wheels at (2, 3) and (5, 6) rad/s: 5 and 11 cm/s, turning at 0.35 rad/s both.
        late = speeds[-1]
        assert math.hypot(late[0], late[1]) == pytest.approx(speed, rel=0.05)
        assert late[2] == pytest.approx(0.02 / 0.05685, rel=0.05)


def test_a_robot_reads_its_synchronization_field(tmp_path: Path) -> None:
    """Webots' ``getSynchronization`` (C: ``wb_robot_get_synchronization``) gives the robot's
    ``synchronization`` field; mazesim steps every robot in lockstep all the same."""
    _, logs = run("unsynced", tmp_path, 1.0)
    assert logs["synced"]["synchronization"] is True
    assert logs["unsynced"]["synchronization"] is False  # a C controller
    assert logs["unsynced_py"]["synchronization"] is False
    assert logs["synced"]["steps"] == logs["unsynced"]["steps"] == logs["unsynced_py"]["steps"]


def test_packets_reach_only_the_receivers_on_the_senders_channel(tmp_path: Path) -> None:
    """The E-puck PROTO's ``emitter_channel`` and ``receiver_channel`` fields: the caller sends
    on 2, only the robot listening on 2 hears it, each packet one step after it was sent, from
    the left as it faces."""
    _, logs = run("channels", tmp_path, 1.0)
    assert logs["caller"]["channels"] == [2, 1] and logs["tuned"]["channels"] == [1, 2]
    heard = logs["tuned"]["heard"]
    assert [step for step, _, _ in heard] == list(range(2, 31))
    assert all(number == step - 1 for step, number, _ in heard)
    assert logs["tuned"]["direction"] == pytest.approx([0.0, 1.0, 0.0], abs=1e-4)
    assert logs["default"]["heard"] == []
