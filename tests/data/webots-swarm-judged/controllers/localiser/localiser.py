"""A supervisor that reads each e-puck's position and orientation every step and sends it
(x, y, heading) to that robot alone, on the channel of its number."""

import math
import struct

from controller import Supervisor

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
radio = supervisor.getDevice("radio")
nodes = {index: supervisor.getFromDef(f"R{index}") for index in (1, 2, 3)}
while supervisor.step(time_step) != -1:
    for index, node in nodes.items():
        x, y, _ = node.getPosition()
        matrix = node.getOrientation()
        heading = math.atan2(matrix[3], matrix[0])
        radio.setChannel(index)
        radio.send(struct.pack("<3d", x, y, heading))
