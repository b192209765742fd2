"""A third set of multi-robot Webots worlds, in patterns the first two left out, each run whole
and checked against what Webots documents: a rendezvous by radio signal strength and emitter
direction alone, a supervisor that resets the simulation while C robots drive, robots that
retune their own Emitter's channel and range and a Receiver on every channel, a Receiver
queue that overflows, a supervisor that turns every robot it finds towards the centre by its
``rotation`` field, robots stepping by 16, 32 and 64 ms in one world, a C++ robot talking to a
Python one, twelve robots of one controller, and a supervisor that labels, snapshots and saves
the world (#33, #32)."""

from __future__ import annotations

import functools
import itertools
import math
from pathlib import Path

import pytest
from PIL import Image

from mazesim.webots.importer import import_wbt
from swarm_project import BODY_RADIUS, run_project

PROJECT = Path(__file__).resolve().parent.parent / "data" / "webots-swarm-trials"


pytestmark = pytest.mark.usefixtures("own_cache")


run = functools.partial(run_project, PROJECT)


def test_robots_gather_by_signal_strength_and_emitter_direction(tmp_path: Path) -> None:
    """Each robot hears the others at 1 / d^2 from the direction of each in its own frame, and
    steering towards the loudest brings the three together without touching."""
    done, logs = run("rendezvous", tmp_path / "logs", 8.1)
    starts = {"a": (-0.4, 0.0, 0.0), "b": (0.4, 0.0, math.pi / 2), "c": (0.0, 0.5, math.pi)}
    for name, (x, y, yaw) in starts.items():
        for other, (ox, oy, _) in starts.items():
            if other == name:
                continue
            step, strength, direction = logs[name]["first"][other]
            d = math.dist((x, y), (ox, oy))
            assert step == 2 and strength == pytest.approx(1 / d**2, rel=1e-5)
            bearing = math.atan2(oy - y, ox - x) - yaw
            assert direction == pytest.approx([math.cos(bearing), math.sin(bearing), 0], abs=1e-4)
    poses = [r.final_pose[:2] for r in done.robots]
    assert max(math.dist(p, q) for p, q in itertools.combinations(poses, 2)) < 0.3
    assert [r.collisions for r in done.robots] == [0, 0, 0]


def test_a_supervisor_reset_puts_the_driving_robots_back_and_restarts_their_clocks(
    tmp_path: Path,
) -> None:
    """The reset asked at step 20 puts the runner back at its start after step 21, its clock
    and wheel encoder from 0, its motors back at position control (it stays there); the
    restart of the runner's controller asked at step 50 starts that controller again, which
    drives on from there, its devices new and its clock the world's (#33)."""
    done, logs = run("reset_restart", tmp_path / "logs", 4.0)
    x = {int(k): v for k, v in logs["boss"]["x"].items()}
    assert x[20] == pytest.approx(-0.5 + 20 * 5.0 * 0.02 * 0.032, abs=1e-4)
    assert all(x[step] == pytest.approx(-0.5, abs=1e-9) for step in range(21, 51))
    assert x[80] == pytest.approx(-0.5 + 30 * 5.0 * 0.02 * 0.032, abs=1e-4)
    assert logs["walker"]["clock_back_to"] == 0.0
    assert logs["walker"]["time"] == pytest.approx((100 - 21) * 0.032)
    assert logs["walker"]["encoder"] == pytest.approx(0.0, abs=1e-9)
    # The runner's second process started after the reset: its clock never went back, and
    # its encoder counts from where the first process's reset left it.
    assert (tmp_path / "logs" / "runner.starts").read_text() == "start\nstart\n"
    assert (tmp_path / "logs" / "walker.starts").read_text() == "start\n"
    assert logs["runner"]["clock_back_to"] == -1.0
    steps = logs["runner"]["steps"]
    assert logs["runner"]["encoder"] == pytest.approx(steps * 5.0 * 0.032, rel=1e-4)
    runner = next(r for r in done.robots if r.name == "runner")
    assert runner.restarts_s == [pytest.approx(50 * 0.032)]  # the run's clock, as imported_s
    assert all(r.exit_status == 0 for r in done.robots)


def test_robots_retune_their_own_radio_at_run_time(tmp_path: Path) -> None:
    """The caller's packets reach the hearer on channel 1, then on channel 2 once it moved
    there too, and not while the caller's range (0.3 m) is short of it; a range asked above
    maxRange is maxRange; a Receiver on channel -1 hears every channel."""
    _, logs = run("self_tuning", tmp_path / "logs", 2.0)
    assert logs["caller"]["range_asked_5"] == 0.6 and logs["caller"]["channel"] == 2
    expected = [*range(1, 11), *range(15, 21), *range(31, 40)]
    assert logs["hearer"]["heard"] == expected and logs["hearer"]["channel"] == 2
    assert logs["scanner"]["heard"] == list(range(1, 40))


