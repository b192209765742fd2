"""Touches every device of the e-puck with `from controller import *` and prints a reading of
each, spinning in place so that the gyro sees a turn.

Test controller of mazesim's Webots interoperability (tests/test_webots_controllers.py).
"""

from controller import *  # noqa: F403

robot = Robot()  # noqa: F405
timestep = int(robot.getBasicTimeStep())
sensors = {}
names = [f"ps{i}" for i in range(8)] + [f"ls{i}" for i in range(8)]
names += ["gs0", "gs1", "gs2", "accelerometer", "gyro", "camera", "receiver"]
for name in names:
    device = robot.getDevice(name)
    device.enable(timestep)
    sensors[name] = device
for i in range(10):
    robot.getDevice(f"led{i}").set(i % 2)
robot.getDevice("emitter").send("hello")
robot.getDevice("speaker").speak("hello", 1.0)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
left.setPosition(float("inf"))
right.setPosition(float("inf"))
left.setVelocity(-2.0)
right.setVelocity(2.0)

for _ in range(20):
    robot.step(timestep)

print("ps0", round(sensors["ps0"].getValue(), 1))
print("ls0", round(sensors["ls0"].getValue(), 1))
print("gs1", round(sensors["gs1"].getValue(), 1))
print("accelerometer z", round(sensors["accelerometer"].getValues()[2], 2))
print("gyro z", round(sensors["gyro"].getValues()[2], 3))
camera = sensors["camera"]
print("camera", camera.getWidth(), camera.getHeight(), len(camera.getImage()))
print("receiver queue", sensors["receiver"].getQueueLength())
print("led1", robot.getDevice("led1").get())
print("model", robot.getModel())
print("missing", robot.getDevice("lidar"))
