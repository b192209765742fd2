"""A Webots world with several robots, run as Webots runs it: each robot's controller in its own
process, in lockstep, talking over Emitter and Receiver."""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path
from typing import Any

import pytest

from mazesim.webots.lockstep import controller_of, run_world
from mazesim_process import mazesim_command

SWARM = Path(__file__).resolve().parent.parent / "data" / "webots-swarm"
WORLD = SWARM / "worlds" / "leader_followers.wbt"
C_CONTROLLERS = Path(__file__).resolve().parent.parent / "data" / "controllers"


@pytest.fixture(scope="module")
def leader_and_followers(tmp_path_factory: pytest.TempPathFactory) -> tuple[object, Path]:
    logs = tmp_path_factory.mktemp("swarm")
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("SWARM_LOG", str(logs))
        run = run_world(str(WORLD), seconds=10.0, seed=3)
    return run, logs


def test_every_robot_runs_its_own_controller(leader_and_followers: tuple[object, Path]) -> None:
    run, logs = leader_and_followers
    assert [r.name for r in run.robots] == ["leader", "near", "far"]  # type: ignore[attr-defined]
    assert [Path(str(r.controller)).name for r in run.robots] == [  # type: ignore[attr-defined]
        "leader.py",
        "follower.py",
        "follower.py",
    ]
    assert [r.exit_status for r in run.robots] == [0, 0, 0]  # type: ignore[attr-defined]
    assert run.steps == 60  # type: ignore[attr-defined]
    # Module-level state is each process's own: each follower heard only its own orders.
    near = json.loads((logs / "near.json").read_text())
    assert near["orders"] == ["go"] * 30 + ["stop"] * 29


def test_orders_arrive_one_step_later_and_only_within_range(
    leader_and_followers: tuple[object, Path],
) -> None:
    run, logs = leader_and_followers
    near = json.loads((logs / "near.json").read_text())
    far = json.loads((logs / "far.json").read_text())
    # Sent after the leader's first step, heard when the follower's second step returns.
    assert near["first_heard"] == 2
    strength, direction = near["strengths"]
    assert strength == pytest.approx(1 / 0.3**2)
    assert direction == pytest.approx([0.0, -1.0, 0.0], abs=1e-9), "the leader is on its right"
    # 0.9 m away, beyond the 0.8 m the leader sets its emitter's range to: nothing arrives.
    assert far["first_heard"] is None and far["orders"] == []
    leader = json.loads((logs / "leader.json").read_text())
    # Acknowledgements on channel 2 come from the near follower only, one step after each order
    # it heard (the last order's acknowledgement is still on its way when the leader stops).
    assert set(leader["acknowledgements"]) == {"near go", "near stop"}
    assert leader["acknowledgements"].count("near go") == 30


def test_the_followers_obey(leader_and_followers: tuple[object, Path]) -> None:
    run, _ = leader_and_followers
    leader, near, far = run.robots  # type: ignore[attr-defined]
    assert leader.distance_m < 1e-6, "the leader does not drive"
    assert far.distance_m < 1e-6, "the far follower heard no order"
    # The near follower drove forward (+x) while told "go", then stopped.
    assert 0.04 < near.final_pose[0] < 0.12
    assert near.final_pose[1] == pytest.approx(0.3, abs=0.01)
    assert near.xs[-1] == pytest.approx(near.xs[-10], abs=1e-4), "stopped at the end"
    assert len(near.xs) == run.steps + 1  # type: ignore[attr-defined]


def test_controllers_are_found_in_the_project_or_given() -> None:
    robot = {"name": "near", "def_name": "NEAR", "controller": "follower"}
    found, _ = controller_of(robot, str(WORLD), {})
    assert found == str(SWARM / "controllers" / "follower" / "follower.py")
    given, _ = controller_of(robot, str(WORLD), {"NEAR": "other.py"})
    assert Path(str(given)).name == "other.py"
    none, why = controller_of({**robot, "controller": "<extern>"}, str(WORLD), {})
    assert none is None and "--robot-controller near=FILE" in why
    none, why = controller_of({**robot, "controller": "void"}, str(WORLD), {})
    assert none is None and why == "no controller"


