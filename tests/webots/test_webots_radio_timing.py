"""What a receiver measures of a packet (range, direction, strength) is measured where the
robots stand after the step that delivers it, as Webots' ``WbReceiver::postPhysicsStep`` does
(the receiving robot's pose after that step's physics), not where they stood when it was sent
(#33)."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from mazesim.webots.lockstep import run_world
from supervised_world import project_of

pytestmark = pytest.mark.usefixtures("fresh_robot")

WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
E-puck { translation 0.2 0 0 name "spinner" controller "spinner" emitter_channel 1
  receiver_channel 2 turretSlot [ InertialUnit { } ] }
E-puck { translation 0 0 0 name "beacon" controller "beacon" emitter_channel 2
  receiver_channel 1 }
"""
#: Turns in place and says, at each step, its yaw and the bearing of the beacon it heard.
SPINNER = """import math
from controller import Robot

robot = Robot()
receiver = robot.getDevice("receiver")
receiver.enable(32)
unit = robot.getDevice("inertial unit")
unit.enable(32)
for name, speed in (("left wheel motor", -6.0), ("right wheel motor", 6.0)):
    robot.getDevice(name).setPosition(math.inf)
    robot.getDevice(name).setVelocity(speed)
for count in range(6):
    robot.step(32)
    while receiver.getQueueLength() > 0:
        x, y, _ = receiver.getEmitterDirection()
        print(f"yaw {unit.getRollPitchYaw()[2]:.6f} bearing {math.atan2(y, x):.6f}")
        receiver.nextPacket()
"""
#: Sends a packet at every step.
BEACON = """from controller import Robot

robot = Robot()
emitter = robot.getDevice("emitter")
while robot.step(32) != -1:
    emitter.send("here")
"""


def test_a_spinning_robot_hears_the_beacon_where_it_points_after_the_step(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    sources = {"spinner": SPINNER, "beacon": BEACON}
    world = project_of(tmp_path, "spin.wbt", WORLD, sources)
    run_world(str(world), seconds=0.3, noise=False)
    heard = [
        [float(v) for v in m.groups()]
        for line in capfd.readouterr().out.splitlines()
        if (m := re.fullmatch(r"yaw (\S+) bearing (\S+)", line))
    ]
    assert len(heard) >= 4
    for yaw, bearing in heard:
        # The beacon is at the origin, the spinner at (0.2, 0): world bearing pi, so pi - yaw
        # in the spinner's frame as it stands now (it turns 0.135 rad a step).
        assert math.remainder(bearing - (math.pi - yaw), math.tau) == pytest.approx(0, abs=1e-4)
