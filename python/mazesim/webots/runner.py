"""Running an unmodified Webots controller file headless on mazesim.

:func:`run_controller` prepares a simulation, installs :mod:`mazesim.webots.controller` as the
module ``controller`` and executes the file as Webots does (as ``__main__``, from its own folder,
with that folder on ``sys.path``) until the controller returns or ``Robot.step`` reports the end.
"""

from __future__ import annotations

import os
import sys
import time
from dataclasses import dataclass, field
from types import ModuleType

from mazesim._core import World
from mazesim.errors import MazesimIOError
from mazesim.webots import controller as controller_module
from mazesim.webots import simulation as simulations

__all__ = ["ControllerRun", "run_controller"]


@dataclass
class ControllerRun:
    """What a controller run did.

    Attributes:
        world: The world it ran in.
        controller: The controller file.
        simulated_seconds: Simulated time at the end.
        steps: Basic time steps simulated.
        distance_m: Distance the robot travelled.
        collisions: Contacts with walls that began during the run.
        longest_stop_s: Longest time the robot stood still (moved under 0.1 mm per step).
        reached_end: Whether ``Robot.step`` returned -1 (the time was up) before the controller
            ended.
        wall_clock_seconds: Real time the run took.
        xs: The robot's x after each step, the start first.
        ys: The robot's y after each step, the start first.
    """

    world: World
    controller: str
    simulated_seconds: float
    steps: int
    distance_m: float
    collisions: int
    longest_stop_s: float
    reached_end: bool
    wall_clock_seconds: float
    xs: list[float] = field(repr=False)
    ys: list[float] = field(repr=False)


def _read_source(path: str) -> str:
    try:
        with open(path, encoding="utf-8") as handle:
            return handle.read()
    except OSError as error:
        failure = MazesimIOError(f"{path}: cannot read the controller: {error.strerror or error}")
        failure.filename = path
        raise failure from None


def run_controller(
    path: str | os.PathLike[str],
    world: World,
    *,
    seconds: float = 60.0,
    seed: int = 0,
    noise: bool = True,
) -> ControllerRun:
    """Runs a Webots-style controller file on the e-puck in ``world``.

    Args:
        path: The controller's Python file (``from controller import Robot`` and the usual loop).
        world: The world to run in.
        seconds: Simulated seconds after which ``Robot.step`` returns -1.
        seed: Seed of the sensor noise.
        noise: Whether the sensors are noisy.

    Returns:
        What the run did.

    Raises:
        MazesimIOError: The file cannot be read.
        InvalidArgumentError: ``seconds`` is not positive.
        Exception: Whatever the controller raises (its own errors are its traceback).
    """
    file = os.path.abspath(os.fspath(path))
    source = _read_source(file)
    code = compile(source, file, "exec")
    simulation = simulations.prepare(world, seconds=seconds, seed=seed, noise=noise)
    controller_module.Robot.created = None
    folder = os.path.dirname(file)
    saved_module: ModuleType | None = sys.modules.get("controller")
    saved_argv, saved_path, saved_cwd = sys.argv, list(sys.path), os.getcwd()
    sys.modules["controller"] = controller_module
    sys.argv = [file]
    sys.path.insert(0, folder)
    started = time.perf_counter()
    try:
        os.chdir(folder)
        exec(code, {"__name__": "__main__", "__file__": file, "__builtins__": __builtins__})
    except controller_module.ControllerStopped:
        pass
    except SystemExit as request:
        if request.code not in (None, 0):
            raise
    finally:
        os.chdir(saved_cwd)
        sys.path[:] = saved_path
        sys.argv = saved_argv
        if saved_module is None:
            sys.modules.pop("controller", None)
        else:
            sys.modules["controller"] = saved_module
        controller_module.Robot.created = None
        simulations.release()
    simulator = simulation.simulator
    return ControllerRun(
        world=world,
        controller=file,
        simulated_seconds=float(simulator.time),
        steps=simulation.steps,
        distance_m=float(simulator.distance_travelled),
        collisions=int(simulator.collisions),
        longest_stop_s=simulation.longest_stop_steps * simulation.basic_time_step_ms / 1000.0,
        reached_end=simulation.ended,
        wall_clock_seconds=time.perf_counter() - started,
        xs=simulation.xs,
        ys=simulation.ys,
    )
