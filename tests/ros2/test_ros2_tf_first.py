"""Each step's ``/tf`` goes out first, then the robot's motion (``/odom``, ``/joint_states``,
``/imu``, ``/pose``), then the sensor messages of that step, ``/clock`` last: a node that looks up
``odom`` -> ``base_link`` at a ``/scan``'s stamp in its callback (tf2's ``lookup_transform``, the
listener filling its buffer on a thread of its own) has the transform already, and a node that
answers each ``/scan`` with the latest ``/odom`` (skipping scans until one has come, as Bug
planners do) has that step's, the reset state's included."""

from __future__ import annotations

from pathlib import Path

import pytest

from ros2_support import MAZESIM, needs_namespace, needs_ros2, run_in_namespace

STEPS = 5
MOTION = ("/odom", "/joint_states", "/imu", "/pose")
SENSORS = ("/ps0", "/ps7", "/gs0", "/scan", "/sensors")


@needs_ros2
@needs_namespace
def test_each_step_sends_tf_then_the_motion_then_the_sensors_and_clock_last(
    tmp_path: Path,
) -> None:
    make_reader = pytest.importorskip("mcap.reader").make_reader
    bag = tmp_path / "bag"
    bridge = [*MAZESIM, "ros2", "bridge", "--mode", "free", "--speed", "0", "--bag", str(bag)]
    result = run_in_namespace([], [*bridge, "--stop-after", str(STEPS)])
    assert result.returncode == 0, result.stderr
    # The bag holds what went out, in the order it went out, each message at its step's stamp.
    order: dict[int, list[str]] = {}
    with next(bag.glob("*.mcap")).open("rb") as stream:
        for _, channel, message in make_reader(stream).iter_messages(log_time_order=False):
            if channel.topic not in ("/tf_static", "/map"):
                order.setdefault(message.log_time, []).append(channel.topic)
    assert len(order) == STEPS + 1, sorted(order)
    for stamp, topics in order.items():
        assert topics[0] == "/tf" and topics[-1] == "/clock", (stamp, topics)
        assert set(MOTION) | set(SENSORS) <= set(topics), (stamp, topics)
        last_motion = max(topics.index(topic) for topic in MOTION)
        first_sensor = min(topics.index(topic) for topic in SENSORS)
        assert last_motion < first_sensor, (stamp, topics)
