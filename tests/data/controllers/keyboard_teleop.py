"""Keyboard teleoperation: arrows drive, S stops, Q ends the controller.

Test controller of mazesim's Webots interoperability (tests/test_webots_controllers.py).
"""

from controller import Keyboard, Robot

SPEED = 4.0

robot = Robot()
timestep = int(robot.getBasicTimeStep())
keyboard = Keyboard()
keyboard.enable(timestep)

left_motor = robot.getDevice("left wheel motor")
right_motor = robot.getDevice("right wheel motor")
for motor in (left_motor, right_motor):
    motor.setPosition(float("inf"))
    motor.setVelocity(0.0)

pressed = set()
while robot.step(timestep) != -1:
    left, right = 0.0, 0.0
    key = keyboard.getKey()
    while key != -1:
        pressed.add(key)
        if key == Keyboard.UP:
            left, right = SPEED, SPEED
        elif key == Keyboard.DOWN:
            left, right = -SPEED, -SPEED
        elif key == Keyboard.LEFT:
            left, right = -SPEED / 2, SPEED / 2
        elif key == Keyboard.RIGHT:
            left, right = SPEED / 2, -SPEED / 2
        elif key == Keyboard.SHIFT + ord("Q"):
            print("quit key")
            raise SystemExit(0)
        key = keyboard.getKey()
    left_motor.setVelocity(left)
    right_motor.setVelocity(right)

print("keys seen:", sorted(pressed))
