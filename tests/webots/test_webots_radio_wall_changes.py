"""An infra-red packet meets the walls where a supervisor left them: moved, imported or removed
while the world runs, in a world run (#32, #33)."""

from __future__ import annotations

from pathlib import Path

import pytest

from mazesim.webots.lockstep import run_world
from supervised_world import project_of

#: Two e-pucks 0.6 m apart facing each other, an infra-red Emitter and Receiver in their
#: turrets, and a wall between them (WALL) or off to the side (its translation given).
WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 2 2 }
DEF WALL Solid {
  translation WALL_AT
  children [ Shape { geometry DEF W Box { size 0.05 0.4 0.1 } } ]
  name "wall"
  boundingObject USE W
}
E-puck {
  translation -0.3 0 0
  name "talker"
  controller "talker"
  supervisor TRUE
  turretSlot [ Emitter { name "ir" type "infra-red" channel 3 } ]
}
E-puck {
  translation 0.3 0 0
  rotation 0 0 1 3.14159
  name "listener"
  controller "listener"
  turretSlot [ Receiver { name "ir" type "infra-red" channel 3 } ]
}
"""

#: A wall imported between the two robots.
IMPORTED_WALL = (
    "Solid { translation 0 0 0.05 children [ Shape { geometry DEF I Box { size 0.05 0.4 0.1 } "
    '} ] name \\"imported\\" boundingObject USE I }'
)

#: An e-puck without a controller imported between the two robots: its body stops packets.
IMPORTED_E_PUCK = 'E-puck { translation 0 0 0 name \\"blocker\\" controller \\"void\\" }'

#: What the talker does after its fourth step, and where the wall stands at the start.
CHANGES = {
    "remove": ("0 0 0.05", 'robot.getFromDef("WALL").remove()'),
    "move away": (
        "0 0 0.05",
        'robot.getFromDef("WALL").getField("translation").setSFVec3f([0.0, 0.8, 0.05])',
    ),
    "import": (
        "0 0.8 0.05",
        f'robot.getRoot().getField("children").importMFNodeFromString(-1, "{IMPORTED_WALL}")',
    ),
    "import an e-puck": (
        "0 0.8 0.05",
        f'robot.getRoot().getField("children").importMFNodeFromString(-1, "{IMPORTED_E_PUCK}")',
    ),
}

#: Sends a packet every step; changes the world after its fourth step.
TALKER = """from controller import Supervisor

robot = Supervisor()
emitter = robot.getDevice("ir")
for step in range(12):
    emitter.send(b"x")
    robot.step(32)
    if step == 3:
        CHANGE
"""

#: Writes, for each step, 1 when a packet arrived, else 0.
LISTENER = """from controller import Robot

robot = Robot()
receiver = robot.getDevice("ir")
receiver.enable(32)
heard = []
for _ in range(12):
    robot.step(32)
    heard.append(str(int(receiver.getQueueLength() > 0)))
    while receiver.getQueueLength() > 0:
        receiver.nextPacket()
with open(OUT, "w") as out:
    out.write("".join(heard))
"""


@pytest.mark.parametrize("change", sorted(CHANGES))
def test_infra_red_packets_meet_the_walls_a_supervisor_changed(tmp_path: Path, change: str) -> None:
    out = tmp_path / "heard.txt"
    wall_at, action = CHANGES[change]
    world = project_of(
        tmp_path,
        "radio.wbt",
        WORLD.replace("WALL_AT", wall_at),
        {
            "talker": TALKER.replace("CHANGE", action),
            "listener": LISTENER.replace("OUT", repr(str(out))),
        },
    )
    run = run_world(str(world), seconds=0.6, seed=1, noise=False)
    assert all(robot.exit_status == 0 for robot in run.robots), [r.error for r in run.robots]
    heard = out.read_text()
    assert len(heard) == 12, heard
    # Before the change (packets of steps 2 to 4) and after it (steps 7 to 12).
    blocked_first = not change.startswith("import")
    before, after = heard[1:4], heard[6:]
    assert before == ("000" if blocked_first else "111"), heard
    assert after == ("1" * 6 if blocked_first else "0" * 6), heard
