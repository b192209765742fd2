"""Webots' stock controllers that a PROTO names by default, written for mazesim.

A robot whose world file leaves its ``controller`` field out runs the controller its PROTO
declares (:mod:`mazesim.webots.proto_fields`): for the E-puck, ``e-puck_avoid_obstacles``,
which Webots finds among its own projects when the world's project has no controller of that
name. mazesim runs this file in its place (as ``__main__``, with the ``controller`` module of
:mod:`mazesim.webots.controller`), a controller written here from how Webots' own behaves.

``e-puck_avoid_obstacles`` (cyberbotics/webots, ``projects/robots/gctronic/e-puck/
controllers/e-puck_avoid_obstacles``, R2022b on): a Braitenberg vehicle. Each step it reads the
eight proximity sensors scaled to [0, 1] (the raw value / 4096) and sets each wheel to
0.5 * 6.28 rad/s plus 6.28 times the weighted sum of them, clamped to +-6.28 rad/s; the
weights (left wheel, right wheel) of ps0..ps7 are (-1.3, -1.0), (-1.3, -1.0), (-0.5, 0.5),
(0, 0), (0, 0), (0.05, -0.5), (-0.75, 0), (-0.75, 0). It lights one of the ten LEDs after
another, each for 10 steps. With all three ground sensors gs0..gs2 fitted, a ground value
below 500 (a cliff) makes it reverse at full speed for 0.2 s, then spin left for 0.2 s.
It prints ``Default controller of the e-puck robot started...`` as it starts.
"""

from __future__ import annotations

import math
from typing import Any

from mazesim._core import EPUCK_DEFAULT_CONTROLLER

__all__ = ["STOCK", "stock_controller"]

#: The stock controllers mazesim has, by the name a ``controller`` field gives: their files.
STOCK = {EPUCK_DEFAULT_CONTROLLER: __file__}

#: Full wheel speed of Webots' E-puck (rad/s).
MAX_SPEED = 6.28
#: The Braitenberg weights (left wheel, right wheel) of ps0..ps7.
WEIGHTS = (
    (-1.3, -1.0),
    (-1.3, -1.0),
    (-0.5, 0.5),
    (0.0, 0.0),
    (0.0, 0.0),
    (0.05, -0.5),
    (-0.75, 0.0),
    (-0.75, 0.0),
)
#: A ground sensor below this reads a cliff.
CLIFF = 500.0
#: Seconds of each of the two moves away from a cliff.
ESCAPE_S = 0.2


def stock_controller(name: str) -> str | None:
    """The file of the stock controller ``name``, or None if mazesim has none of that name."""
    return STOCK.get(name)


def wheel_speeds(proximity: list[float]) -> tuple[float, float]:
    """The left and right wheel speeds (rad/s) the Braitenberg weights give for the raw values
    of ps0..ps7."""
    speeds = []
    for wheel in (0, 1):
        total = sum(value / 4096.0 * weight[wheel] for value, weight in zip(proximity, WEIGHTS))
        speed = 0.5 * MAX_SPEED + total * MAX_SPEED
        speeds.append(min(MAX_SPEED, max(-MAX_SPEED, speed)))
    return speeds[0], speeds[1]


def e_puck_avoid_obstacles() -> None:
    """Runs the E-puck's default controller until the simulation ends."""
    from controller import Robot  # type: ignore[import-not-found]

    robot = Robot()
    step = int(robot.getBasicTimeStep())
    print("Default controller of the e-puck robot started...")
    proximity = [robot.getDevice(f"ps{i}") for i in range(8)]
    for sensor in proximity:
        sensor.enable(step)
    leds = [robot.getDevice(f"led{i}") for i in range(10)]
    names = {robot.getDeviceByIndex(i).getName() for i in range(robot.getNumberOfDevices())}
    ground: list[Any] = []
    if all(f"gs{i}" in names for i in range(3)):
        ground = [robot.getDevice(f"gs{i}") for i in range(3)]
        for sensor in ground:
            sensor.enable(step)
    left, right = robot.getDevice("left wheel motor"), robot.getDevice("right wheel motor")
    for motor in (left, right):
        motor.setPosition(math.inf)
        motor.setVelocity(0.0)

    def wait(seconds: float) -> bool:
        start = robot.getTime()
        while True:
            if robot.step(step) == -1:
                return False
            if robot.getTime() >= start + seconds:
                return True

    if robot.step(step) == -1:
        return
    counter = 0
    while True:
        counter += 1
        for index, led in enumerate(leds):
            if led is not None:
                led.set(1 if index == (counter // 10) % len(leds) else 0)
        if ground and any(sensor.getValue() < CLIFF for sensor in ground):
            for speed_left, speed_right in ((-MAX_SPEED, -MAX_SPEED), (-MAX_SPEED, MAX_SPEED)):
                left.setVelocity(speed_left)
                right.setVelocity(speed_right)
                if not wait(ESCAPE_S):
                    return
            speed_left = speed_right = 0.0
        else:
            speed_left, speed_right = wheel_speeds([sensor.getValue() for sensor in proximity])
        left.setVelocity(speed_left)
        right.setVelocity(speed_right)
        if robot.step(step) == -1:
            return


if __name__ == "__main__":
    e_puck_avoid_obstacles()
