"""Opens a log file that does not exist after a few steps: the error is the controller's own.

Test controller of mazesim's Webots interoperability (tests/test_webots_controllers.py).
"""

from controller import Robot

robot = Robot()
timestep = int(robot.getBasicTimeStep())
for _ in range(10):
    robot.step(timestep)
with open("no-such-folder/log.txt") as log:
    print(log.read())
