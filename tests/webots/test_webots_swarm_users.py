"""A seventh set of multi-robot Webots worlds written as users write them, each run whole and
checked against what Webots documents: a C leader and Python followers on a channel they move
to, a supervisor that moves robots by their translation and resets their physics, e-pucks a
supervisor imports while the world runs, a robot removed while another messages it, ten e-pucks
aggregating under a C supervisor that reads every one's position, controllers stepping by
different multiples of the basic time step, controllerArgs in Python and C, an unsynchronized
robot whose robot window is absent, a box a supervisor puts in a robot's path, and a C follower
that changes channel when its leader says so (#33)."""

from __future__ import annotations

import functools
import itertools
import math
from pathlib import Path

import pytest

from swarm_project import BODY_RADIUS, run_project

PROJECT = Path(__file__).resolve().parent.parent / "data" / "webots-swarm-users"
#: The e-puck's wheel radius (m): its wheels' bounding cylinder in Webots' E-puck.proto.
WHEEL_RADIUS = 0.02
#: Where a GPS in the E-puck's turretSlot sits ahead of the robot's origin (m).
TURRET_X = -0.0095

run = functools.partial(run_project, PROJECT)


def test_python_followers_hear_a_c_leader_on_the_channel_both_moved_to(tmp_path: Path) -> None:
    """Packet ``k``, sent after the leader's step ``k``, is in the followers' queue when their
    step ``k + 1`` returns, one a step, at 1 / r^2 and from the leader's direction in the
    follower's frame (ahead, left); the follower left on channel 1 hears nothing."""
    done, logs = run("leader_follow", tmp_path, 2.0)
    assert logs["leader"] == {"sent": 60, "channel": 3}
    for name, direction in (("behind", [1.0, 0.0, 0.0]), ("above", [0.0, 1.0, 0.0])):
        log = logs[name]
        assert log["channel"] == 3
        assert log["lengths"] == [0] + [1] * 59
        assert [(step, number) for step, number, _, _ in log["heard"]] == [
            (k + 1, k) for k in range(1, 60)
        ]
        first = log["heard"][0]
        assert first[2] == pytest.approx(1 / 0.3**2 if name == "behind" else 1 / 0.4**2, rel=0.03)
        assert first[3] == pytest.approx(direction, abs=0.02)
    assert logs["deaf"]["channel"] == 1 and logs["deaf"]["heard"] == []
    assert [r.exit_status for r in done.robots] == [0, 0, 0, 0]


def test_a_supervisor_moves_robots_by_their_translation_and_resets_their_physics(
    tmp_path: Path,
) -> None:
    """Moved after the supervisor's 20th step, the runner's GPS reads its new place after its
    21st, having driven on from there for one step at most; the fields and getPosition agree."""
    _, logs = run("teleport", tmp_path, 1.0)
    track = [[x - TURRET_X, y] for x, y, _ in logs["runner"]["track"]]
    step = 4.0 * WHEEL_RADIUS * 0.016
    assert track[19][0] == pytest.approx(-0.5 + 20 * step, abs=1e-4)
    x, y = track[20]
    assert 0.3 - 1e-6 <= x <= 0.3 + step + 1e-6 and y == pytest.approx(0.3, abs=1e-6)
    assert track[-1][0] == pytest.approx(x + (len(track) - 21) * step, abs=1e-4)
    mover = logs["mover"]
    assert mover["before"][:2] == pytest.approx(track[19], abs=1e-6)
    for (field, position), gps in zip(mover["after"], track[20:23]):
        assert field[:2] == pytest.approx(gps, abs=1e-6)
        assert position[:2] == pytest.approx(gps, abs=1e-6)
    assert mover["still_after"][:2] == pytest.approx([0.0, -0.5], abs=1e-6)
    assert logs["still"]["track"][-1][:2] == pytest.approx([TURRET_X, -0.5], abs=1e-6)


