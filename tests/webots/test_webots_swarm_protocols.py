"""Multi-robot Webots worlds in patterns swarm projects use, each run whole and checked against
what Webots does: a formation kept on the relative poses a supervisor reads with
``Node.getPose(leader)``, an average consensus over radios of limited range that a robot leaves,
a supervisor that changes another robot's ``controller`` field, a controller that fails while
the others run, an e-puck and an e-puck2 beside a Pioneer and a Thymio kept as obstacles, a
robot climbing a beacon's signal strength, LEDs and a Display per robot, and robots started in
contact (#33, #32)."""

from __future__ import annotations

import functools
import math
from pathlib import Path

import pytest

from mazesim.webots.native_controller import build
from swarm_project import BODY_RADIUS, run_project

PROJECT = Path(__file__).resolve().parent.parent / "data" / "webots-swarm-protocols"


run = functools.partial(run_project, PROJECT)


def test_followers_keep_their_slots_on_relative_poses_from_get_pose(tmp_path: Path) -> None:
    """``Node.getPose(fromNode)`` is the pose in ``fromNode``'s frame (Webots'
    ``wb_supervisor_node_get_pose(node, from_node)``): the followers steering by it close on
    their slots beside the leader."""
    _, logs = run("formation", tmp_path, 5.0)
    shepherd = logs["shepherd"]
    for relative, by_hand in zip(shepherd["relative"], shepherd["by_hand"]):
        assert relative == pytest.approx(by_hand, abs=1e-6)
    # The first relative poses are the world file's: wing_l 0.2 m behind and 0.25 m left.
    assert shepherd["relative"][0][:2] == pytest.approx([-0.2, 0.25], abs=0.01)
    assert max(shepherd["errors"]) < 0.03


def test_an_average_consensus_holds_its_sum_as_a_robot_leaves_its_range(tmp_path: Path) -> None:
    """Five robots 0.3 m apart in a row, radios of range 0.35 m: each hears its neighbours only
    (at 1 / 0.3^2), the values' sum is kept, and once n4 drives out of n3's range the four
    others agree on what is left while n4 keeps its value."""
    done, logs = run("consensus", tmp_path, 9.0)
    names = [f"n{i}" for i in range(5)]
    assert sorted(logs["n0"]["heard"]) == ["n1"]
    assert sorted(logs["n2"]["heard"]) == ["n1", "n3"]
    assert all(s == pytest.approx(1 / 0.3**2, rel=1e-4) for s in logs["n2"]["strengths"])
    assert logs["n0"]["range"] == pytest.approx(0.35)
    last_heard = max(logs["n3"]["heard"]["n4"])
    assert 61 < last_heard < 130 and max(logs["n4"]["heard"]["n3"]) == last_heard
    start_sum = sum(logs[n]["start"] for n in names)
    final = [logs[n]["values"][-1] for n in names]
    assert sum(final) == pytest.approx(start_sum, abs=1e-9)
    assert max(final[:4]) - min(final[:4]) < 1e-3
    assert final[4] == logs["n4"]["values"][last_heard - 1]
    assert [r.exit_status for r in done.robots] == [0] * 5


def test_a_supervisor_changes_another_robots_controller_field(tmp_path: Path) -> None:
    """Webots ends a robot's controller when a supervisor writes the robot's ``controller``
    field and starts the one named on the robot where it stands; an empty name starts none.
    The C controller started mid-run is built before the run, so that the run only starts it."""
    build(PROJECT / "controllers" / "spin" / "spin.c")
    done, logs = run("swap", tmp_path, 4.0)
    switcher = logs["switcher"]
    assert (switcher["before"], switcher["after"]) == ("forward", "spin")
    forward = logs["forward_worker"]
    assert forward["steps"] in (20, 21)
    spin = logs["spin"]
    assert spin["started"] == pytest.approx(forward["ended"], abs=0.033)
    assert spin["steps"] in (39, 40, 41)
    # The robot turned on the spot while "spin" ran: it went no farther forward.
    assert switcher["x_at_stop"] == pytest.approx(switcher["x_at_switch"], abs=0.005)
    assert logs["forward_other"]["steps"] == 125
    worker = next(r for r in done.robots if r.name == "worker")
    assert len(worker.restarts_s) == 2


def test_a_controller_that_fails_leaves_the_others_running(tmp_path: Path) -> None:
    done, logs = run("crash", tmp_path, 3.0)
    fragile, steady, tally = done.robots
    assert fragile.exit_status == 1 and "ZeroDivisionError" in (fragile.error or "")
    assert (steady.exit_status, tally.exit_status) == (0, 0)
    assert logs["steady"]["steps"] == 80
    assert logs["tally"]["steps"] == 94
    # Its controller ended after 80 steps with the wheels at 2 rad/s, which they keep to the
    # run's end (94 steps), as Webots keeps a motor's last commands.
    assert steady.distance_m == pytest.approx(2.0 * 0.02 * 94 * 0.032, rel=0.02)


def test_e_pucks_stop_before_a_pioneer_and_a_thymio_kept_as_obstacles(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    done, logs = run("mixed_fleet", tmp_path, 8.5)
    err = capfd.readouterr().err
    assert "Pioneer3dx" in err and "Thymio2" in err
    assert logs["second"]["max_speed"] == pytest.approx(7.536)
    assert logs["classic"]["max_speed"] == pytest.approx(6.28)
    for name in ("classic", "second"):
        assert logs[name]["stopped"] > 0 and logs[name]["peak"] > 300
    classic, second = done.robots[:2]
    assert classic.collisions == 0 and second.collisions == 0
    assert classic.final_pose[0] < -0.2 and second.final_pose[0] < -0.3 - 0.05


def test_robots_climb_a_beacons_signal_strength(tmp_path: Path) -> None:
    done, logs = run("gradient", tmp_path, 30.0)
    for name in ("seeker_a", "seeker_b"):
        assert logs[name]["arrived"] is not None
        robot = next(r for r in done.robots if r.name == name)
        x, y, _ = robot.final_pose
        assert math.hypot(x - 0.6, y - 0.2) < 0.12


def test_each_robot_lights_its_own_leds_and_draws_on_its_display(tmp_path: Path) -> None:
    _, logs = run("lights", tmp_path, 1.0)
    for i in range(3):
        log = logs[f"lamp{i}"]
        assert log["leds"] == log["pattern"]
        assert log["display"] == [64, 32]
        others = {f"lamp{j}" for j in range(3)} - {f"lamp{i}"}
        assert set(log["heard"]) == others
        for other in others:
            assert log["heard"][other] == logs[other]["pattern"]


def test_robots_started_in_contact_drive_apart(tmp_path: Path) -> None:
    done, logs = run("contact", tmp_path, 1.5)
    for robot in done.robots:
        assert robot.distance_m == pytest.approx(3.0 * 0.02 * 30 * 0.032, rel=0.05), robot.name
    poses = {r.name: r.final_pose for r in done.robots}
    names = sorted(poses)
    for a in names:
        for b in names:
            if a < b:
                gap = math.dist(poses[a][:2], poses[b][:2])
                assert gap >= 2 * BODY_RADIUS - 0.001, (a, b, gap)
    # Touching robots read each other at once.
    assert max(logs["west"]["first"]) > 300
