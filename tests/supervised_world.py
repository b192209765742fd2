"""A Webots world with a supervisor e-puck, a static wall and a movable box, and its
supervisor prepared as ``mazesim webots run`` prepares it: what the tests of a supervisor that
moves and resets the world's Solids share (#33)."""

from __future__ import annotations

import math
from pathlib import Path

from mazesim.webots import controller, import_wbt, prepare
from mazesim.webots.scene import read_scene

#: An e-puck supervisor at the origin facing +x; a static wall (GATE) 0.1 m ahead; a light box
#: with physics (BOX, a movable body) off to the side, inside a Pose.
WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 2 2 }
DEF GATE Solid {
  translation 0.1 0 0.05
  children [ Shape { geometry DEF GATE_BOX Box { size 0.02 0.3 0.1 } } ]
  name "gate"
  boundingObject USE GATE_BOX
}
DEF PLACE Pose {
  translation 0.3 0.3 0
  children [
    DEF BOX Solid {
      translation 0 0 0.02
      children [ Shape { geometry DEF BOX_SHAPE Box { size 0.04 0.04 0.04 } } ]
      name "box"
      boundingObject USE BOX_SHAPE
      physics Physics { density -1 mass 0.05 }
    }
  ]
}
DEF EPUCK E-puck { translation 0 0 0 supervisor TRUE controller "<extern>" }
"""


def supervisor_of(tmp_path: Path, noise: bool = False, seed: int = 0) -> controller.Supervisor:
    """The e-puck's supervisor in ``WORLD``, as ``mazesim webots run`` prepares it."""
    path = tmp_path / "solids.wbt"
    path.write_text(WORLD)
    world, report = import_wbt(str(path))
    scene = read_scene(WORLD, report["robot_model"], report["robot_line"])
    prepare(world, seconds=60.0, noise=noise, seed=seed, report=report, scene=scene)
    controller.Robot.created = None
    return controller.Supervisor()


def drive(supervisor: controller.Supervisor, speed: float, steps: int) -> None:
    """Turns both wheels at ``speed`` rad/s for ``steps`` steps."""
    for name in ("left wheel motor", "right wheel motor"):
        motor = supervisor.getDevice(name)
        motor.setPosition(math.inf)
        motor.setVelocity(speed)
    for _ in range(steps):
        assert supervisor.step(32) != -1
