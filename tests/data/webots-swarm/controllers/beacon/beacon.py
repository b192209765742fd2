"""Stands still and sends "infra-red" from its infra-red emitter and "radio" from its radio
emitter at every step, for 20 steps."""

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
infra_red = robot.getDevice("infra-red emitter")
radio = robot.getDevice("radio emitter")
steps = 0
while steps < 20:
    infra_red.send("infra-red")
    radio.send("radio")
    if robot.step(time_step) == -1:
        break
    steps += 1