def test_a_full_receiver_queue_drops_the_packets_beyond_its_buffer(tmp_path: Path) -> None:
    """The emitter (800 bytes a step) takes 8 of 10 packets of 100 bytes; the receiver (500
    bytes) keeps the first 5 of each step's, and keeps them while it is not read."""
    _, logs = run("overflow", tmp_path / "logs", 2.0)
    assert logs["flood"]["accepted_a_step"] == 8 and logs["flood"]["buffer"] == 800
    reads = {int(k): v for k, v in logs["sink"]["reads"].items()}
    assert reads[1] == []
    for step in range(2, 11):
        assert reads[step] == [10 * (step - 1) + i for i in range(5)]
    assert reads[21] == [100, 101, 102, 103, 104]


def test_a_supervisor_turns_every_robot_it_finds_by_its_rotation_field(tmp_path: Path) -> None:
    _, logs = run("face_centre", tmp_path / "logs", 3.0)
    turner = logs["turner"]
    assert turner["names"] == ["e1", "e2", "e3", "e4"]
    for name in turner["names"]:
        x, y = turner["at10"][name]
        axis_angle = turner["set"][name]
        assert axis_angle[:3] == [0.0, 0.0, 1.0]
        turn = axis_angle[3] - math.atan2(-y, -x)
        assert math.cos(turn) == pytest.approx(1.0, abs=1e-6)
        # 40 steps of 32 ms at 3 rad/s x 0.02 m, straight at the centre.
        closer = math.hypot(x, y) - math.hypot(*turner["at50"][name])
        assert closer == pytest.approx(40 * 0.032 * 0.06, abs=2e-3)


def test_robots_step_by_periods_of_their_own_in_one_world(tmp_path: Path) -> None:
    done, logs = run("mixed_steps", tmp_path / "logs", 3.0)
    assert logs["quick"]["times"] == pytest.approx([0.016 * k for k in range(1, 63)])
    assert logs["slow"]["times"] == pytest.approx([0.064 * k for k in range(1, 16)])
    assert (logs["quick"]["period"], logs["slow"]["period"]) == (16, 64)
    assert logs["middle"] == {"steps": 31, "first": 0.032}
    # Each drove at 4 rad/s x 0.02 m until its first step ending at or past 1 s.
    driven = [robot.distance_m / (4.0 * 0.02) for robot in done.robots]
    assert driven == pytest.approx([1.008, 1.024, 1.024], abs=1e-4)


def test_a_cpp_robot_and_a_python_robot_talk(tmp_path: Path) -> None:
    """Each "ping N" sent at step N is heard at N + 1 and its "pong N" is back at N + 2."""
    _, logs = run("cpp_pair", tmp_path / "logs", 2.0)
    assert logs["listener"]["heard"] == [[n + 1, f"ping {n}"] for n in range(1, 20)]
    assert logs["talker"]["back"] == [[n + 2, f"pong {n}"] for n in range(1, 19)]


def test_twelve_robots_of_one_controller_run_in_one_world_without_overlapping(
    tmp_path: Path,
) -> None:
    done, logs = run("crowd", tmp_path / "logs", 2.0)
    assert len(done.robots) == 12 and all(r.exit_status == 0 for r in done.robots)
    assert {log["steps"] for log in logs.values()} == {63}
    poses = [r.final_pose[:2] for r in done.robots]
    gaps = [math.dist(p, q) for p, q in itertools.combinations(poses, 2)]
    assert min(gaps) > 2 * BODY_RADIUS - 1e-3


def test_a_supervisor_saves_the_world_where_its_robots_are(tmp_path: Path) -> None:
    """``worldSave`` writes the world with each robot's ``translation`` where it stands (the
    file imports again with that start) and says True; ``setLabel`` is accepted and
    ``exportImage`` writes the view, here of a supervisor without a body."""
    logs_dir = tmp_path / "logs"
    _, logs = run("reporter", logs_dir, 2.0)
    assert logs["reporter"]["saved"] is True
    _, report = import_wbt(str(logs_dir / "saved.wbt"))
    poses = {robot["name"]: robot["pose"] for robot in report["robots"]}
    assert set(poses) == {"reporter", "one", "two"}
    assert poses["one"][0] == pytest.approx(logs["reporter"]["x_one"], abs=1e-6)
    assert poses["one"][0] == pytest.approx(20 * 3.0 * 0.02 * 0.032, abs=1e-4)
    assert poses["two"][:2] == pytest.approx([poses["one"][0], 0.3], abs=1e-6)
    assert poses["reporter"] == [0.0, 0.0, 0.0]
    assert logs["reporter"]["files"] == ["saved.wbt", "view.jpg"]
    with Image.open(logs_dir / "view.jpg") as view:
        assert (view.format, view.size) == ("JPEG", (400, 400))
