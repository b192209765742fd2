"""Sends its step number as text after each step; after its 10th step it sends "hop 5" on
channel 1 and moves its emitter to channel 5."""

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
emitter = robot.getDevice("emitter")
steps = 0
while robot.step(time_step) != -1 and steps < 30:
    steps += 1
    if steps == 10:
        emitter.send("hop 5")
        emitter.setChannel(5)
    else:
        emitter.send(f"hopper:{steps}")
