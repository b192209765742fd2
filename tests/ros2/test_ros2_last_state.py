"""A lockstep bridge stopped by ``--stop-after``: its last state reaches a reliable reader that
reads until the bridge says it stopped, every topic of it, ``/clock`` included (a reader that
counted a fixed second after its last answer missed the last messages on a loaded machine)."""

from __future__ import annotations

import sys

from ros2_support import (
    AWAIT_BACKGROUND,
    MAZESIM,
    needs_namespace,
    needs_ros2,
    run_in_namespace,
)

STEPS = 100

# A node reading every state topic as `ros2 bag record -a` does (reliable, a deep queue) that
# answers each /odom; it takes what is left once the bridge has said it stopped.
RECORDER = f"""
import time
from mazesim.ros2.node import Node
from mazesim.ros2.qos import COMMAND, TopicQos
from mazesim.ros2 import cdr
node = Node('recorder')
types = {{'/odom': 'nav_msgs/msg/Odometry', '/clock': 'rosgraph_msgs/msg/Clock',
         '/pose': 'std_msgs/msg/Float64MultiArray', '/sensors': 'std_msgs/msg/Float64MultiArray',
         '/scan': 'sensor_msgs/msg/LaserScan', '/tf': 'tf2_msgs/msg/TFMessage',
         '/imu': 'sensor_msgs/msg/Imu', '/joint_states': 'sensor_msgs/msg/JointState',
         '/ps0': 'sensor_msgs/msg/Range', '/ps7': 'sensor_msgs/msg/Range'}}
deep = TopicQos(True, False, 1000)
readers = {{topic: node.reader(topic, kind, deep) for topic, kind in types.items()}}
motor = node.writer('/motor', 'std_msgs/msg/Float64MultiArray', COMMAND)
counts = dict.fromkeys(readers, 0)
answered = 0
ceiling = time.monotonic() + 300
while answered < {STEPS}:
    assert time.monotonic() < ceiling, counts
    for topic, reader in readers.items():
        got = reader.take(1000)
        counts[topic] += len(got)
        if topic == '/odom':
            for _ in got:
                motor.publish(cdr.encode_float64_multi_array([], [2.0, 3.0]))
                answered += 1
    time.sleep(0.001)
{AWAIT_BACKGROUND}
await_background(0, 'stopped after {STEPS} steps')
for topic, reader in readers.items():
    counts[topic] += len(reader.take(1000))
short = {{topic: count for topic, count in counts.items() if count != {STEPS + 1}}}
assert not short, short
print('every topic', {STEPS + 1})
"""


@needs_ros2
@needs_namespace
def test_the_last_state_reaches_a_reader_that_reads_until_the_bridge_stopped() -> None:
    bridge = [*MAZESIM, "ros2", "bridge", "--stop-after", str(STEPS)]
    result = run_in_namespace([bridge], [sys.executable, "-c", RECORDER])
    assert result.returncode == 0, result.stderr
    assert f"every topic {STEPS + 1}" in result.stdout
