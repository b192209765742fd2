"""A supervisor restarts another robot's controller in a world run, as Webots'
``wb_supervisor_node_restart_controller`` does: that controller's ``Robot.step`` returns -1, and
a new process of it starts at once on the robot where it stands, with the world's clock going on
(#33)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from mazesim.webots.lockstep import run_world
from supervised_world import project_of

#: A supervisor without a body and an e-puck runner.
WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
Robot { name "boss" controller "restarter" supervisor TRUE }
DEF RUNNER E-puck { translation -0.5 0 0 name "runner" controller "runner" }
"""

#: Notes each start (its clock) and how its run ended, drives 10 steps at 5 rad/s and stands.
RUNNER = """import json
import math

from controller import Robot

robot = Robot()
step = int(robot.getBasicTimeStep())
with open("starts.json", "a") as out:
    out.write(json.dumps({"started_s": robot.getTime()}) + "\\n")
wheels = [robot.getDevice(name) for name in ("left wheel motor", "right wheel motor")]
for wheel in wheels:
    wheel.setPosition(math.inf)
    wheel.setVelocity(5.0)
steps = 0
while robot.step(step) != -1:
    steps += 1
    if steps == 10:
        for wheel in wheels:
            wheel.setVelocity(0.0)
with open("starts.json", "a") as out:
    out.write(json.dumps({"ended_s": robot.getTime(), "steps": steps}) + "\\n")
"""

#: Restarts the runner's controller after its 20th step, and tries its own after the 30th.
RESTARTER = """from controller import Supervisor

boss = Supervisor()
step = int(boss.getBasicTimeStep())
steps = 0
while boss.step(step) != -1:
    steps += 1
    if steps == 20:
        boss.getFromDef("RUNNER").restartController()
    if steps == 30:
        boss.getSelf().restartController()
"""

STEP_S = 0.032


