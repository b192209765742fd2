"""The Python twin of c_lens_torque/c_lens_torque.c and cpp_lens_torque: a camera's lens, a
motor's torque and force, lookup tables, sensor types and the robot's battery, URDF and robot
window, printed alike."""

import math

from controller import GPS, Robot


def shown(value):
    return "none" if value is None or math.isnan(value) else f"{value:.6f}"


robot = Robot()
step = int(robot.getBasicTimeStep())
camera = robot.getDevice("camera")
motor = robot.getDevice("left wheel motor")
encoder = robot.getDevice("left wheel sensor")
light = robot.getDevice("ls0")
accelerometer = robot.getDevice("accelerometer")
camera.enable(step)
camera.setFov(camera.getFov())
camera.setExposure(2.0)
camera.setFocalDistance(0.5)
print("fov", shown(camera.getFov()), shown(camera.getMinFov()), shown(camera.getMaxFov()))
print("exposure", shown(camera.getExposure()), "near", shown(camera.getNear()))
print(
    "focus",
    shown(camera.getFocalLength()),
    shown(camera.getFocalDistance()),
    shown(camera.getMinFocalDistance()),
    shown(camera.getMaxFocalDistance()),
)
motor.setAvailableTorque(5.0)
motor.enableTorqueFeedback(step)
print("torque", shown(motor.getAvailableTorque()), shown(motor.getMaxTorque()))
print("force", shown(motor.getAvailableForce()), shown(motor.getMaxForce()))
print("multiplier", shown(motor.getMultiplier()), "brake", 0 if motor.getBrake() is None else 1)
table = light.getLookupTable()
print("light table", len(table) // 3, " ".join(shown(v) for v in table[:3]))
print("accelerometer table", len(accelerometer.getLookupTable()) // 3)
print("encoder type", encoder.getType(), "brake", 0 if encoder.getBrake() is None else 1)
print("dms", GPS.convertToDegreesMinutesSeconds(12.5826))
robot.batterySensorEnable(step)
print("battery", shown(robot.batterySensorGetValue()), robot.batterySensorGetSamplingPeriod())
print("type", robot.getType(), "urdf", robot.getUrdf("my_").splitlines()[1])
robot.wwiSendText("hello")
print("window", robot.wwiReceiveText() or "none")
n = 0
while robot.stepBegin(step) != -1:
    robot.stepEnd()
    n += 1
    if n % 16 == 0:
        print("feedback", shown(motor.getTorqueFeedback()), motor.getTorqueFeedbackSamplingPeriod())
