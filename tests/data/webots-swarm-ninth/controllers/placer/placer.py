"""Imports, after its first step, a parked e-puck carrying a bumper in its bodySlot as the world
file's "parked" carries one, 0.8 m lower; then watches the world run on."""

import json
import os

from controller import Supervisor

robot = Supervisor()
time_step = int(robot.getBasicTimeStep())
children = robot.getRoot().getField("children")
robot.step(time_step)
children.importMFNodeFromString(
    -1,
    'DEF TWIN E-puck { translation 0 -0.4 0 name "parked_imported" controller "<none>" '
    "bodySlot [ Solid { translation -0.06 0 0.033 children [ Shape { appearance "
    "PBRAppearance { baseColor 1 1 1 roughness 1 metalness 0 } geometry DEF BUMPER_I Box { "
    'size 0.02 0.1 0.02 } } ] name "bumper" boundingObject USE BUMPER_I } ] }',
)
while robot.step(time_step) != -1 and robot.getTime() < 4.0 - 1e-9:
    pass
twin = robot.getFromDef("TWIN")
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "placer.json"), "w") as out:
    json.dump({"twin": list(twin.getPosition())}, out)
