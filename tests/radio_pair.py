"""Two e-pucks sharing one Webots radio, for the Emitter and Receiver tests: the second 0.3 m
east of the first, at a heading of the test's choosing, stepped as a world's owner steps them."""

from __future__ import annotations

import mazesim
from mazesim._core import Simulator
from mazesim.webots.radio import Radio
from mazesim.webots.radio_devices import Receiver
from mazesim.webots.simulation import RobotSimulation


class RadioPair:
    """Robot 0 at the arena's start, robot 1 0.3 m east of it turned to ``heading`` (rad)."""

    def __init__(self, heading: float = 0.0) -> None:
        world = mazesim.World.builtin("arena")
        self.radio = Radio()
        self.robots: list[RobotSimulation] = []
        for index in range(2):
            simulator = Simulator(world, seed=index)
            x, y, _ = simulator.pose
            simulator.set_pose(x + 0.3 * index, y, heading * index)
            self.robots.append(
                RobotSimulation(world, simulator=simulator, radio=self.radio, robot_index=index)
            )
        self.receivers: list[Receiver] = []

    def step(self) -> None:
        """Carries what was sent, advances both robots one step and fills the receivers."""
        self.radio.transmit({r.robot_index: r.simulator.pose for r in self.robots})
        for robot in self.robots:
            robot.advance(0.0, 0.0)
        for receiver in self.receivers:
            receiver._after_step()