def test_a_robot_writing_no_name_is_given_a_controller_by_the_name_webots_gives_it(
    capsys: pytest.CaptureFixture[str],
) -> None:
    # An E-puck writing no name field is "e-puck" in the summary and to getName(), but
    # --robot-controller e-puck=FILE did not reach it; a robot with controller "" could not be
    # given one at all; a NAME matching no robot was ignored without a word.
    e_puck = {"model": "E-puck", "controller": "<extern>"}
    given, _ = controller_of(e_puck, str(WORLD), {"e-puck": "fwd.py"})
    assert Path(str(given)).name == "fwd.py"
    none, why = controller_of(e_puck, str(WORLD), {})
    assert none is None and "--robot-controller e-puck=FILE" in why
    given, _ = controller_of({**e_puck, "controller": ""}, str(WORLD), {"e-puck": "fwd.py"})
    assert Path(str(given)).name == "fwd.py"
    from mazesim.webots.lockstep import _say_unmatched

    _say_unmatched({"e-puck": "fwd.py", "epuck": "fwd.py"}, [e_puck], str(WORLD))
    said = capsys.readouterr().err
    assert "robot 'epuck', but no robot" in said and "'e-puck' (DEF -" in said, said
    assert "robot 'e-puck'," not in said


def test_a_controller_field_with_a_typo_is_told_the_project_controller_meant(
    tmp_path: Path,
) -> None:
    """A world's ``controller "wandr"`` beside ``controllers/wander/``: the robot stands still,
    and the note names the controller folder meant, as a mistyped file on the command line is."""
    world = tmp_path / "worlds" / "w.wbt"
    world.parent.mkdir()
    world.write_text("#VRML_SIM R2023b utf8\n")
    for name in ("wander", "follow_line"):
        (tmp_path / "controllers" / name).mkdir(parents=True)
        (tmp_path / "controllers" / name / f"{name}.py").write_text("pass\n")
    none, why = controller_of({"name": "e-puck", "controller": "wandr"}, str(world), {})
    assert none is None
    assert why == (
        "no controller controllers/wandr/wandr.py, .c, .cpp, .cc, .cxx, .bsg "
        "(did you mean 'wander'?)"
    )
    _, far = controller_of({"name": "e-puck", "controller": "gripper"}, str(world), {})
    assert far == "no controller controllers/gripper/gripper.py, .c, .cpp, .cc, .cxx, .bsg"


def test_a_robot_whose_controller_is_java_or_matlab_says_so(tmp_path: Path) -> None:
    """Webots' MATLAB and Java example worlds: a robot whose controller folder holds only a
    MATLAB or Java file stands still, and its note names the language, as a run of that
    controller alone does, rather than a missing controller."""
    world = tmp_path / "worlds" / "example.wbt"
    world.parent.mkdir()
    world.write_text("#VRML_SIM R2023b utf8\n")
    for name, suffix in (("matlab", ".m"), ("Slave", ".java"), ("blink", ".bsg")):
        (tmp_path / "controllers" / name).mkdir(parents=True)
        (tmp_path / "controllers" / name / f"{name}{suffix}").write_text("% its code\n")
    none, why = controller_of({"name": "e-puck", "controller": "matlab"}, str(world), {})
    assert none is None
    assert why == "a MATLAB controller controllers/matlab/matlab.m, which mazesim does not run"
    none, why = controller_of({"name": "robot1", "controller": "Slave"}, str(world), {})
    assert none is None and why.startswith("a Java controller controllers/Slave/Slave.java")
    # A BotStudio automaton is run (mazesim.webots.botstudio).
    found, _ = controller_of({"name": "e-puck", "controller": "blink"}, str(world), {})
    assert found == str(tmp_path / "controllers" / "blink" / "blink.bsg")
    none, why = controller_of({"name": "e-puck", "controller": "matlab"}, str(world), {})
    # A world run says so among what its robot lacks, as the run of a controller whose Python
    # package is not installed does; a robot without a controller lacks nothing.
    world.write_text(
        '#VRML_SIM R2023b utf8\nRectangleArena { }\nE-puck { controller "matlab" }\n'
        'E-puck { translation 0.2 0 0 name "e-puck(1)" controller "void" }\n'
    )
    run = run_world(str(world), seconds=0.2)
    assert [robot.missing for robot in run.robots] == [(why,), ()]
    assert run.robots[0].distance_m == 0.0


def test_a_c_controller_is_found_in_its_webots_folder(tmp_path: Path) -> None:
    (tmp_path / "worlds").mkdir()
    (tmp_path / "controllers" / "avoid").mkdir(parents=True)
    (tmp_path / "controllers" / "avoid" / "avoid.c").write_text("int main(void) { return 0; }\n")
    world = str(tmp_path / "worlds" / "w.wbt")
    found, _ = controller_of({"name": "e", "controller": "avoid"}, world, {})
    assert found == str(tmp_path / "controllers" / "avoid" / "avoid.c")
    none, why = controller_of({"name": "e", "controller": "absent"}, world, {})
    assert none is None and "absent.py, .c, .cpp, .cc, .cxx, .bsg" in why