def test_e_pucks_imported_at_run_time_start_their_controllers_and_are_heard(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    done, logs = run("spawned_pingers", tmp_path, 1.5)
    spawner = logs["spawner"]
    assert spawner["count_before"] == 4 and spawner["counts"] == [5, 6]
    assert spawner["p1"][:2] == pytest.approx([0.3, 0.5], abs=1e-6)
    assert logs["pinger1"]["argv"] == ["1"] and logs["pinger2"]["argv"] == ["2"]
    # Imported after the spawner's 10th (20th) step: its controller's first step ends at the
    # next step's end or later, on the running clock.
    assert 0.32 < logs["pinger1"]["first"] <= 0.32 + 2 * 0.032 + 1e-9
    assert 0.64 < logs["pinger2"]["first"] <= 0.64 + 2 * 0.032 + 1e-9
    heard = logs["listener"]["first"]
    assert heard["1"][1] == "1:1" and heard["2"][1] == "2:1"
    assert heard["2"][0] - heard["1"][0] == 10
    assert [r.name for r in done.robots][:2] == ["listener", "spawner"]
    # The imports work in a run of the whole world: no "missing:" statement says otherwise.
    assert "missing:" not in capfd.readouterr().err


def test_a_robot_removed_while_another_messages_it_leaves_the_others_talking(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    done, logs = run("removed_target", tmp_path, 1.5)
    assert logs["culler"] == {"count_before": 6, "count_after": 5, "gone": True}
    assert logs["caller"]["sent"] == 40
    # Every packet of steps 1 to 39 reaches the bystander, one a step.
    assert logs["bystander"]["count"] == 39 and logs["bystander"]["first"]["caller"][0] == 2
    # The target heard the caller until it was taken out after the culler's 15th step.
    assert (
        logs["target"]["steps"] in (15, 16)
        and logs["target"]["count"] == logs["target"]["steps"] - 1
    )
    by_name = {r.name: r for r in done.robots}
    assert by_name["caller"].exit_status == by_name["bystander"].exit_status == 0
    assert "missing:" not in capfd.readouterr().err


def test_ten_e_pucks_aggregate_and_a_c_supervisor_reads_where_each_one_is(
    tmp_path: Path,
) -> None:
    """Ten copies of one controller drive on circles and turn away from what they see ahead;
    after 300 steps no two overlap, and the C supervisor's ``wb_supervisor_node_get_position``,
    orientation and translation field say where each robot's run ends."""
    done, logs = run("aggregation", tmp_path, 300 * 0.032)
    robots = [r for r in done.robots if r.name.startswith("a")]
    assert len(robots) == 10 and all(logs[f"a{i}"]["steps"] == 300 for i in range(10))
    census = logs["census"]
    assert census["steps"] == 300
    for robot, seen in zip(robots, census["robots"]):
        x, y, yaw = robot.final_pose
        assert seen[:2] == pytest.approx([x, y], abs=1e-5), robot.name
        assert seen[5:7] == pytest.approx([x, y], abs=1e-5), robot.name
        # The orientation matrix's first column is the robot's x axis: (cos yaw, sin yaw).
        assert seen[3:5] == pytest.approx([math.cos(yaw), math.sin(yaw)], abs=1e-4), robot.name
    for a, b in itertools.combinations(robots, 2):
        gap = math.dist(a.final_pose[:2], b.final_pose[:2])
        assert gap > 2 * BODY_RADIUS - 1e-3, (a.name, b.name)
    assert all(r.distance_m > 0.1 for r in robots)


def test_controllers_stepping_by_multiples_of_the_basic_step_meet_on_one_clock(
    tmp_path: Path,
) -> None:
    """Basic step 8 ms; controllers step by 8, 24 (C) and 40 ms. Each one's clock reads its
    multiples; a packet sent after the 40 ms robot's step at t is read by the 8 ms robot at
    t + 8 ms, and by the 40 ms robot from the 8 ms one 40 ms after its previous step."""
    _, logs = run("multiples", tmp_path, 0.6)
    fast, slow, middle = logs["fast"], logs["slow"], logs["middle"]
    assert fast["times"] == pytest.approx([0.008 * k for k in range(1, 7)])
    assert slow["times"] == pytest.approx([0.04 * k for k in range(1, 7)])
    assert middle["times"] == pytest.approx([0.024 * k for k in range(1, 7)])
    assert (fast["steps"], middle["steps"], slow["steps"]) == (62, 20, 12)
    from_slow = [[read, sent] for read, name, sent in fast["heard"] if name == "slow"]
    for (read, sent), expected in zip(from_slow, slow["times"]):
        assert (read, sent) == pytest.approx((expected + 0.008, expected))
    assert len(from_slow) == slow["steps"]
    # The slow robot reads, after its step at t, the fast one's five packets sent since t - 40.
    at_second = [sent for read, name, sent in slow["heard"] if read == pytest.approx(0.08)]
    assert at_second == pytest.approx([0.04, 0.048, 0.056, 0.064, 0.072])


def test_controller_args_reach_python_and_c_controllers(tmp_path: Path) -> None:
    done, logs = run("arguments", tmp_path, 1.5)
    assert logs["py_quick"]["argv"] == ["--speed", "5.5", "two words"]
    assert logs["py_plain"]["argv"] == [] and logs["py_plain"]["speed"] == 1.0
    assert logs["c_quick"] == {"argc": 4, "speed": 2.5, "last": "x y"}
    # 32 steps of 32 ms: the first step that ends at 1 s or later ends at 1.024 s.
    assert logs["py_quick"]["encoder"] == pytest.approx(5.5 * 1.024, rel=1e-3)
    distances = {r.name: r.distance_m for r in done.robots}
    for name, speed in (("py_quick", 5.5), ("py_plain", 1.0), ("c_quick", 2.5)):
        assert distances[name] == pytest.approx(speed * WHEEL_RADIUS * 1.024, rel=0.03), name


def test_an_unsynchronized_robot_without_its_robot_window_runs_beside_a_synchronized_one(
    tmp_path: Path,
) -> None:
    done, logs = run("unsynced_windowless", tmp_path, 1.5)
    loner, paced = logs["loner"], logs["paced"]
    assert loner["synchronization"] is False and paced["synchronization"] is True
    assert loner["times"] == pytest.approx([0.064, 0.128, 0.192]) and loner["steps"] == 15
    assert paced["times"] == pytest.approx([0.016, 0.032, 0.048]) and paced["steps"] == 62
    assert [r.exit_status for r in done.robots] == [0, 0]


def test_a_box_put_in_a_robots_path_is_pushed_and_stops_when_the_robot_does(
    tmp_path: Path,
) -> None:
    """The supervisor puts the box 0.1 m ahead of the pusher and resets its physics; the pusher
    meets it and pushes it on at its own speed; once the pusher stops (1.5 s), the floor's
    Coulomb friction (Webots' default contact, coulombFriction 1) stops the box within
    v^2 / (2 g) = 0.35 mm."""
    _, logs = run("placed_box", tmp_path, 2.5)
    xs = logs["box_mover"]["xs"]
    assert xs[4] == pytest.approx(0.1, abs=1e-6)
    speed = 4.0 * WHEEL_RADIUS
    # Pushed: the box moves at the robot's speed near the end of the push.
    assert (xs[90] - xs[80]) / (10 * 0.016) == pytest.approx(speed, rel=0.05)
    stop = round(1.5 / 0.016)
    coast = xs[-1] - xs[stop]
    assert 0.0 <= coast < speed**2 / (2 * 9.81) + 0.0016, coast
    assert xs[-1] == xs[-20]


def test_a_c_follower_changes_channel_when_its_leader_says_so(tmp_path: Path) -> None:
    """The leader sends "hop 5" on channel 1 after its 10th step, then moves to channel 5; the
    C follower reads it at its 11th step and moves too: it hears every packet, the later ones
    on channel 5, at 1 / 0.25^2 from ahead; the robot left on channel 1 hears none
    after the hop."""
    _, logs = run("channel_hop", tmp_path, 1.2)
    heard = logs["tagalong"]["heard"]
    assert [(step, channel, text) for step, channel, text, *_ in heard[:10]] == [
        (k + 1, 1, f"hopper:{k}") for k in range(1, 10)
    ] + [(11, 1, "hop 5")]
    assert [(step, channel, text) for step, channel, text, *_ in heard[10:]] == [
        (k + 1, 5, f"hopper:{k}") for k in range(11, 30)
    ]
    assert all(s == pytest.approx(1 / 0.25**2, rel=1e-4) for _, _, _, s, _, _ in heard)
    assert heard[0][4:] == pytest.approx([1.0, 0.0], abs=1e-4)
    behind = logs["left_behind"]
    assert behind["count"] == 10 and behind["first"]["hopper"][0] == 2
