"""A robot whose controller has ended goes on as its motors' last commands have it, as in
Webots, where nothing resets a motor's target when the controller ends: a wheel under velocity
control keeps its velocity, one under position control keeps turning to its target, while the
world's other robots run on (#33, #32)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from mazesim.webots.lockstep import run_world
from supervised_world import project_of

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
CRUISER = """import math

from controller import Robot

robot = Robot()
for name in ("left wheel motor", "right wheel motor"):
    wheel = robot.getDevice(name)
    wheel.setPosition(math.inf)
    wheel.setVelocity(5.0)
for _ in range(10):
    robot.step(int(robot.getBasicTimeStep()))
"""

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
