"""A supervisor that sends each follower its pose relative to the leader every step, read by
Node.getPose(leader), and logs it beside the same pose worked out from the world poses."""

import json
import math
import os

from controller import Supervisor

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
radio = supervisor.getDevice("radio")
lead = supervisor.getFromDef("LEAD")
wings = {"wing_l": supervisor.getFromDef("WING_L"), "wing_r": supervisor.getFromDef("WING_R")}


def by_hand(node):
    """The node's x, y, yaw in the leader's frame, from both world poses."""
    lx, ly, _ = lead.getPosition()
    lm = lead.getOrientation()
    lyaw = math.atan2(lm[3], lm[0])
    x, y, _ = node.getPosition()
    m = node.getOrientation()
    yaw = math.atan2(m[3], m[0])
    dx, dy = x - lx, y - ly
    c, s = math.cos(lyaw), math.sin(lyaw)
    turn = math.atan2(math.sin(yaw - lyaw), math.cos(yaw - lyaw))
    return [c * dx + s * dy, -s * dx + c * dy, turn]


log = {"relative": [], "by_hand": [], "errors": []}
steps = 0
while supervisor.step(time_step) != -1:
    steps += 1
    for name, node in wings.items():
        pose = node.getPose(lead)
        relative = [pose[3], pose[7], math.atan2(pose[4], pose[0])]
        radio.send(json.dumps({"to": name, "pose": relative}))
        if steps in (1, 100):
            log["relative"].append(relative)
            log["by_hand"].append(by_hand(node))
    if steps == 150:
        for name, node in wings.items():
            x, y, _ = by_hand(node)
            target_y = 0.15 if name == "wing_l" else -0.15
            log["errors"].append(math.hypot(x + 0.15, y - target_y))
        break
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "shepherd.json"), "w") as out:
    json.dump(log, out)
