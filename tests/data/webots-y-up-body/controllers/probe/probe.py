"""Drives ahead and prints what its GPS, distance sensors, inertial unit and accelerometer
read."""

from controller import Robot

robot = Robot()
step = int(robot.getBasicTimeStep())
gps = robot.getDevice("gps")
unit = robot.getDevice("inertial unit")
accelerometer = robot.getDevice("accelerometer")
sensors = [robot.getDevice(name) for name in ("ps0", "front")]
for device in (gps, unit, accelerometer, *sensors):
    device.enable(step)
for side in ("left", "right"):
    motor = robot.getDevice(f"{side} wheel motor")
    motor.setPosition(float("inf"))
    motor.setVelocity(2.0)
for count in range(1, 31):
    robot.step(step)
    if count in (1, 30):
        x, y, z = gps.getValues()
        ps0, front = (sensor.getValue() for sensor in sensors)
        print(f"step {count} gps {x:.5f} {y:.5f} {z:.5f} ps0 {ps0:.3f} front {front:.3f}")
        roll, pitch, yaw = unit.getRollPitchYaw()
        ax, ay, az = accelerometer.getValues()
        print(f"attitude {roll:.4f} {pitch:.4f} {yaw:.4f} gravity {ax:.3f} {ay:.3f} {az:.3f}")
