"""Follows a black line on a white floor with the camera: the dark pixels of the bottom rows
steer the robot (proportional control on the line's column).

Test controller of mazesim's Webots interoperability (tests/test_webots_controllers.py).
"""

from controller import Camera, Robot

MAX_SPEED = 6.28
BASE_SPEED = 2.5
GAIN = 4.0
DARK = 80

robot = Robot()
timestep = int(robot.getBasicTimeStep())
camera = robot.getDevice("camera")
camera.enable(timestep)
width = camera.getWidth()
height = camera.getHeight()

left_motor = robot.getDevice("left wheel motor")
right_motor = robot.getDevice("right wheel motor")
left_motor.setPosition(float("inf"))
right_motor.setPosition(float("inf"))
left_motor.setVelocity(0.0)
right_motor.setVelocity(0.0)

last_error = 0.0
while robot.step(timestep) != -1:
    image = camera.getImage()
    if image is None:
        continue
    columns = []
    for y in range(height - 8, height):
        for x in range(width):
            if Camera.imageGetGray(image, width, x, y) < DARK:
                columns.append(x)
    if columns:
        centre = sum(columns) / len(columns)
        last_error = (centre - width / 2) / (width / 2)
    # A lost line: keep turning the way it was last seen.
    turn = GAIN * last_error
    left_speed = max(-MAX_SPEED, min(MAX_SPEED, BASE_SPEED + turn))
    right_speed = max(-MAX_SPEED, min(MAX_SPEED, BASE_SPEED - turn))
    left_motor.setVelocity(left_speed)
    right_motor.setVelocity(right_speed)
