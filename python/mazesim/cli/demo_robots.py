"""``mazesim demo`` on a world of several robots (``[[robots]]``, ``docs/multi-robot.md``).

Every robot runs the report's avoid-collision controller (Alg. 1) on its own proximity sensors,
all in lockstep in one simulator, for ``--seconds``; ``DIR/summary.json``, ``DIR/trajectory.png``
and ``--html``/``--video``/``--record`` cover every robot, as does the ``--live`` window.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import time
from typing import Any, TextIO

import numpy as np

from mazesim._atomic import atomic_file
from mazesim._core import RobotProfile, Simulator
from mazesim._paths import make_output_folder
from mazesim.cli.demo import speed_summary
from mazesim.cli.progress import progress_display
from mazesim.errors import InvalidArgumentError, _shown

__all__ = ["proximity_columns", "run_robots_demo"]

#: The e-puck's proximity sensors, which the avoid-collision controller reads.
PROXIMITY = [f"ps{i}" for i in range(8)]


def proximity_columns(robot: RobotProfile, name: str | None = None) -> list[int]:
    """The columns of ps0-ps7 among a robot's distance sensors (the e-puck2 lists its ToF beside
    them).

    Raises:
        InvalidArgumentError: The robot lacks the e-puck's 8 raw proximity sensors.
    """
    names = list(robot.distance_sensor_names)
    if robot.distance_sensor_unit != "raw" or not set(PROXIMITY) <= set(names):
        which = f"robot {_shown(name)} ({robot.name})" if name else f"robot {_shown(robot.name)}"
        raise InvalidArgumentError(
            f"the demo's avoid-collision controller needs the e-puck's 8 raw proximity sensors "
            f"ps0-ps7; {which} has {', '.join(names)} in {_shown(robot.distance_sensor_unit)}"
        )
    return [names.index(sensor) for sensor in PROXIMITY]


def run_robots_demo(
    args: argparse.Namespace, out: TextIO, simulator: Simulator, seconds: float
) -> int:
    """Drives every robot of ``simulator`` with the avoid-collision controller for ``seconds``
    and writes the picture, the summary and the views asked for."""
    from mazesim.controllers import AvoidCollision
    from mazesim.plotting import save_robot_paths_png
    from mazesim.replay.views import SimulatorWatch, written_lines

    world = simulator.world
    names = list(simulator.robot_names)
    count = len(names)
    profiles = [simulator.robot_profile(i) for i in range(count)]
    columns = [proximity_columns(profile, name) for profile, name in zip(profiles, names)]
    controllers = [AvoidCollision(max_speed=profile.max_wheel_speed) for profile in profiles]
    make_output_folder(args.out)
    steps = max(1, math.ceil(seconds * 1000.0 / simulator.control_step_ms - 1e-9))
    watch = SimulatorWatch(args, simulator, "avoid-collision", args.seed)
    paths = np.empty((count, steps + 1, 2), dtype=np.float64)
    paths[:, 0] = simulator.poses()[:, :2]
    commands = np.zeros((count, 2), dtype=np.float64)
    started = time.perf_counter()
    with progress_display(args, unit="steps") as progress:
        for step in range(1, steps + 1):
            for index in range(count):
                readings = simulator.distance_sensors(robot_index=index)
                commands[index] = controllers[index](readings[columns[index]])
            watch.before_robots_step(commands)
            simulator.step_robots(commands)
            paths[:, step] = simulator.poses()[:, :2]
            progress("simulating", step, steps)
    wall_clock = time.perf_counter() - started
    states = [simulator.robot_state(i) for i in range(count)]
    summary: dict[str, Any] = {
        "world": world.name,
        "seed": args.seed,
        "controller": "avoid-collision",
        "simulated_seconds": simulator.time,
        "steps": simulator.steps,
        "robots": [
            {
                "name": name,
                "robot": profile.name,
                "distance_m": float(state["distance_travelled"]),
                "collisions": int(state["collisions"]),
                "final_pose": [float(v) for v in state["pose"]],
            }
            for name, profile, state in zip(names, profiles, states)
        ],
        **speed_summary(simulator.time, wall_clock),
    }
    picture = os.path.join(args.out, "trajectory.png")
    save_robot_paths_png(
        world,
        [(name, paths[i, :, 0], paths[i, :, 1]) for i, name in enumerate(names)],
        picture,
        title=f"{world.name}: {count} robots, avoid-collision, {simulator.time:.0f} s, "
        f"seed {args.seed}",
    )
    summary_path = os.path.join(args.out, "summary.json")
    with atomic_file(summary_path) as handle:
        handle.write((json.dumps(summary, indent=2) + "\n").encode("utf-8"))
    views = watch.finish(f"{simulator.time:.0f} s up")
    out.write(
        f"world              {world.name} ({count} robots, seed {args.seed})\n"
        f"simulated time     {simulator.time:.2f} s ({simulator.steps} steps)\n"
    )
    for entry in summary["robots"]:
        out.write(
            f"  {entry['name']:<16} {entry['distance_m']:.2f} m, {entry['collisions']} collisions\n"
        )
    out.write(written_lines(args, picture, [picture, summary_path, *views]))
    return 0
