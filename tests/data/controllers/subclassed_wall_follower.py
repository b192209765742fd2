"""A robot class that follows the wall on its left, written as a Robot subclass.

Test controller of mazesim's Webots interoperability (tests/test_webots_controllers.py).
"""

from controller import Robot


class WallFollower(Robot):
    SPEED = 4.0
    NEAR = 150.0
    FAR = 90.0

    def __init__(self):
        super().__init__()
        self.timestep = int(self.getBasicTimeStep())
        self.sensors = []
        for i in range(8):
            sensor = self.getDevice(f"ps{i}")
            sensor.enable(self.timestep)
            self.sensors.append(sensor)
        self.left_motor = self.getDevice("left wheel motor")
        self.right_motor = self.getDevice("right wheel motor")
        for motor in (self.left_motor, self.right_motor):
            motor.setPosition(float("inf"))
            motor.setVelocity(0.0)

    def drive(self, left, right):
        self.left_motor.setVelocity(left)
        self.right_motor.setVelocity(right)

    def run(self):
        while self.step(self.timestep) != -1:
            values = [sensor.getValue() for sensor in self.sensors]
            front = max(values[0], values[7])
            left_side = values[5]
            if front > self.NEAR:
                self.drive(self.SPEED, -self.SPEED)
            elif left_side > self.NEAR:
                self.drive(self.SPEED, self.SPEED * 0.6)
            elif left_side < self.FAR:
                self.drive(self.SPEED * 0.6, self.SPEED)
            else:
                self.drive(self.SPEED, self.SPEED)


controller = WallFollower()
controller.run()
