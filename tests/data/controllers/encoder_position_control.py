"""Position control with encoders: both wheels turn 12 rad, then odometry says how far.

Test controller of mazesim's Webots interoperability (tests/test_webots_controllers.py).
"""

from controller import Robot

WHEEL_TURN = 12.0  # rad

robot = Robot()
timestep = int(robot.getBasicTimeStep())

left_motor = robot.getDevice("left wheel motor")
right_motor = robot.getDevice("right wheel motor")
left_encoder = robot.getDevice("left wheel sensor")
right_encoder = robot.getDevice("right wheel sensor")
left_encoder.enable(timestep)
right_encoder.enable(timestep)

robot.step(timestep)
start_left = left_encoder.getValue()
start_right = right_encoder.getValue()
left_motor.setVelocity(4.0)
right_motor.setVelocity(4.0)
left_motor.setPosition(start_left + WHEEL_TURN)
right_motor.setPosition(start_right + WHEEL_TURN)

settled = 0
while robot.step(timestep) != -1:
    left_error = start_left + WHEEL_TURN - left_encoder.getValue()
    right_error = start_right + WHEEL_TURN - right_encoder.getValue()
    if abs(left_error) < 0.01 and abs(right_error) < 0.01:
        settled += 1
        if settled > 5:
            break

print(f"left turned {left_encoder.getValue() - start_left:.4f} rad")
print(f"right turned {right_encoder.getValue() - start_right:.4f} rad")
