"""Drives forward, leaves its loop when the run ends, then fails while tidying up.

Test controller of mazesim's Webots interoperability (tests/test_webots_controllers.py).
"""

from controller import Robot

robot = Robot()
timestep = int(robot.getBasicTimeStep())
for name in ("left wheel motor", "right wheel motor"):
    motor = robot.getDevice(name)
    motor.setPosition(float("inf"))
    motor.setVelocity(2.0)

while robot.step(timestep) != -1:
    pass

results = {"laps": 0}
print("average lap", 10 / results["laps"])
