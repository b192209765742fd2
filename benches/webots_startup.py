"""Start-up of a Webots world's controller processes (a benchmark, not a test: run it by hand).

For each number of robots it writes a Webots project into a temporary folder: one world of that
many E-pucks on a 15 m x 15 m arena, a grid 0.5 m apart, every one running the controller
``wander`` (``from controller import Robot, DistanceSensor``, enables the eight proximity
sensors, sets its wheels and takes ``--steps`` basic steps). It then runs the world with
:func:`mazesim.webots.lockstep.run_world`, several times, and prints the median real time of
the run and the processor time of this process and of every process it started (the controller
processes, and the process they are made from), both from the run's start to its end::

    .venv/bin/python benches/webots_startup.py [--robots 1 10 40] [--repeats 3] [--steps 1]

With one step, a run is almost all start-up: importing the world, starting each controller's
process and the controller's own set-up. Run it with another build's interpreter
(``OTHER/.venv/bin/python benches/webots_startup.py``) to compare builds.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

from mazesim.webots.lockstep import run_world

CONTROLLER = '''"""Enables the proximity sensors, sets the wheels and takes a few basic steps."""

import sys

from controller import DistanceSensor, Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
sensors = [robot.getDevice(f"ps{i}") for i in range(8)]
for sensor in sensors:
    sensor.enable(time_step)
for name in ("left wheel motor", "right wheel motor"):
    motor = robot.getDevice(name)
    motor.setPosition(float("inf"))
    motor.setVelocity(1.0)
steps = int(sys.argv[1]) if len(sys.argv) > 1 else 1
while steps > 0 and robot.step(time_step) != -1:
    steps -= 1
    readings = [sensor.getValue() for sensor in sensors]
assert isinstance(sensors[0], DistanceSensor)
'''


def write_project(folder: Path, robots: int, steps: int) -> Path:
    """A Webots project of ``robots`` E-pucks running ``wander``; returns the world file."""
    (folder / "worlds").mkdir(parents=True)
    (folder / "controllers" / "wander").mkdir(parents=True)
    (folder / "controllers" / "wander" / "wander.py").write_text(CONTROLLER, encoding="utf-8")
    lines = [
        "#VRML_SIM R2023b utf8",
        'EXTERNPROTO "webots://projects/objects/floors/protos/RectangleArena.proto"',
        'EXTERNPROTO "webots://projects/robots/gctronic/e-puck/protos/E-puck.proto"',
        "WorldInfo {",
        "  basicTimeStep 16",
        "}",
        "RectangleArena {",
        "  floorSize 15 15",
        "}",
    ]
    for index in range(robots):
        x, y = -5.0 + 0.5 * (index % 20), -5.0 + 0.5 * (index // 20)
        lines += [
            "E-puck {",
            f"  translation {x:g} {y:g} 0",
            f'  name "e-puck_{index}"',
            '  controller "wander"',
            f'  controllerArgs [ "{steps}" ]',
            "}",
        ]
    world = folder / "worlds" / "crowd.wbt"
    world.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return world


def processor_seconds() -> float:
    """User and system time of this process and of the processes it has waited for."""
    times = os.times()
    return times.user + times.system + times.children_user + times.children_system


def measure(world: Path, seconds: float) -> tuple[float, float]:
    """Real and processor seconds of one run of the world."""
    processor, started = processor_seconds(), time.perf_counter()
    run = run_world(str(world), seconds=seconds, noise=False)
    wall = time.perf_counter() - started
    failed = [r.name for r in run.robots if r.exit_status or r.error]
    if failed:
        raise SystemExit(f"controllers failed: {failed}: {run.robots[0].error}")
    return wall, processor_seconds() - processor


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robots", type=int, nargs="+", default=[1, 10, 40])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--steps", type=int, default=1, help="basic steps each controller takes")
    args = parser.parse_args()
    print(f"{sys.executable}, load average {os.getloadavg()[0]:.1f}")
    print("robots  wall s (median)  processor s (median)  runs")
    for robots in args.robots:
        with tempfile.TemporaryDirectory(prefix="mazesim-startup-") as folder:
            world = write_project(Path(folder), robots, args.steps)
            runs = [measure(world, 60.0) for _ in range(args.repeats)]
        walls, processors = zip(*runs)
        detail = ", ".join(f"{w:.2f}/{p:.2f}" for w, p in runs)
        print(
            f"{robots:6d}  {statistics.median(walls):14.2f}  {statistics.median(processors):19.2f}"
            f"  {detail}",
            flush=True,
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
