"""Paces itself to real time with ``time.time()`` and prints a status line every half second of
wall-clock time, as controllers written for a live robot do.

Test controller of mazesim's Webots interoperability (tests/test_webots_user_controllers.py).
"""

import time

from controller import Robot

robot = Robot()
timestep = int(robot.getBasicTimeStep())
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
left.setPosition(float("inf"))
right.setPosition(float("inf"))
left.setVelocity(3.0)
right.setVelocity(2.0)

start = time.time()
last_status = start
steps = 0
while robot.step(timestep) != -1:
    steps += 1
    ahead = robot.getTime() - (time.time() - start)
    if ahead > 0:
        time.sleep(ahead)
    now = time.time()
    if now - last_status >= 0.5:
        print(f"t={robot.getTime():.2f} s wall={now - start:.2f} s")
        last_status = now
print(f"paced {steps} steps in {time.time() - start:.2f} s of wall-clock time")
