"""``mazesim ros2 demo``: the bridge and a controller node over ROS 2, recorded in a bag.

The bridge (``seed`` robot in ``seed-maze``, lockstep, stopping at the goal) and the
perform-learning node (the shipped hierarchical navigator) run as two processes, as any two ROS 2
nodes would; the bridge records everything it publishes into ``OUT/bag`` (rosbag2, MCAP).
``--controller avoid-collision`` runs the e-puck with the avoid-collision node instead, for
``--steps`` steps.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path
from typing import NamedTuple

from mazesim._paths import make_output_folder
from mazesim.episodes import MAX_STEPS
from mazesim.errors import MazesimError, MazesimIOError
from mazesim.ros.local_master import LocalMaster
from mazesim.ros.topics import demo_robot

__all__ = ["DemoResult", "run_demo"]

#: Wall-clock seconds the demo waits for the bridge before giving up.
DEMO_TIMEOUT_S = 300.0


class DemoResult(NamedTuple):
    """What the demo did: steps run, the step at which the goal was reached, the bag."""

    steps: int
    goal_step: int | None
    bag: Path


def _command(*arguments: str) -> list[str]:
    return [sys.executable, "-m", "mazesim", "ros2", *arguments]


def run_demo(
    out: Path,
    controller: str = "hrl",
    distro: str = "humble",
    seed: int = 0,
    steps: int = MAX_STEPS,
    world: str = "seed-maze",
    robot: str | None = None,
) -> DemoResult:
    """Runs the bridge and a controller node until the goal (or ``steps``); returns the result.
    ``robot``: a built-in profile or a profile file (:func:`mazesim.ros.topics.demo_robot`).

    Raises:
        InvalidArgumentError: The robot lacks the sensors the controller node reads.
        MazesimIOError: ``OUT/bag`` exists already.
        MazesimError: The bridge failed or did not finish in time.
    """
    robot = demo_robot(controller, robot)
    make_output_folder(out, "out")
    bag = out / "bag"
    if bag.exists():
        raise MazesimIOError(f"expected a new bag folder; found {bag}, which exists")
    bridge_arguments = [
        "bridge", "--robot", robot, "--world", world, "--seed", str(seed),
        "--ros-distro", distro, "--stop-after", str(steps), "--bag", str(bag),
    ]  # fmt: skip
    if controller == "hrl":
        bridge_arguments.append("--stop-at-goal")
        node = _command("perform-learning", "--ros-distro", distro)
    else:
        node = _command("avoid-collision", "--ros-distro", distro)
    environment = dict(os.environ, PYTHONUNBUFFERED="1")
    bridge = subprocess.Popen(
        _command(*bridge_arguments), stderr=subprocess.PIPE, text=True, env=environment
    )
    driver = None
    try:
        driver = subprocess.Popen(node, stderr=subprocess.DEVNULL, env=environment)
        _, errors = bridge.communicate(timeout=DEMO_TIMEOUT_S)
    except subprocess.TimeoutExpired as error:
        raise MazesimError(
            f"expected the bridge to finish within {DEMO_TIMEOUT_S:.0f} s"
        ) from error
    finally:
        # Neither node outlives the demo, however it ends (a timeout, Ctrl-C): a bridge left
        # behind waited for a driver for its idle timeout, 10 minutes, writing to the terminal.
        for process in (driver, bridge):
            if process is not None:
                LocalMaster.stop_process(process)  # SIGINT, then SIGTERM and SIGKILL
        if bridge.stderr is not None:  # left open when the wait for it was interrupted
            bridge.stderr.close()
    if bridge.returncode != 0:
        raise MazesimError(f"the bridge failed (exit {bridge.returncode}): {errors.strip()[-400:]}")
    stopped = re.search(r"stopped after (\d+) steps", errors)
    reached = re.search(r"goal reached at step (\d+)", errors)
    if stopped is None:
        raise MazesimError(f"expected the bridge's summary line; found {errors.strip()[-400:]}")
    return DemoResult(int(stopped.group(1)), int(reached.group(1)) if reached else None, bag)
