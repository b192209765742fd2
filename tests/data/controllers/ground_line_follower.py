"""Follows the black line with the three ground sensors, as e-puck line followers do: the
sensor that sees black pulls the robot its way.

Test controller of mazesim's Webots interoperability (tests/test_webots_controllers.py).
"""

from controller import Robot

TIME_STEP = 32
MAX_SPEED = 6.28
BLACK = 500


def main():
    robot = Robot()
    ground = []
    for name in ["gs0", "gs1", "gs2"]:
        sensor = robot.getDevice(name)
        sensor.enable(TIME_STEP)
        ground.append(sensor)
    left_motor = robot.getDevice("left wheel motor")
    right_motor = robot.getDevice("right wheel motor")
    left_motor.setPosition(float("inf"))
    right_motor.setPosition(float("inf"))

    while robot.step(TIME_STEP) != -1:
        left_black, middle_black, right_black = (s.getValue() < BLACK for s in ground)
        if left_black and not right_black:
            left_speed, right_speed = 0.1 * MAX_SPEED, 0.5 * MAX_SPEED
        elif right_black and not left_black:
            left_speed, right_speed = 0.5 * MAX_SPEED, 0.1 * MAX_SPEED
        elif middle_black:
            left_speed, right_speed = 0.5 * MAX_SPEED, 0.5 * MAX_SPEED
        else:
            # Lost: turn on the spot towards the inside of the loop until a sensor finds it.
            left_speed, right_speed = -0.2 * MAX_SPEED, 0.2 * MAX_SPEED
        left_motor.setVelocity(left_speed)
        right_motor.setVelocity(right_speed)


if __name__ == "__main__":
    main()
