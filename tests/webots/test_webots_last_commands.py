"""A robot whose controller has ended goes on as its motors' last commands have it, as in
Webots, where nothing resets a motor's target when the controller ends: a wheel under velocity
control keeps its velocity, one under position control keeps turning to its target, while the
world's other robots run on (#33, #32)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from mazesim.webots.lockstep import run_world
from supervised_world import cruising_controller, project_of

#: A robot without a body that runs to the end, and two e-pucks whose controllers end early.
WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
Robot { name "clock" controller "clock" }
E-puck { translation -0.5 0 0 name "cruiser" controller "cruiser" }
E-puck { translation 0.5 0 0 name "parker" controller "parker" }
"""

CLOCK = """from controller import Robot

robot = Robot()
while robot.step(int(robot.getBasicTimeStep())) != -1:
    pass
"""

#: Velocity control at 5 rad/s for 10 steps, then the controller returns.
CRUISER = cruising_controller(5.0, steps=10)

#: Position control to 10 rad, one step, then the controller raises.
PARKER = """from controller import Robot

robot = Robot()
for name in ("left wheel motor", "right wheel motor"):
    robot.getDevice(name).setPosition(10.0)
robot.step(int(robot.getBasicTimeStep()))
raise RuntimeError("the controller crashes")
"""

STEP_S = 0.032
SECONDS = 3.2


def test_the_wheels_keep_their_last_commands_after_the_controller_ends(tmp_path: Path) -> None:
    sources = {"clock": CLOCK, "cruiser": CRUISER, "parker": PARKER}
    world = project_of(tmp_path, "coast.wbt", WORLD, sources)
    clock, cruiser, parker = run_world(str(world), seconds=SECONDS, noise=False).robots
    assert [clock.exit_status, cruiser.exit_status] == [0, 0], [clock.error, cruiser.error]
    assert parker.exit_status != 0 and "the controller crashes" in parker.error
    steps = round(SECONDS / STEP_S)
    # The cruiser's wheels turn at 5 rad/s over the whole run, not its 10 steps only.
    assert cruiser.final_pose[0] == pytest.approx(-0.5 + steps * 5.0 * 0.02 * STEP_S, abs=3e-3)
    assert math.isclose(cruiser.final_pose[1], 0.0, abs_tol=1e-3)
    # The parker's wheels reach their 10 rad target: 0.2 m of a 0.02 m wheel, then stop.
    assert parker.final_pose[0] == pytest.approx(0.5 + 10.0 * 0.02, abs=3e-3)
    assert math.isclose(parker.final_pose[1], 0.0, abs_tol=1e-3)


#: Velocity control at 5 rad/s for 10 steps, a command no step sends, then the process dies
#: without a word (as a controller that segfaults or is killed does).
KILLED_CRUISER = (
    "import os\nimport signal\n\n"
    + cruising_controller(5.0, steps=10)
    + 'for name in ("left wheel motor", "right wheel motor"):\n'
    + "    robot.getDevice(name).setVelocity(0.0)\n"
    + "os.kill(os.getpid(), signal.SIGKILL)\n"
)

#: Position control to 10 rad, one step, then the process dies without a word.
KILLED_PARKER = """import os
import signal

from controller import Robot

robot = Robot()
for name in ("left wheel motor", "right wheel motor"):
    robot.getDevice(name).setPosition(10.0)
robot.step(int(robot.getBasicTimeStep()))
os.kill(os.getpid(), signal.SIGKILL)
"""

#: Two e-pucks whose fields name no controller, one written empty, one ``<none>``.
IDLE = """E-puck { translation 0 0.5 0 name "empty" controller "" }
E-puck { translation 0 -0.5 0 name "none" controller "<none>" }
"""


def test_a_controller_killed_without_a_word_leaves_what_its_last_step_sent(
    tmp_path: Path,
) -> None:
    sources = {"clock": CLOCK, "cruiser": KILLED_CRUISER, "parker": KILLED_PARKER}
    world = project_of(tmp_path, "killed.wbt", WORLD + IDLE, sources)
    run = run_world(str(world), seconds=SECONDS, noise=False)
    clock, cruiser, parker, empty, none = run.robots
    assert clock.exit_status == 0, clock.error
    for killed in (cruiser, parker):
        assert killed.exit_status != 0 and "killed by SIGKILL" in killed.error
    steps = round(SECONDS / STEP_S)
    # The velocity its steps sent (5 rad/s) goes on; the 0 set after its last step was never
    # sent, as Webots' library sends a motor's commands with the next wb_robot_step.
    assert cruiser.final_pose[0] == pytest.approx(-0.5 + steps * 5.0 * 0.02 * STEP_S, abs=3e-3)
    assert math.isclose(cruiser.final_pose[1], 0.0, abs_tol=1e-3)
    assert parker.final_pose[0] == pytest.approx(0.5 + 10.0 * 0.02, abs=3e-3)
    # A robot whose field names no controller runs none (not its PROTO's default) and stands
    # where the world file puts it: its motors hold the wheels at their first target.
    for idle, y in ((empty, 0.5), (none, -0.5)):
        assert idle.controller is None and idle.exit_status == 0
        assert idle.final_pose[:2] == pytest.approx((0.0, y), abs=1e-6)


def test_a_world_whose_robots_run_no_controller_still_runs_its_seconds(tmp_path: Path) -> None:
    # Webots runs such a world until it is stopped; the run once ended at 0 s, with no step.
    world = project_of(tmp_path, "idle.wbt", WORLD.split("Robot {")[0] + IDLE, {})
    run = run_world(str(world), seconds=SECONDS, noise=False)
    steps = round(SECONDS / STEP_S)
    assert run.steps == steps and run.simulated_seconds == pytest.approx(SECONDS)
    assert not run.interrupted
    for idle, y in zip(run.robots, (0.5, -0.5)):
        assert idle.controller is None and len(idle.xs) == steps + 1
        assert idle.final_pose[:2] == pytest.approx((0.0, y), abs=1e-6)
