"""Steps four basic time steps at a time and counts the control steps.

Test controller of mazesim's Webots interoperability (tests/test_webots_controllers.py).
"""

from controller import Robot

robot = Robot()
timestep = int(robot.getBasicTimeStep())
left_motor = robot.getDevice("left wheel motor")
right_motor = robot.getDevice("right wheel motor")
left_motor.setPosition(float("inf"))
right_motor.setPosition(float("inf"))
left_motor.setVelocity(2.0)
right_motor.setVelocity(-2.0)

count = 0
last_time = robot.getTime()
gaps = set()
while robot.step(4 * timestep) != -1:
    count += 1
    gaps.add(round((robot.getTime() - last_time) * 1000))
    last_time = robot.getTime()
print(f"control steps {count}")
print(f"gaps ms {sorted(gaps)}")
