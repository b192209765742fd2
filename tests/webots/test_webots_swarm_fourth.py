"""A fourth set of multi-robot Webots worlds, in patterns the first three left out, each run
whole and checked against what Webots documents: two robots pushing a crate, a supervisor
removing a running robot, a supervisor importing a robot whose controller then talks, two
robots of one name, Emitters and Receivers with ``allowedChannels``, a C++ receiver draining
three C senders in one step, a C robot that cleans up and leaves while the others run on, the
keyboard typed to a world of three robots, and thirty robots of one controller (#33, #32)."""

from __future__ import annotations

import functools
import itertools
import json
import math
from pathlib import Path

import pytest

from mazesim.webots.keyboard import read_keys
from swarm_project import BODY_RADIUS, run_project

PROJECT = Path(__file__).resolve().parent.parent / "data" / "webots-swarm-fourth"

pytestmark = pytest.mark.usefixtures("own_cache")

run = functools.partial(run_project, PROJECT)

#: The e-puck's speed at 1 rad/s (its wheel radius, m).
WHEEL_RADIUS = 0.02


def test_two_robots_push_a_crate_ahead_of_them(tmp_path: Path) -> None:
    """Side by side at 3 rad/s they reach the crate 6.3 cm ahead after about 1 s and push it
    straight on for the rest of the 3 s, their front sensors against it at the end."""
    done, logs = run("push_box", tmp_path / "logs", 3.1)
    track = {int(step): position for step, position in logs["referee"].items()}
    assert track[1][:2] == pytest.approx([-0.15, 0.0])
    moved = track[max(track)][0] - track[1][0]
    # Their motors hold their speed against the crate's floor friction: it goes as far as
    # they drove past the 6.3 cm gap.
    driven = [r.distance_m for r in done.robots[:2]]
    assert driven == pytest.approx([94 * 0.032 * 3.0 * WHEEL_RADIUS] * 2, rel=0.01)
    assert moved == pytest.approx(min(driven) - 0.063, abs=1e-3)
    assert abs(track[max(track)][1]) < 0.005
    for name in ("left_pusher", "right_pusher"):
        assert max(logs[name]["front_at_start"]) < 150
        assert min(logs[name]["front_at_end"]) > 1000
    assert [r.exit_status for r in done.robots] == [0, 0, 0]


def test_a_removed_robot_stops_talking_and_its_controller_ends(tmp_path: Path) -> None:
    """``remove()`` at step 30: the watcher heard "alive N" each step until then and nothing
    after; the removed robot's step returned -1 and its controller ended."""
    done, logs = run("cull", tmp_path / "logs", 3.1)
    assert logs["warden"]["gone"] is True
    assert logs["warden"]["names"] == ["WorldInfo", "RectangleArena", "E-puck", "Robot"]
    heard = logs["watcher"]["heard"]
    assert heard == [[n + 1, f"alive {n}"] for n in range(1, 30)]
    assert logs["doomed"]["last_step"] in (30, 31)
    doomed = next(r for r in done.robots if r.name == "doomed")
    assert doomed.removed_s == pytest.approx(0.96) and doomed.exit_status == 0


def test_a_robot_imported_mid_run_starts_its_controller_on_the_running_clock(
    tmp_path: Path,
) -> None:
    done, logs = run("late_joiner", tmp_path / "logs", 2.1)
    assert logs["joiner"]["first_time"] == pytest.approx(20 * 0.032)
    assert logs["joiner"]["name"] == "newcomer"
    heard = logs["host"]["heard"]
    assert heard[0] == [22, "hello 0.672"]
    assert [step for step, _ in heard] == list(range(22, 22 + len(heard)))
    newcomer = next(r for r in done.robots if r.name == "newcomer")
    assert newcomer.imported_s == pytest.approx(0.64)
    assert logs["host"]["newcomer_at"][0] == pytest.approx(newcomer.final_pose[0], abs=1e-6)
    assert newcomer.distance_m == pytest.approx(
        logs["joiner"]["steps"] * 0.032 * 2.0 * WHEEL_RADIUS, abs=0.004
    )


def test_two_robots_of_one_name_both_run(tmp_path: Path) -> None:
    """Both E-pucks leave ``name`` out: both are "e-puck" to their controllers, as in Webots;
    the summary tells them apart."""
    done, logs = run("twins", tmp_path / "logs", 1.1)
    assert logs["twin3"]["name"] == logs["twin5"]["name"] == "e-puck"
    assert [r.name for r in done.robots] == ["e-puck(0)", "e-puck(1)"]
    distances = [r.distance_m for r in done.robots]
    assert distances == pytest.approx([32 * 0.032 * s * WHEEL_RADIUS for s in (3, 5)], abs=1e-4)


