"""A ``MyRobot(Robot)`` class whose ``run()`` steps with ``self.step``, as object-style
controllers are written.

Test controller of mazesim's Webots interoperability (tests/test_webots_user_controllers.py).
"""

from controller import Robot


class MyRobot(Robot):
    """Braitenberg obstacle avoidance on the eight proximity sensors."""

    WEIGHTS_LEFT = (-1.0, -0.8, -0.4, 0.0, 0.0, 0.4, 0.8, 1.0)

    def __init__(self):
        super().__init__()
        self.timestep = int(self.getBasicTimeStep())
        self.sensors = [self.getDevice(f"ps{i}") for i in range(8)]
        for sensor in self.sensors:
            sensor.enable(self.timestep)
        self.left_motor = self.getDevice("left wheel motor")
        self.right_motor = self.getDevice("right wheel motor")
        for motor in (self.left_motor, self.right_motor):
            motor.setPosition(float("inf"))
            motor.setVelocity(0.0)
        self.steps = 0

    def run(self):
        while self.step(self.timestep) != -1:
            self.steps += 1
            values = [sensor.getValue() / 4096.0 for sensor in self.sensors]
            left = 3.0 + sum(w * v for w, v in zip(self.WEIGHTS_LEFT, values)) * 8.0
            right = 3.0 - sum(w * v for w, v in zip(self.WEIGHTS_LEFT, values)) * 8.0
            limit = self.left_motor.getMaxVelocity()
            self.left_motor.setVelocity(max(-limit, min(limit, left)))
            self.right_motor.setVelocity(max(-limit, min(limit, right)))
        print(f"MyRobot stepped {self.steps} times")


if __name__ == "__main__":
    robot = MyRobot()
    robot.run()
