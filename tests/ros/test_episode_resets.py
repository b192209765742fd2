"""The resets both ROS bridges offer (``mazesim.ros.resets``), without ROS."""

from __future__ import annotations

import pytest

import mazesim
from mazesim.errors import InvalidArgumentError
from mazesim.ros.resets import (
    RESET_POSITIONS,
    RESET_SIMULATION,
    RESET_WORLD,
    EpisodeResets,
    service_name,
)

SPEEDS = [(6.0, 2.5), (-3.0, 4.0), (5.5, 5.5), (1.0, -6.0)] * 5


def drive(simulator: mazesim.Simulator) -> list[tuple[tuple[float, float, float], float]]:
    out = []
    for left, right in SPEEDS:
        simulator.step(left, right)
        out.append((simulator.pose, float(simulator.distance_sensors()[0])))
    return out


def test_reset_simulation_gives_the_run_of_a_fresh_simulator_bit_for_bit() -> None:
    simulator = mazesim.Simulator(mazesim.load_world("seed-maze"), robot="e-puck", seed=4)
    resets = EpisodeResets(simulator)
    first = drive(simulator)
    resets.apply(RESET_SIMULATION)
    assert simulator.time == 0.0 and simulator.steps == 0
    assert drive(simulator) == first
    assert resets.applied == {RESET_SIMULATION: 1, RESET_WORLD: 0, RESET_POSITIONS: 0}


@pytest.mark.parametrize("kind", [RESET_WORLD, RESET_POSITIONS])
def test_reset_world_puts_the_robot_at_its_start_while_time_goes_on(kind: str) -> None:
    # reset_positions is Stage's name for it (stage_ros): every robot at its start pose.
    simulator = mazesim.Simulator(mazesim.load_world("seed-maze"), robot="e-puck", seed=4)
    start = simulator.pose
    resets = EpisodeResets(simulator)
    drive(simulator)
    assert simulator.pose != start
    resets.apply(kind)
    assert simulator.pose == start
    assert simulator.steps == len(SPEEDS)
    assert simulator.time == pytest.approx(len(SPEEDS) * 0.032)


def test_another_reset_is_refused_naming_the_two() -> None:
    simulator = mazesim.Simulator(mazesim.load_world("seed-maze"), robot="e-puck", seed=4)
    with pytest.raises(InvalidArgumentError, match="reset_simulation, reset_world"):
        EpisodeResets(simulator).apply("reset")


def test_each_reset_is_offered_where_its_simulator_offers_it() -> None:
    # Gazebo's ROS 1 node under /gazebo, gazebo_ros under ROS 2 at the root, stage_ros at the
    # root in both, as the nodes written for each call them.
    assert service_name(RESET_WORLD, ros1=True) == "/gazebo/reset_world"
    assert service_name(RESET_SIMULATION, ros1=False) == "/reset_simulation"
    assert service_name(RESET_POSITIONS, ros1=True) == "/reset_positions"
    assert service_name(RESET_POSITIONS, ros1=False) == "/reset_positions"