def test_allowed_channels_refuse_other_channels(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    """An Emitter allowed [1 3] stays on 1 when asked for 2 and moves to 3; one whose channel 5
    is not among [2 4] starts on 2; a Receiver allowed [3] stays on 3 when asked for 1. Each
    refusal prints Webots' error."""
    _, logs = run("allowed", tmp_path / "logs", 0.5)
    talker = logs["talker"]
    assert (talker["after_asking_2"], talker["after_asking_3"]) == (1, 3)
    assert talker["misfiled_channel"] == 2
    assert logs["ears"]["on3_channel"] == 3
    assert logs["ears"]["heard"] == {"on1": ["a", "b"], "on2": ["d"], "on3": ["c"]}
    err = capfd.readouterr().err
    for function, channel in (("wb_emitter_set_channel", 2), ("wb_receiver_set_channel", 1)):
        assert (
            f"Error: {function}() called with channel={channel}, which is not between allowed "
            "channels. Please use an allowed channel." in err
        )


def test_a_cpp_receiver_drains_three_c_senders_in_one_step(tmp_path: Path) -> None:
    _, logs = run("drain", tmp_path / "logs", 1.0)
    counts = logs["drainer"]["counts"]
    assert counts[0] == 0 and counts[1:21] == [6] * 20 and set(counts[21:]) == {0}
    packets = logs["drainer"]["packets"]
    assert sorted(packets) == sorted(
        f"{name}:{step}:{k}" for name in ("s1", "s2", "s3") for step in range(1, 21) for k in (0, 1)
    )


def test_a_robot_that_cleans_up_early_leaves_the_others_running(tmp_path: Path) -> None:
    done, logs = run("early_quit", tmp_path / "logs", 3.1)
    for name in ("stayer", "runner"):
        assert logs[name]["heard"] == [[n + 1, f"step {n}"] for n in range(1, 11)]
        assert logs[name]["steps"] == 93 and logs[name]["time"] == pytest.approx(3.008)
    quitter, stayer, _ = done.robots
    assert quitter.exit_status == 0
    assert quitter.final_pose[0] == pytest.approx(10 * 0.032 * 4.0 * WHEEL_RADIUS, abs=2e-4)
    assert stayer.distance_m == pytest.approx(94 * 0.032 * 2.0 * WHEEL_RADIUS, abs=1e-3)


def test_the_keyboard_reaches_the_robot_that_reads_it_while_the_others_run(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """UP held from 0.32 s for 0.64 s, LEFT from 1.28 s for 0.32 s: the pilot reads them at
    its steps 10-29 and 40-49 and drives and turns by them; the drones, which enable no
    keyboard, drive on."""
    from mazesim.webots.lockstep import run_world

    logs = tmp_path / "logs"
    logs.mkdir()
    monkeypatch.setenv("SWARM_LOG", str(logs))
    done = run_world(
        str(PROJECT / "worlds" / "teleop.wbt"),
        seconds=2.1,
        seed=5,
        keys=read_keys(PROJECT / "worlds" / "teleop_keys.txt"),
    )
    pilot = json.loads((logs / "pilot.json").read_text())
    assert pilot["keys"] == [[s, 315] for s in range(10, 30)] + [[s, 314] for s in range(40, 50)]
    pilot_run, one, two = done.robots
    assert pilot_run.final_pose[0] == pytest.approx(20 * 0.032 * 4.0 * WHEEL_RADIUS, abs=5e-3)
    assert pilot_run.final_pose[2] == pytest.approx(10 * 0.032 * 4.0 * WHEEL_RADIUS / 0.05685)
    assert one.distance_m == two.distance_m == pytest.approx(63 * 0.032 * 3.0 * WHEEL_RADIUS)


def test_thirty_robots_of_one_controller_run_to_the_end_apart(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    """They run apart, and what their one controller lacks (its fast turns in place) is said
    once for the world, naming five of them and counting the rest."""
    done, logs = run("thirty", tmp_path / "logs", 0.7)
    said = [line for line in capfd.readouterr().err.splitlines() if "wheel slip" in line]
    assert len(said) == 1
    assert "robots 't00', 't01', 't02', 't03', 't04' and 25 more (30 in all)" in said[0]
    assert len(done.robots) == len(logs) == 30
    assert all(r.exit_status == 0 for r in done.robots)
    assert {log["steps"] for log in logs.values()} == {20}
    poses = [r.final_pose[:2] for r in done.robots]
    gaps = [math.dist(p, q) for p, q in itertools.combinations(poses, 2)]
    assert min(gaps) > 2 * BODY_RADIUS - 1e-3


def test_a_follower_sees_the_red_mast_of_its_leader(tmp_path: Path) -> None:
    """The follower's camera finds the leader's red mast (a Solid in its turretSlot) 0.25 m
    ahead at its first step and keeps it in sight at every step, following it as it drives
    off and arcs left: it ends where the mast (6 cm wide) spans the 12 columns at which its
    controller stops, about 0.31 m from the lens (0.33 m between the robots' centres)."""
    done, logs = run("colour_follow", tmp_path / "logs", 8.1)
    seen = logs["follower"]
    assert seen["first_seen"] == 1
    assert len(seen["widths"]) == seen["steps"]
    leader, follower = done.robots
    assert follower.distance_m > 0.15
    assert 0.28 < math.dist(leader.final_pose[:2], follower.final_pose[:2]) < 0.38
