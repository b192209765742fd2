"""Logs the proximity readings into numpy arrays and saves a matplotlib plot at the end, as
data-collecting controllers do.

Test controller of mazesim's Webots interoperability (tests/test_webots_user_controllers.py).
"""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from controller import Robot  # noqa: E402

robot = Robot()
timestep = int(robot.getBasicTimeStep())
sensors = [robot.getDevice(f"ps{i}") for i in range(8)]
for sensor in sensors:
    sensor.enable(timestep)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
left.setPosition(float("inf"))
right.setPosition(float("inf"))
left.setVelocity(4.0)
right.setVelocity(4.0)

times, readings = [], []
while robot.step(timestep) != -1:
    times.append(robot.getTime())
    readings.append([sensor.getValue() for sensor in sensors])

data = np.array(readings)
figure, axes = plt.subplots()
for index in range(data.shape[1]):
    axes.plot(times, data[:, index], label=f"ps{index}")
axes.set_xlabel("time (s)")
axes.set_ylabel("reading")
axes.legend()
figure.savefig("proximity.png")
np.save("proximity.npy", data)
print(f"saved {data.shape[0]} rows, ps0 max {data[:, 0].max():.0f}")
