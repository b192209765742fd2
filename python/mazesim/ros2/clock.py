"""Simulation time as ROS 2 sees it, and the free-running mode's pace and controls.

Every stamp is simulation time in nanoseconds, never zero: ROS reads a time of zero as "no clock
yet" (a node with ``use_sim_time`` would not start its timers), so the state before the first
step, at simulated time 0, is stamped 1 ns.

Free-running, the bridge steps on its own: ``speed`` times faster than the wall clock, or as fast
as it can (speed 0), with the last commanded wheel speeds. ``/sim_control``
(``std_msgs/msg/String``) pauses and resumes it and steps it: ``pause``, ``run``, ``step N`` (N
steps, then paused), ``run_until SECONDS`` (runs, then pauses at that simulated time).
"""

from __future__ import annotations

import math
import time

from mazesim.errors import InvalidActionError, _shown
from mazesim.ros.lockstep import stamp_nanoseconds

__all__ = ["FreeRunning", "SIM_CONTROL_TOPIC", "stamp_nanoseconds"]

SIM_CONTROL_TOPIC = "/sim_control"


class FreeRunning:
    """When the free-running bridge takes its next step.

    Args:
        speed: Simulated seconds per wall-clock second; 0 for as fast as possible.
        control_step_s: The simulated length of a step.
        paused: Start paused (then ``run`` or ``step N`` on ``/sim_control`` starts it).
    """

    def __init__(self, speed: float, control_step_s: float, paused: bool = False) -> None:
        self.period = control_step_s / speed if speed > 0.0 else 0.0
        self.paused = paused
        self.steps_left: int | None = None
        self.until: float = math.inf
        self.next_step = time.monotonic()

    def control(self, text: str) -> None:
        """Applies a ``/sim_control`` command.

        Raises:
            InvalidActionError: Not ``pause``, ``run``, ``step N`` or ``run_until SECONDS``.
        """
        words = text.split()
        try:
            if words == ["pause"]:
                self.paused = True
            elif words == ["run"]:
                self.paused, self.steps_left, self.until = False, None, math.inf
            elif len(words) == 2 and words[0] == "step" and int(words[1]) >= 1:
                self.paused, self.steps_left = False, int(words[1])
            elif len(words) == 2 and words[0] == "run_until" and math.isfinite(float(words[1])):
                self.paused, self.steps_left, self.until = False, None, float(words[1])
            else:
                raise ValueError(text)
        except ValueError as error:
            raise InvalidActionError(
                "expected pause, run, step N (N >= 1) or run_until SECONDS on /sim_control; "
                f"found {_shown(text)}"
            ) from error
        self.next_step = time.monotonic()

    def due(self, simulated: float, control_step_s: float) -> float | None:
        """Seconds to wait before the next step (0: now), or ``None`` while paused."""
        if self.paused:
            return None
        if simulated + control_step_s > self.until + 1e-9:
            self.paused = True
            return None
        return max(self.next_step - time.monotonic(), 0.0)

    def stepped(self) -> None:
        """Notes a step: the next is one period later; counts down ``step N``."""
        self.next_step = max(self.next_step + self.period, time.monotonic() - 10 * self.period)
        if self.steps_left is not None:
            self.steps_left -= 1
            if self.steps_left <= 0:
                self.paused, self.steps_left = True, None
