"""The reset services of both bridges, as a simulator's users call them over ROS.

Nodes written for Gazebo call ``std_srvs/Empty`` services to start an episode again: under ROS 1
``/gazebo/reset_simulation`` and ``/gazebo/reset_world`` (the ``gazebo`` node of
``gazebo_ros``), under ROS 2 ``/reset_simulation`` and ``/reset_world`` (``gazebo_ros_init``
in ros-simulation/gazebo_ros_pkgs). Each bridge offers both, with Gazebo's meaning:

- ``reset_simulation``: everything as at the bridge's start, time included (the simulator's
  snapshot taken then, noise stream and counters with it); the run that follows is, step for
  step and bit for bit, the run of a bridge just started with the same commands.
- ``reset_world``: every robot back at its start, at rest, its noise stream started again from
  its seed; time and counters go on (:meth:`mazesim.Simulator.reset_scene`).
- ``reset_positions``: Stage's name for the same (``stage_ros`` offers ``reset_positions``,
  ``std_srvs/Empty``, putting every robot back at its start pose while time goes on; nodes
  written for Stage, and gym environments over it, call ``/reset_positions``).

Either way the robots hold no command afterwards (their wheels at rest until the next one), and
in lockstep the bridge publishes the state after the reset before it answers the call, so the
caller's next command answers that state. Nothing here needs ROS.
"""

from __future__ import annotations

from mazesim._core import Simulator
from mazesim.errors import InvalidArgumentError, _shown

__all__ = [
    "RESET_POSITIONS",
    "RESET_SIMULATION",
    "RESET_WORLD",
    "RESETS",
    "EpisodeResets",
    "service_name",
]

RESET_SIMULATION = "reset_simulation"
RESET_WORLD = "reset_world"
RESET_POSITIONS = "reset_positions"
#: The resets both bridges offer, each with what it does, as the docs say it.
RESETS = {
    RESET_SIMULATION: "everything as at the start, time included",
    RESET_WORLD: "every robot at its start, time going on",
    RESET_POSITIONS: "every robot at its start, time going on (Stage's reset_world)",
}


def service_name(kind: str, ros1: bool) -> str:
    """The service a bridge offers for a reset, as the simulator that has it names it: Gazebo's
    ROS 1 node puts its own under ``/gazebo`` (``/gazebo/reset_world``), ``gazebo_ros`` under
    ROS 2 at the root (``/reset_world``), and ``stage_ros`` at the root in both
    (``/reset_positions``)."""
    if ros1 and kind != RESET_POSITIONS:
        return f"/gazebo/{kind}"
    return f"/{kind}"


class EpisodeResets:
    """Puts one simulator back as a reset service asks.

    Args:
        simulator: The simulator, in the state it starts from (its snapshot is taken now).
    """

    def __init__(self, simulator: Simulator) -> None:
        self.simulator = simulator
        self._start = simulator.snapshot()
        #: How many resets of each kind were applied.
        self.applied = dict.fromkeys(RESETS, 0)

    def apply(self, kind: str) -> None:
        """Applies the reset ``kind`` (:data:`RESET_SIMULATION`, :data:`RESET_WORLD` or
        :data:`RESET_POSITIONS`).

        Raises:
            InvalidArgumentError: Another kind.
        """
        if kind == RESET_SIMULATION:
            self.simulator.restore(self._start)
        elif kind in (RESET_WORLD, RESET_POSITIONS):
            self.simulator.reset_scene()
        else:
            raise InvalidArgumentError(
                f"expected a reset, one of {', '.join(RESETS)}; found {_shown(kind)}"
            )
        self.applied[kind] += 1
