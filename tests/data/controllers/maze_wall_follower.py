"""A student-style maze solver: keeps the wall on its right with the proximity sensors,
turns left at a dead end, and counts its turns.

Test controller of mazesim's Webots interoperability (tests/test_webots_controllers.py).
"""

from controller import DistanceSensor, Motor, Robot

robot = Robot()
timestep = int(robot.getBasicTimeStep())
MAX_SPEED = 6.28

ps = []
for i in range(8):
    sensor = robot.getDevice("ps" + str(i))
    assert isinstance(sensor, DistanceSensor)
    sensor.enable(timestep)
    ps.append(sensor)
left_motor = robot.getDevice("left wheel motor")
right_motor = robot.getDevice("right wheel motor")
assert isinstance(left_motor, Motor)
left_motor.setPosition(float("inf"))
right_motor.setPosition(float("inf"))

turns = 0
turning = False
while robot.step(timestep) != -1:
    values = [s.getValue() for s in ps]
    front_wall = values[0] > 100 or values[7] > 100
    right_wall = values[2] > 80
    right_corner = values[1] > 80
    if front_wall:
        left_speed, right_speed = -MAX_SPEED / 2, MAX_SPEED / 2
        if not turning:
            turns += 1
        turning = True
    else:
        turning = False
        if right_wall:
            left_speed, right_speed = MAX_SPEED / 2, MAX_SPEED / 2
        elif right_corner:
            left_speed, right_speed = MAX_SPEED / 2, MAX_SPEED / 4
        else:
            left_speed, right_speed = MAX_SPEED / 2, MAX_SPEED / 8
    left_motor.setVelocity(left_speed)
    right_motor.setVelocity(right_speed)

print("turns", turns)