def test_a_cpp_controller_in_a_cc_file_is_found_in_its_webots_folder(tmp_path: Path) -> None:
    """Webots' default Makefile compiles ``.cc`` and ``.cxx`` C++ sources too: a controller
    folder whose main file is ``NAME.cc`` runs it, in a world run and a run of one robot."""
    from mazesim.webots.runner import controller_file

    (tmp_path / "worlds").mkdir()
    folder = tmp_path / "controllers" / "bidder"
    folder.mkdir(parents=True)
    (folder / "bidder.cc").write_text("int main() { return 0; }\n")
    world = str(tmp_path / "worlds" / "w.wbt")
    found, why = controller_of({"name": "e", "controller": "bidder"}, world, {})
    assert (found, why) == (str(folder / "bidder.cc"), "")
    assert controller_file(folder) == str(folder / "bidder.cc")


def test_a_controller_its_makefile_builds_from_other_sources_is_found(tmp_path: Path) -> None:
    """Webots' Makefile.include names the program after the folder whatever its sources are
    called: a folder holding ``main.cpp`` and a class its ``CXX_SOURCES`` lists (MTRN4110's
    explorers) runs the source defining ``main``; a Makefile listing none builds the folder's
    own sources; a folder whose sources define no ``main``, or without a Makefile, has none."""
    from mazesim.webots.runner import controller_file

    (tmp_path / "worlds").mkdir()
    world = str(tmp_path / "worlds" / "w.wbt")
    folder = tmp_path / "controllers" / "explorer"
    folder.mkdir(parents=True)
    (folder / "Moves.cpp").write_text("int forward() { return 1; }\n")
    (folder / "main.cpp").write_text("int forward();\nint main(int argc, char **argv) {}\n")
    robot = {"name": "e", "controller": "explorer"}
    none, why = controller_of(robot, world, {})
    assert none is None and "explorer.py, .c" in why, "no Makefile: nothing Webots builds"
    (folder / "Makefile").write_text("CXX_SOURCES = Moves.cpp \\\n  main.cpp\ninclude x\n")
    assert controller_of(robot, world, {}) == (str(folder / "main.cpp"), "")
    assert controller_file(folder) == str(folder / "main.cpp")
    (folder / "Makefile").write_text("include $(WEBOTS_HOME)/resources/Makefile.include\n")
    assert controller_file(folder) == str(folder / "main.cpp"), "the folder's own sources"
    (folder / "main.cpp").write_text("int forward();\nint remain(int n) { return n; }\n")
    none, why = controller_of(robot, world, {})
    assert none is None and "explorer.py, .c" in why


