"""A course obstacle: a plain Robot body that slides itself out of the way by its own
translation, 1 cm a step, once the e-puck has waited in front of it for 20 steps."""

from controller import Supervisor

robot = Supervisor()
time_step = int(robot.getBasicTimeStep())
translation = robot.getSelf().getField("translation")
x, y, z = translation.getSFVec3f()
steps = 0
while robot.step(time_step) != -1:
    steps += 1
    if 20 <= steps < 45:
        y += 0.01
        translation.setSFVec3f([x, y, z])
