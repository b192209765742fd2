"""Sets its emitter's channel to its first argument and sends its second argument once a step."""

import sys

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
emitter = robot.getDevice("tx")
emitter.setChannel(int(sys.argv[1]))
message = sys.argv[2].encode()
while robot.step(time_step) != -1:
    emitter.send(message)
