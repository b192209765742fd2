"""Sends its step count after each of its first 40 steps."""

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
emitter = robot.getDevice("emitter")
steps = 0
while robot.step(time_step) != -1 and steps < 40:
    steps += 1
    emitter.send(str(steps))