@pytest.mark.skipif(shutil.which("gcc") is None, reason="needs gcc")
def test_c_controllers_drive_every_robot_of_a_world_of_several(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Each robot's C controller runs in its own process against the shared world, as a Python
    one does (not on a world of its own, which left the other robots standing)."""
    monkeypatch.setenv("MAZESIM_CACHE", str(tmp_path / "cache"))
    avoider = str(C_CONTROLLERS / "c_wall_avoider" / "c_wall_avoider.c")
    run = run_world(
        str(SWARM / "worlds" / "head_on.wbt"),
        seconds=3.0,
        controllers={"west": avoider, "east": avoider},
    )
    west, east = run.robots
    for robot in (west, east):
        assert robot.controller == avoider and robot.exit_status == 0, robot.error
        assert robot.distance_m > 0.05, f"{robot.name} moved under its C controller"
        assert len(robot.xs) == len(west.xs), "both stepped in lockstep"
    closest = min(
        ((x0 - x1) ** 2 + (y0 - y1) ** 2) ** 0.5
        for x0, y0, x1, y1 in zip(west.xs, west.ys, east.xs, east.ys)
    )
    assert closest > 0.065, "bodies of about 7.4 cm across never pass through each other"


def run_beside_an_avoider(
    tmp_path: Path, name: str, source: str, suffix: str = ".c"
) -> tuple[Any, Any]:
    """The head-on world run for a second: the west robot on the controller ``source`` (in
    ``controllers/NAME/NAME.c``, or ``suffix``), the east one on the wall avoider; their runs."""
    own = tmp_path / "controllers" / name / f"{name}{suffix}"
    own.parent.mkdir(parents=True)
    own.write_text(source)
    avoider = str(C_CONTROLLERS / "c_wall_avoider" / "c_wall_avoider.c")
    run = run_world(
        str(SWARM / "worlds" / "head_on.wbt"),
        seconds=1.0,
        controllers={"west": str(own), "east": avoider},
    )
    west, east = run.robots
    return west, east


@pytest.mark.skipif(shutil.which("gcc") is None, reason="needs gcc")
def test_a_world_run_says_at_its_start_what_a_robots_controller_lacks(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setenv("MAZESIM_CACHE", str(tmp_path / "cache"))
    west, east = run_beside_an_avoider(
        tmp_path,
        "ranging",
        "#include <webots/robot.h>\n#include <webots/microphone.h>\n"
        "int main(void) { wb_robot_init(); while (wb_robot_step(32) != -1) {} return 0; }\n",
    )
    assert any("webots/microphone.h" in missing for missing in west.missing)
    assert east.missing == ()
    said = capsys.readouterr().err
    assert "mazesim: missing: robot 'west':" in said and "webots/microphone.h" in said
    assert "controller not run" in west.error and west.distance_m == 0.0
    assert east.distance_m > 0.0, "the other robot runs on"


@pytest.mark.skipif(shutil.which("gcc") is None, reason="needs gcc")
def test_a_robot_whose_c_controller_does_not_compile_stands_still_and_the_others_run(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """As in Webots, a controller that does not build leaves its own robot without a controller;
    the world's other robots run (the run stopped before any step)."""
    monkeypatch.setenv("MAZESIM_CACHE", str(tmp_path / "cache"))
    west, east = run_beside_an_avoider(
        tmp_path,
        "broken",
        "#include <webots/robot.h>\nint main(void) { wb_robot_init(); this is not C; return 0; }\n",
    )
    (statement,) = west.missing
    assert "C controller broken.c does not compile here" in statement and "error:" in statement
    assert "mazesim: missing: robot 'west':" in capsys.readouterr().err
    assert "controller not run" in west.error and west.distance_m == 0.0
    assert east.missing == () and east.distance_m > 0.0, "the other robot runs on"


def test_a_supervisor_sees_and_moves_every_robot_and_its_own_emitter_reaches_them(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    run = run_world(str(SWARM / "worlds" / "shepherd.wbt"), seconds=10.0)
    shepherd, stray, flock = run.robots
    assert [r.exit_status for r in run.robots] == [0, 0, 0]
    assert stray.controller is None and stray.note == "no controller"
    seen = json.loads((tmp_path / "shepherd.json").read_text())
    assert seen["stray"] == pytest.approx([-1.0, -1.0, 0.0], abs=1e-6)
    assert seen["flock_start"] == pytest.approx([1.0, 1.0, 0.0], abs=1e-6)
    # The Emitter node's own fields: channel 1, and Webots' default range -1 (no limit).
    assert (seen["channel"], seen["range"]) == (1, -1.0)
    assert stray.final_pose[:2] == pytest.approx((0.5, -0.5), abs=1e-6)
    # The flock e-puck, 1.4 m from the shepherd, heard "go" and drove; the shepherd saw it move.
    assert flock.final_pose[0] > 1.03
    assert seen["flock_end"][0] == pytest.approx(flock.xs[40], abs=1e-6)
    assert shepherd.distance_m == 0.0


def _beacon_heard(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, world: str, beacon: str | None = None
) -> dict[str, dict[str, int]]:
    """Runs a world where a beacon sends 20 packets from each of its infra-red and radio
    emitters (its controller ``beacon``, or the Python one) and the other robots count what
    their radio and infra-red receivers hear, each only its own type's packets: their counts
    by name."""
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    monkeypatch.setenv("MAZESIM_CACHE", str(tmp_path / "cache"))
    run = run_world(
        str(SWARM / "worlds" / f"{world}.wbt"),
        seconds=2.0,
        controllers={"beacon": beacon} if beacon else None,
    )
    assert [r.exit_status for r in run.robots] == [0] * len(run.robots)
    return {
        r.name: json.loads((tmp_path / f"{r.name}.json").read_text())
        for r in run.robots
        if r.name != "beacon"
    }


BOTH = {"infra-red": 20, "radio": 20}
RADIO = {"radio": 20}


@pytest.mark.parametrize(
    ("world", "heard"),
    [
        # The wall stands between the beacon and "behind".
        ("beacon_wall", {"behind": RADIO, "beside": BOTH}),
        # Three e-pucks in a row: the middle one's body stands between the beacon and "behind";
        # neither the sender's nor the middle one's own body stops what reaches the middle one.
        ("beacon_in_a_row", {"middle": BOTH, "behind": RADIO}),
        # A movable box (a Solid with physics) stands between the beacon and "behind".
        ("beacon_box", {"behind": RADIO, "beside": BOTH}),
    ],
)
def test_a_wall_a_robot_or_a_box_between_stops_infra_red_packets_not_radio_packets(
    world: str, heard: dict[str, Any], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    assert _beacon_heard(tmp_path, monkeypatch, world) == heard


@pytest.mark.parametrize("language", ["python", "c"])
def test_an_infra_red_emitter_sends_only_within_its_aperture(
    language: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    if language == "c" and shutil.which("gcc") is None:
        pytest.skip("needs gcc")
    beacon = str(C_CONTROLLERS / "c_beacon" / "c_beacon.c") if language == "c" else None
    # Both emitters have an aperture of 1 rad around the beacon's heading (east); the radio
    # one's is ignored, as Webots ignores it.
    heard = _beacon_heard(tmp_path, monkeypatch, "beacon_cone", beacon)
    assert heard == {"ahead": BOTH, "behind": RADIO, "beside": RADIO}


def test_the_command_runs_the_whole_world_and_reports_every_robot(tmp_path: Path) -> None:
    out = tmp_path / "run"
    env = dict(os.environ, SWARM_LOG=str(tmp_path), MPLBACKEND="Agg")
    result = mazesim_command(
        *("webots", "run", str(WORLD), "--seconds", "3", "--out", str(out)),
        *("--robot-controller", f"far={SWARM / 'controllers' / 'leader' / 'leader.py'}"),
        cwd=tmp_path,
        env=env,
    )
    assert result.returncode == 0, result.stderr
    summary = json.loads((out / "summary.json").read_text())
    names = [robot["name"] for robot in summary["robots"]]
    assert names == ["leader", "near", "far"]
    assert Path(summary["robots"][2]["controller"]).name == "leader.py", "given on the command"
    assert summary["steps"] == 60
    assert summary["missing_features"] == [], "every controller has what it needs"
    assert all(robot["missing_features"] == [] for robot in summary["robots"])
    rows = (out / "trajectory.csv").read_text().splitlines()
    assert rows[0] == "robot,time_s,x_m,y_m"
    assert {row.split(",")[0] for row in rows[1:]} == set(names)
    assert (out / "trajectory.png").stat().st_size > 0
    assert "far" in result.stdout and "leader.py" in result.stdout


def test_e_pucks_driving_head_on_see_each_other_and_do_not_pass_through(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    run = run_world(str(SWARM / "worlds" / "head_on.wbt"), seconds=5.0)
    west, east = run.robots
    # 0.3 m apart at 4 rad/s (about 8 cm/s each) they meet within 2 s and push, neither passes.
    assert west.final_pose[0] < east.final_pose[0]
    gap = east.final_pose[0] - west.final_pose[0]
    assert 0.06 < gap < 0.09, "bodies of about 7.4 cm touching"
    for name in ("west", "east"):
        seen = json.loads((tmp_path / f"{name}.json").read_text())["highest_front_reading"]
        # Alone in the arena the front sensors read under 120 (the lookup table's 5 cm and
        # beyond); touching the other e-puck's grey shell they read several hundred.
        assert seen > 300.0, f"{name}'s front sensors see the other e-puck's body"
        # At the start, 0.3 m apart, each camera sees the other's shell in the middle of its
        # image: the E-puck PROTO's grey, 80 % lit (the wall behind would be 204).
        middle = json.loads((tmp_path / f"{name}.json").read_text())["first_middle_pixel"]
        assert middle == [102, 102, 102], f"{name}'s camera sees the other e-puck"


def test_e_pucks_push_a_box_between_them_in_one_shared_world(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    run = run_world(str(SWARM / "worlds" / "box_between.wbt"), seconds=5.0)
    assert "simulators of their own" not in capsys.readouterr().err, "one shared world"
    west, east = run.robots
    # Both push the 5 cm crate from either side: it stays between them, nobody passes through
    # (each alone with a crate of its own would push it past the other's start).
    gap = east.final_pose[0] - west.final_pose[0]
    assert 0.11 < gap < 0.14, "two bodies of 3.7 cm radius either side of a 5 cm crate"
    for name in ("west", "east"):
        seen = json.loads((tmp_path / f"{name}.json").read_text())["highest_front_reading"]
        assert seen > 1000.0, f"{name}'s front sensors see the crate at contact"


def test_the_same_seed_gives_the_same_run_whatever_the_processes_timing(
    leader_and_followers: tuple[object, Path], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    first, _ = leader_and_followers
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    again = run_world(str(WORLD), seconds=10.0, seed=3)
    for one, other in zip(first.robots, again.robots):  # type: ignore[attr-defined]
        assert (one.xs, one.ys) == (other.xs, other.ys)
    assert json.loads((tmp_path / "near.json").read_text())["orders"][:31] == ["go"] * 30 + ["stop"]


BODILESS_WORLD = """#VRML_SIM R2023b utf8
WorldInfo {
  basicTimeStep 32
}
RectangleArena {
  floorSize 2 2
}
Solid {
  children [
    Shape {
      geometry DEF BRICK Box {
        size 0.6 0.01 0.1
      }
    }
  ]
  boundingObject USE BRICK
}
Supervisor {
  children [
    Emitter {
      channel 1
    }
  ]
  controller "orders"
}
E-puck {
  translation 0 -0.4 0
  name "runner"
  controller "runner"
}
"""

ORDERS = """from controller import Supervisor

robot = Supervisor()
emitter = robot.getDevice("emitter")
for _ in range(20):
    emitter.send("go")
    if robot.step(32) == -1:
        break
"""

RUNNER = """from controller import Robot

robot = Robot()
receiver = robot.getDevice("receiver")
receiver.enable(32)
left, right = robot.getDevice("left wheel motor"), robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(0.0)
while robot.step(32) != -1:
    while receiver.getQueueLength() > 0:
        if receiver.getString() == "go":
            left.setVelocity(4.0)
            right.setVelocity(4.0)
        receiver.nextPacket()
"""


def test_a_bodiless_supervisor_inside_a_wall_runs_beside_the_e_pucks(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A Supervisor node without a body, left at the origin where a thin wall stands (a common
    way of saving a world), runs its controller: an e-puck's body there would overlap the wall,
    but the stand-in of a robot that is not an e-puck stands in a world without walls."""
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "w.wbt").write_text(BODILESS_WORLD)
    for name, text in (("orders", ORDERS), ("runner", RUNNER)):
        (tmp_path / "controllers" / name).mkdir(parents=True)
        (tmp_path / "controllers" / name / f"{name}.py").write_text(text)
    run = run_world(str(tmp_path / "worlds" / "w.wbt"), seconds=1.5, seed=1)
    supervisor, runner = run.robots
    assert [supervisor.exit_status, runner.exit_status] == [0, 0], runner.error
    assert supervisor.distance_m == 0.0
    assert supervisor.final_pose[:2] == pytest.approx((0.0, 0.0))
    assert runner.distance_m > 0.05, "the e-puck heard the supervisor's orders"
    assert "refused" not in capsys.readouterr().err


#: A plain Robot box whose own supervisor controller slides it along y through a wall, as a
#: patrolling obstacle of a course world does, beside an e-puck that stands still.
SLIDING_WORLD = """#VRML_SIM R2025a utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 2 2 }
Solid {
  translation 0 0.3 0.05
  children [ Shape { geometry DEF WALL Box { size 0.6 0.05 0.1 } } ]
  boundingObject USE WALL
}
Robot {
  translation 0 0 0.05
  children [ Shape { geometry DEF CUBE Box { size 0.1 0.1 0.1 } } ]
  name "slider"
  boundingObject USE CUBE
  physics Physics { }
  controller "slide"
  supervisor TRUE
}
E-puck { translation -0.6 -0.6 0 name "still" controller "still" }
"""
SLIDE = """from controller import Supervisor
robot = Supervisor()
translation = robot.getSelf().getField("translation")
y = 0.0
while robot.step(32) != -1:
    y += 0.01
    translation.setSFVec3f([0.0, y, 0.05])
"""


def test_a_robot_that_is_not_an_e_puck_slides_through_a_wall_where_its_supervisor_puts_it(
    tmp_path: Path,
) -> None:
    """Webots puts a node wherever its translation is set: the stand-in of a robot that is not
    an e-puck follows its controller's translation through the wall at y = 0.3 (an e-puck's
    disc there was refused, and the controller stopped with an error)."""
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "w.wbt").write_text(SLIDING_WORLD)
    still = "from controller import Robot\nrobot = Robot()\nwhile robot.step(32) != -1:\n    pass\n"
    for name, text in (("slide", SLIDE), ("still", still)):
        (tmp_path / "controllers" / name).mkdir(parents=True)
        (tmp_path / "controllers" / name / f"{name}.py").write_text(text)
    run = run_world(str(tmp_path / "worlds" / "w.wbt"), seconds=1.6, seed=1)
    slider, _ = run.robots
    assert slider.exit_status == 0, slider.error
    # 50 steps of 1 cm: through the wall (0.275 to 0.325) and on to 0.5 m.
    assert slider.final_pose[1] == pytest.approx(0.5, abs=1e-6)


def test_a_robots_state_after_a_step_comes_with_the_steps_answer(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The pose, time and encoders a controller reads at every step come with the answer to its
    step: past the set-up before the first step, the world's process answers no call for them."""
    import collections

    import mazesim.webots.lockstep as lockstep

    asked: collections.Counter[str] = collections.Counter()
    answer = lockstep.answer

    def counted(target: object, name: str, args: tuple[object, ...] | None) -> tuple[str, object]:
        asked[name] += 1
        return answer(target, name, args)

    monkeypatch.setattr(lockstep, "answer", counted)
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    run = run_world(str(WORLD), seconds=10.0, seed=3)
    assert run.steps == 60
    for name in ("pose", "time", "encoders"):
        assert asked[name] <= 3 * len(run.robots), (name, asked[name])


PLACER_WORLD = """#VRML_SIM R2023b utf8

EXTERNPROTO "webots://projects/objects/floors/protos/RectangleArena.proto"
EXTERNPROTO "webots://projects/robots/gctronic/e-puck/protos/E-puck.proto"

WorldInfo {
  basicTimeStep 32
}
RectangleArena {
  floorSize 2 2
}
Robot {
  translation 0 0 0.5
  name "placer"
  controller "placer"
  supervisor TRUE
}
DEF STILL E-puck {
  translation 0 0 0
  name "still"
  controller "void"
}
DEF MOVED E-puck {
  translation 0.5 0.5 0
  name "moved"
  controller "void"
}
"""

PLACER = """from controller import Supervisor

robot = Supervisor()
robot.step(32)
# 2 cm into the other e-puck, as Webots lets a supervisor put it.
robot.getFromDef("MOVED").getField("translation").setSFVec3f([0.054, 0.0, 0.0])
for _ in range(10):
    robot.step(32)
"""


def test_a_supervisor_may_put_an_e_puck_onto_another_and_the_contacts_part_them(
    tmp_path: Path,
) -> None:
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "w.wbt").write_text(PLACER_WORLD)
    (tmp_path / "controllers" / "placer").mkdir(parents=True)
    (tmp_path / "controllers" / "placer" / "placer.py").write_text(PLACER)
    run = run_world(str(tmp_path / "worlds" / "w.wbt"), seconds=0.5, seed=1)
    placer, still, moved = run.robots
    assert [placer.exit_status, still.exit_status, moved.exit_status] == [0, 0, 0], placer.error
    # Pushed apart by half the overlap each: touching, 1 cm from where each was put.
    apart = moved.final_pose[0] - still.final_pose[0]
    assert apart == pytest.approx(0.074, abs=1e-3)
    assert still.final_pose[0] == pytest.approx(-0.01, abs=1e-3)


SCATTERED_WORLD = PLACER_WORLD.replace("translation 0.5 0.5 0", "translation 0 0 0").replace(
    'controller "placer"', 'controller "scatterer"'
)

SCATTERER = """from controller import Supervisor

robot = Supervisor()
# Before the first step, as a swarm's supervisor scatters the e-pucks its world writes at the
# origin: the moved one 10 cm ahead of the still one.
robot.getFromDef("MOVED").getField("translation").setSFVec3f([0.1, 0.0, 0.0])
for _ in range(10):
    robot.step(32)
"""


def test_e_pucks_written_on_one_another_that_a_supervisor_scatters_share_one_world(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "w.wbt").write_text(SCATTERED_WORLD)
    (tmp_path / "controllers" / "scatterer").mkdir(parents=True)
    (tmp_path / "controllers" / "scatterer" / "scatterer.py").write_text(SCATTERER)
    shared: list[bool] = []

    def watch(world: Any, runs: Any, simulators: list[Any], wheels: Any) -> None:
        still, moved = simulators[1], simulators[2]
        shared.append(getattr(still, "simulator", None) is getattr(moved, "simulator", 0))

    run = run_world(str(tmp_path / "worlds" / "w.wbt"), seconds=0.3, seed=1, observer=watch)
    assert "simulators of their own" not in capsys.readouterr().err
    scatterer, still, moved = run.robots
    assert scatterer.exit_status == 0, scatterer.error
    # One simulator, where they see and touch each other, as in Webots once scattered.
    assert shared and all(shared)
    assert moved.final_pose[0] == pytest.approx(0.1, abs=1e-6)
    assert still.final_pose[0] == pytest.approx(0.0, abs=1e-6)


def test_a_controller_beside_the_world_file_runs_with_a_warning_that_webots_would_not_find_it(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # Webots' project is the folder above the world's (WbProject::projectPathFromWorldFile):
    # controllers/ beside the world file is not looked in. mazesim runs it and says so.
    (tmp_path / "controllers" / "still").mkdir(parents=True)
    (tmp_path / "controllers" / "still" / "still.py").write_text(
        "from controller import Robot\nrobot = Robot()\nwhile robot.step(32) != -1:\n    pass\n"
    )
    world = tmp_path / "w.wbt"
    world.write_text('#VRML_SIM R2023b utf8\nRectangleArena { }\nE-puck { controller "still" }\n')
    found, note = controller_of({"name": "e-puck", "controller": "still"}, str(world), {})
    assert found == str(tmp_path / "controllers" / "still" / "still.py")
    assert "beside the world file" in note and "would not start it" in note
    run = run_world(str(world), seconds=0.1)
    assert run.robots[0].controller == found and run.robots[0].note == ""
    assert run.robots[0].exit_status == 0
    assert "robot 'e-puck': its controller still was found in controllers/ beside" in (
        capsys.readouterr().err
    )
    (tmp_path / "worlds").mkdir()
    inside = tmp_path / "worlds" / "w.wbt"
    inside.write_text(world.read_text())
    assert controller_of({"name": "e-puck", "controller": "still"}, str(inside), {}) == (found, "")


def test_a_makefile_folder_with_a_fifo_or_a_folder_for_a_source_has_no_controller(
    tmp_path: Path,
) -> None:
    """A source the Makefile lists that is a FIFO (read, it would wait for a writer for ever)
    or a folder, and a FIFO for a Makefile, are no program's source."""
    (tmp_path / "worlds").mkdir()
    world = str(tmp_path / "worlds" / "w.wbt")
    folder = tmp_path / "controllers" / "explorer"
    folder.mkdir(parents=True)
    os.mkfifo(folder / "main.cpp")
    (folder / "other.cpp").mkdir()
    (folder / "Makefile").write_text("CXX_SOURCES = main.cpp other.cpp\n")
    none, why = controller_of({"name": "e", "controller": "explorer"}, world, {})
    assert none is None and "explorer.py, .c" in why
    (folder / "Makefile").unlink()
    os.mkfifo(folder / "Makefile")
    none, _ = controller_of({"name": "e", "controller": "explorer"}, world, {})
    assert none is None


#: A controller whose threads call the API while its main thread steps.
THREADED = """import threading
from controller import Robot
robot = Robot()
sensor = robot.getDevice("ps0")
sensor.enable(32)
done = threading.Event()
calls = []
def ask():
    while not done.is_set():
        robot.getTime()
        sensor.getValue()
        calls.append(1)
threads = [threading.Thread(target=ask) for _ in range(4)]
for thread in threads:
    thread.start()
for _ in range(20):
    robot.step(32)
done.set()
for thread in threads:
    thread.join()
print("threads done", len(calls) > 0, robot.getTime())
"""


def test_a_python_controller_s_threads_may_call_the_api_at_once_in_a_world_run(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    # Each call is a question on the controller's pipe to the world's process: unserialised,
    # the threads read each other's answers (EOFError, UnpicklingError) and the run hung.
    west, _ = run_beside_an_avoider(tmp_path, "threaded", THREADED, ".py")
    assert (west.exit_status, west.error) == (0, "")
    out, err = capfd.readouterr()
    assert "threads done True 0.64" in out
    assert "internal error" not in err


def test_a_proto_robot_writing_no_name_is_never_called_e_puck(tmp_path: Path) -> None:
    # A TurtleBot3Burger and a Pioneer3dx writing no name field: getName() said "e-puck".
    (tmp_path / "worlds").mkdir()
    (tmp_path / "controllers" / "who").mkdir(parents=True)
    (tmp_path / "controllers" / "who" / "who.py").write_text(
        "from controller import Robot\nr = Robot()\nprint('name:', r.getName())\nr.step(32)\n"
    )
    world = tmp_path / "worlds" / "names.wbt"
    world.write_text(
        "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\nRectangleArena { floorSize 4 4 }\n"
        'TurtleBot3Burger { translation -1 0 0 controller "who" }\n'
        'Pioneer3dx { translation 1 0 0 controller "who" }\n'
    )
    result = mazesim_command(
        *("webots", "run", str(world), "--seconds", "0.1", "--out", str(tmp_path / "run")),
        cwd=tmp_path,
        env=dict(os.environ, MPLBACKEND="Agg"),
    )
    assert result.returncode == 0, result.stderr
    names = sorted(line for line in result.stdout.splitlines() if line.startswith("name:"))
    assert names == ["name: Pioneer3dx", "name: TurtleBot3Burger"], result.stdout