def test_another_robot_s_controller_restarts_where_its_robot_stands(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    world = project_of(tmp_path, "restart.wbt", WORLD, {"restarter": RESTARTER, "runner": RUNNER})
    boss, runner = run_world(str(world), seconds=1.6, noise=False).robots
    assert [boss.exit_status, runner.exit_status] == [0, 0], [boss.error, runner.error]
    err = capfd.readouterr().err
    # Only the supervisor's own controller is refused.
    assert err.count("wb_supervisor_node_restart_controller() is not available") == 1
    assert "node Robot" in err and "node E-puck" not in err
    notes = [
        json.loads(line)
        for line in (tmp_path / "controllers" / "runner" / "starts.json").read_text().splitlines()
    ]
    assert [list(note) for note in notes] == [
        ["started_s"],
        ["ended_s", "steps"],
        ["started_s"],
        ["ended_s", "steps"],
    ]
    first_start, first_end, second_start, second_end = notes
    assert first_start["started_s"] == 0.0
    # The first process's step after the restart returns -1; the second starts on the world's
    # clock and steps to the run's end.
    assert first_end["ended_s"] == pytest.approx(20 * STEP_S)
    assert second_start["started_s"] == pytest.approx(20 * STEP_S)
    assert second_end == {"ended_s": pytest.approx(50 * STEP_S), "steps": 50 - 20}
    assert runner.restarts_s == [pytest.approx(20 * STEP_S)]
    # Each process drove 10 steps from where the robot stood: twice the one run's way.
    one_run = 10 * 5.0 * 0.02 * STEP_S
    assert runner.final_pose[0] == pytest.approx(-0.5 + 2 * one_run, abs=2e-3)
    assert math.isclose(runner.final_pose[1], 0.0, abs_tol=1e-3)


#: Writes the worker's controller field after its 10th step.
WRITER = """from controller import Supervisor

boss = Supervisor()
step = int(boss.getBasicTimeStep())
field = boss.getFromDef("WORKER").getField("controller")
steps = 0
while boss.step(step) != -1:
    steps += 1
    if steps == 10:
        field.setSFString(NEW)
"""

#: Notes its own name and the clock at its start, then steps to the end.
NOTED = """import json
import os

from controller import Robot

robot = Robot()
log = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "starts.json")
with open(log, "a") as out:
    out.write(json.dumps([NAME, robot.getTime()]) + "\\n")
while robot.step(int(robot.getBasicTimeStep())) != -1:
    pass
"""

FIELD_WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
Robot { name "boss" controller "writer" supervisor TRUE }
DEF WORKER E-puck { translation -0.5 0 0 name "worker" controller "first" }
"""


@pytest.mark.parametrize(
    ("new", "given_by", "expected"),
    [
        # The field names the new controller: a file given by the robot's name or DEF name
        # (which stood for the field's old value) no longer applies.
        ("second", "worker", "second"),
        ("second", "WORKER", "second"),
        # A file given by the new value applies to it.
        ("second", "second", "given"),
        # <extern>: the controller left to be started outside, the one given by name.
        ("<extern>", "worker", "given"),
    ],
)
def test_a_written_controller_field_names_the_controller_that_starts(
    tmp_path: Path, new: str, given_by: str, expected: str
) -> None:
    sources = {
        "writer": WRITER.replace("NEW", repr(new)),
        **{name: NOTED.replace("NAME", repr(name)) for name in ("first", "second", "given")},
    }
    world = project_of(tmp_path, "field.wbt", FIELD_WORLD, sources)
    given = str(tmp_path / "controllers" / "given" / "given.py")
    boss, worker = run_world(
        str(world), seconds=0.64, noise=False, controllers={given_by: given}
    ).robots
    assert [boss.exit_status, worker.exit_status] == [0, 0], [boss.error, worker.error]
    starts = [
        json.loads(line)
        for line in (tmp_path / "controllers" / "starts.json").read_text().splitlines()
    ]
    first = "given" if given_by in ("worker", "WORKER") else "first"
    assert starts == [[first, 0.0], [expected, pytest.approx(10 * STEP_S)]]
    assert worker.controller is not None and worker.controller.endswith(f"{expected}.py")


#: Two e-pucks whose customData the file gives, and a supervisor that writes both fields, then
#: restarts one's controller and switches the other's.
CUSTOM_WORLD = """#VRML_SIM R2025a utf8
WorldInfo { basicTimeStep 32 }
DEF R1 E-puck { translation -0.2 0 0 name "r1" controller "reader" customData "file1" }
DEF R2 E-puck { translation 0.2 0 0 name "r2" controller "reader" customData "file2" }
Robot { name "boss" controller "writer" supervisor TRUE }
"""
CUSTOM_WRITER = """from controller import Supervisor

boss = Supervisor()
step = int(boss.getBasicTimeStep())
for count in range(1, 8):
    boss.step(step)
    if count == 2:
        boss.getFromDef("R1").getField("customData").setSFString("new1")
        boss.getFromDef("R2").getField("customData").setSFString("new2")
    if count == 5:
        boss.getFromDef("R1").restartController()
        boss.getFromDef("R2").getField("controller").setSFString("other")
"""
CUSTOM_READER = """from controller import Robot

robot = Robot()
print(f"{robot.getName()} starts at {robot.getTime():.3f} with {robot.getCustomData()}")
while robot.step(int(robot.getBasicTimeStep())) != -1:
    pass
"""


def test_a_controller_started_while_the_world_runs_reads_the_custom_data_as_it_is_then(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    # Webots hands a starting controller its robot's customData field as it is (WbRobot's
    # configure message), not as the file wrote it.
    sources = {"writer": CUSTOM_WRITER, "reader": CUSTOM_READER, "other": CUSTOM_READER}
    world = project_of(tmp_path, "custom.wbt", CUSTOM_WORLD, sources)
    run_world(str(world), seconds=0.3, noise=False)
    starts = sorted(x for x in capfd.readouterr().out.splitlines() if " starts at " in x)
    assert starts == [
        "r1 starts at 0.000 with file1",
        "r1 starts at 0.160 with new1",
        "r2 starts at 0.000 with file2",
        "r2 starts at 0.160 with new2",
    ]
