"""Go to a goal with a GPS and a compass mounted in the e-puck's turret slot.

Test controller of mazesim's Webots interoperability (tests/test_webots_controllers.py).
"""

import math

from controller import Robot

GOAL = (0.3, 0.25)
MAX_SPEED = 6.28


def heading(north):
    # The compass gives north in the robot's frame; in ENU north is +y.
    return math.atan2(north[0], north[1])


robot = Robot()
timestep = int(robot.getBasicTimeStep())
gps = robot.getDevice("gps")
compass = robot.getDevice("compass")
gps.enable(timestep)
compass.enable(timestep)
left_motor = robot.getDevice("left wheel motor")
right_motor = robot.getDevice("right wheel motor")
left_motor.setPosition(float("inf"))
right_motor.setPosition(float("inf"))

while robot.step(timestep) != -1:
    x, y, _ = gps.getValues()
    dx, dy = GOAL[0] - x, GOAL[1] - y
    if math.hypot(dx, dy) < 0.02:
        left_motor.setVelocity(0.0)
        right_motor.setVelocity(0.0)
        print(f"reached the goal at {x:.3f} {y:.3f}")
        break
    error = math.atan2(dy, dx) - heading(compass.getValues())
    error = math.atan2(math.sin(error), math.cos(error))
    forward = 0.5 * MAX_SPEED * max(0.0, math.cos(error))
    turn = 2.0 * error
    left_motor.setVelocity(max(-MAX_SPEED, min(MAX_SPEED, forward - turn)))
    right_motor.setVelocity(max(-MAX_SPEED, min(MAX_SPEED, forward + turn)))
