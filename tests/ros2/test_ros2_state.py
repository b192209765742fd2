"""The state topics' messages in process: ``/imu``'s noise, as Webots' E-puck tables give it."""

from __future__ import annotations

import statistics
from typing import Any

import mazesim
from mazesim.ros2 import cdr
from mazesim.ros2.state import GRAVITY, IMU_NOISE, StateTopics
from ros2_support import needs_ros2

pytestmark = [needs_ros2]


def _imu_run(imu_seed: int | None, steps: int = 200) -> list[Any]:
    """The ``/imu`` messages of ``steps`` steps turning in place, decoded."""
    from rosbags.typesys import Stores, get_typestore

    store = get_typestore(Stores.ROS2_HUMBLE)
    simulator = mazesim.Simulator(mazesim.load_world("arena"), robot="e-puck", seed=3)
    state = StateTopics(simulator, "humble", imu_seed=imu_seed)
    index = [topic.name for topic in state.topics].index("/imu")
    found = []
    for _ in range(steps):
        simulator.step(-2.0, 2.0)
        stamp = cdr.stamp_of(round(simulator.time * 1e9))
        data = state.messages(stamp, simulator.control_step_ms / 1000.0)[index]
        found.append(store.deserialize_cdr(data, "sensor_msgs/msg/Imu"))
    return found


def test_imu_noise_is_webots_share_of_each_value_and_replays_from_its_seed() -> None:
    # /imu was noise-free: a filter tuned on Webots' e-puck (whose accelerometer and gyro
    # tables add 0.3 % of the value) saw a perfect sensor, its gravity exactly 9.81.
    noisy = _imu_run(5)
    gravity = [m.linear_acceleration.z for m in noisy]
    spread = statistics.pstdev(gravity)
    assert 0.7 * IMU_NOISE * GRAVITY < spread < 1.3 * IMU_NOISE * GRAVITY
    assert abs(statistics.fmean(gravity) - GRAVITY) < 4 * spread / len(gravity) ** 0.5
    clean = _imu_run(None)
    assert {m.linear_acceleration.z for m in clean} == {GRAVITY}
    # The turn rate too, relative to itself; the orientation is the inertial unit's, noise-free.
    rates = [n.angular_velocity.z / c.angular_velocity.z - 1.0 for n, c in zip(noisy, clean)]
    assert 0.7 * IMU_NOISE < statistics.pstdev(rates) < 1.3 * IMU_NOISE
    assert [n.orientation.z for n in noisy] == [c.orientation.z for c in clean]
    # Same seed, same readings; another seed, others.
    again = _imu_run(5)
    assert [m.linear_acceleration.z for m in again] == gravity
    assert [m.linear_acceleration.z for m in _imu_run(6)] != gravity


def test_a_state_published_again_carries_the_same_imu_readings() -> None:
    # The reset state sent again before the first command (a node answering from its second
    # message) drew new noise, so it was not the state the in-process run has.
    simulator = mazesim.Simulator(mazesim.load_world("arena"), robot="e-puck", seed=1)
    state = StateTopics(simulator, "humble", imu_seed=1)
    index = [topic.name for topic in state.topics].index("/imu")
    first = state.messages(cdr.stamp_of(1), 0.0)[index]
    assert state.messages(cdr.stamp_of(1), 0.0)[index] == first
    simulator.step(1.0, 1.0)
    assert state.messages(cdr.stamp_of(32_000_000), 0.032)[index] != first
