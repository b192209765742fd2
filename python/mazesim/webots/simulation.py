"""The simulation behind mazesim's Webots ``controller`` module.

A :class:`RobotSimulation` is one e-puck in one world, stepped one basic time step at a time,
with an optional time limit after which ``Robot.step`` returns -1, and the trajectory of the run.
:func:`prepare` makes the simulation that the next ``controller.Robot()`` attaches to; the
``mazesim webots run`` command prepares one before it runs a controller file.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from contextlib import contextmanager

import numpy as np
import numpy.typing as npt

from mazesim._core import Simulator, World
from mazesim.errors import InvalidArgumentError

__all__ = ["RobotSimulation", "StepObserver", "current", "observing_steps", "prepare", "release"]

#: Displacement per step (metres) below which the robot counts as stopped.
STOP_DISPLACEMENT = 1e-4


class RobotSimulation:
    """One e-puck in one world, driven by a Webots-style controller.

    Attributes:
        world: The world.
        simulator: The simulator, stepped one basic time step at a time.
        basic_time_step_ms: The world's basic time step in milliseconds.
        step_limit: The number of basic steps after which the run ends, or None for no limit.
        steps: Basic steps taken so far.
        ended: Whether ``Robot.step`` has returned -1.
        xs: The robot's x after each step (the start first).
        ys: The robot's y after each step (the start first).
        longest_stop_steps: The longest run of consecutive steps in which the robot moved less
            than :data:`STOP_DISPLACEMENT`.
    """

    def __init__(
        self, world: World, *, seconds: float | None = None, seed: int = 0, noise: bool = True
    ) -> None:
        """Creates the simulator of the run.

        Args:
            world: The world to run in.
            seconds: Simulated seconds after which ``Robot.step`` returns -1; None runs forever.
            seed: Seed of the sensor noise.
            noise: Whether the sensors are noisy, as in Webots.

        Raises:
            InvalidArgumentError: ``seconds`` is not a positive number.
        """
        if seconds is not None and not (math.isfinite(seconds) and seconds > 0.0):
            raise InvalidArgumentError(f"expected a positive number of seconds, found {seconds!r}")
        self.world = world
        self.simulator = Simulator(world, robot="e-puck", seed=seed, noise=noise)
        self.basic_time_step_ms = float(self.simulator.control_step_ms)
        self.step_limit = (
            None
            if seconds is None
            else max(1, math.ceil(seconds * 1000.0 / self.basic_time_step_ms - 1e-9))
        )
        self.steps = 0
        self.ended = False
        x, y, _ = self.simulator.pose
        self.xs: list[float] = [x]
        self.ys: list[float] = [y]
        self.longest_stop_steps = 0
        self._stop_steps = 0
        self._distance: npt.NDArray[np.float32] | None = None
        self._ground: npt.NDArray[np.float32] | None = None

    @property
    def time_is_up(self) -> bool:
        """Whether the time limit has been reached."""
        return self.step_limit is not None and self.steps >= self.step_limit

    def advance(self, left: float, right: float) -> None:
        """Runs one basic time step with these wheel speeds (rad/s), after showing the
        observers (:func:`observing_steps`) the state before it."""
        for observer in _observers:
            observer(self, left, right)
        self.simulator.step(left, right)
        self.steps += 1
        self._distance = None
        self._ground = None
        x, y, _ = self.simulator.pose
        moved = math.hypot(x - self.xs[-1], y - self.ys[-1])
        self.xs.append(x)
        self.ys.append(y)
        self._stop_steps = self._stop_steps + 1 if moved < STOP_DISPLACEMENT else 0
        self.longest_stop_steps = max(self.longest_stop_steps, self._stop_steps)

    def distance_readings(self) -> npt.NDArray[np.float32]:
        """The proximity readings ps0..ps7 after the last step."""
        if self._distance is None:
            self._distance = self.simulator.distance_sensors()
        return self._distance

    def ground_readings(self) -> npt.NDArray[np.float32]:
        """The ground readings gs0..gs2 after the last step."""
        if self._ground is None:
            self._ground = self.simulator.ground_sensors()
        return self._ground


_current: RobotSimulation | None = None

#: Called before every step of every simulation with the wheel speeds of the step.
StepObserver = Callable[[RobotSimulation, float, float], None]
_observers: list[StepObserver] = []


@contextmanager
def observing_steps(observer: StepObserver) -> Iterator[None]:
    """Calls ``observer(simulation, left, right)`` before every step taken inside the block (to
    record a run or show it live)."""
    _observers.append(observer)
    try:
        yield
    finally:
        _observers.remove(observer)


def prepare(
    world: World, *, seconds: float | None = None, seed: int = 0, noise: bool = True
) -> RobotSimulation:
    """Makes the simulation that the next ``controller.Robot()`` drives.

    Args:
        world: The world to run in.
        seconds: Simulated seconds after which ``Robot.step`` returns -1; None runs forever.
        seed: Seed of the sensor noise.
        noise: Whether the sensors are noisy.

    Returns:
        The new simulation (it replaces any earlier one).
    """
    global _current
    _current = RobotSimulation(world, seconds=seconds, seed=seed, noise=noise)
    return _current


def current() -> RobotSimulation:
    """The prepared simulation.

    Raises:
        InvalidArgumentError: No simulation was prepared.
    """
    if _current is None:
        raise InvalidArgumentError(
            "no simulation to attach the controller to: run it with "
            "'mazesim webots run CONTROLLER.py', or call "
            "mazesim.webots.prepare(world) before creating the Robot"
        )
    return _current


def release() -> None:
    """Forgets the prepared simulation."""
    global _current
    _current = None
