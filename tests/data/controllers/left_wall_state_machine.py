"""Left-wall follower as a state machine, turning 90 degrees on the wheel encoders.

Test controller of mazesim's Webots interoperability (tests/test_webots_user_controllers.py).
Written as course controllers are: the e-puck datasheet's wheel radius and axle length
(calibrated on the real robot, not on the simulation), ps5/ps6 for the wall on the left and
ps7/ps0 for the wall ahead, and the odometry of a turn in place.
"""

import math

from controller import Robot

R = 0.0205  # wheel radius (m), e-puck datasheet
D = 0.052  # distance between the wheels (m), e-puck datasheet
MAX_SPEED = 6.28
WALL_AHEAD = 100.0
WALL_LEFT = 80.0
TOO_CLOSE = 300.0

robot = Robot()
timestep = int(robot.getBasicTimeStep())
ps = {}
for name in ("ps0", "ps5", "ps6", "ps7"):
    ps[name] = robot.getDevice(name)
    ps[name].enable(timestep)
left_motor = robot.getDevice("left wheel motor")
right_motor = robot.getDevice("right wheel motor")
left_motor.setPosition(float("inf"))
right_motor.setPosition(float("inf"))
left_encoder = robot.getDevice("left wheel sensor")
right_encoder = robot.getDevice("right wheel sensor")
left_encoder.enable(timestep)
right_encoder.enable(timestep)

state = "FORWARD"
turn_start = (0.0, 0.0)
turns = 0
states_seen = set()


def heading_change(start):
    """Angle turned since ``start`` (encoder readings), from the datasheet's R and D."""
    left = left_encoder.getValue() - start[0]
    right = right_encoder.getValue() - start[1]
    return (right - left) * R / D


while robot.step(timestep) != -1:
    if math.isnan(ps["ps0"].getValue()) or math.isnan(left_encoder.getValue()):
        continue
    front = max(ps["ps0"].getValue(), ps["ps7"].getValue())
    left_wall = max(ps["ps5"].getValue(), ps["ps6"].getValue())
    states_seen.add(state)
    if state == "FORWARD":
        if front > WALL_AHEAD:
            state = "TURN_RIGHT"
            turn_start = (left_encoder.getValue(), right_encoder.getValue())
            left_speed, right_speed = 0.4 * MAX_SPEED, -0.4 * MAX_SPEED
        elif left_wall > TOO_CLOSE:
            left_speed, right_speed = 0.6 * MAX_SPEED, 0.4 * MAX_SPEED
        elif left_wall < WALL_LEFT:
            left_speed, right_speed = 0.35 * MAX_SPEED, 0.6 * MAX_SPEED
        else:
            left_speed, right_speed = 0.6 * MAX_SPEED, 0.6 * MAX_SPEED
    else:
        if abs(heading_change(turn_start)) >= math.pi / 2:
            state = "FORWARD"
            turns += 1
            left_speed, right_speed = 0.6 * MAX_SPEED, 0.6 * MAX_SPEED
        else:
            left_speed, right_speed = 0.4 * MAX_SPEED, -0.4 * MAX_SPEED
    left_motor.setVelocity(left_speed)
    right_motor.setVelocity(right_speed)

print(f"turns {turns} states {sorted(states_seen)}")
