"""A ROS node for the ROS tests: drives or listens to a bridge and prints what it saw as JSON.

rospy allows one node per process, so the tests run this script in a subprocess (with the master's
environment) and read its standard output.

    ros_probe.py drive COMMANDS_JSON   publish each command, wait for the state it produces
    ros_probe.py listen SECONDS        record what the bridge publishes for SECONDS (wall clock)
    ros_probe.py count TOPIC N         receive N messages of TOPIC (e.g. from rosbag play)

A drive command is ``{"topic": "motor" | "action", "data": ..., "steps": 0 | 1}``: ``steps`` is
how many control steps it must cause (0 for a message the bridge must reject).
"""

from __future__ import annotations

import json
import sys
import threading
import time
import warnings
from typing import Any

import rospy
from rosgraph_msgs.msg import Clock
from std_msgs.msg import Float64MultiArray, String

TIMEOUT_S = 20.0
STATE_TOPICS = ("pose", "sensors", "sensor_data")


class Recorder:
    """Keeps every message of some Float64MultiArray topics (and when it came), and /clock."""

    def __init__(self, topics: tuple[str, ...]) -> None:
        self.lock = threading.Condition()
        self.data: dict[str, list[list[float]]] = {topic: [] for topic in topics}
        self.wall: dict[str, list[float]] = {topic: [] for topic in topics}
        self.labels: dict[str, str] = {}
        self.clock: list[float] = []
        for topic in topics:
            rospy.Subscriber(
                topic, Float64MultiArray, self.on_array, callback_args=topic, tcp_nodelay=True
            )
        rospy.Subscriber("/clock", Clock, self.on_clock, tcp_nodelay=True)

    def on_array(self, message: Float64MultiArray, topic: str) -> None:
        with self.lock:
            self.data[topic].append(list(message.data))
            self.wall[topic].append(time.monotonic())
            if message.layout.dim:
                self.labels[topic] = message.layout.dim[0].label
            self.lock.notify_all()

    def on_clock(self, message: Clock) -> None:
        with self.lock:
            self.clock.append(message.clock.to_sec())

    def wait_for(self, counts: dict[str, int], timeout: float = TIMEOUT_S) -> None:
        with self.lock:
            done = self.lock.wait_for(
                lambda: all(len(self.data[topic]) >= n for topic, n in counts.items()), timeout
            )
        if not done:
            have = {topic: len(self.data[topic]) for topic in counts}
            raise SystemExit(f"timed out waiting for {counts}; have {have}")

    def result(self) -> dict[str, Any]:
        with self.lock:
            return {
                "data": self.data,
                "wall": self.wall,
                "labels": self.labels,
                "clock": self.clock,
            }


def publisher(topic: str, message_class: Any) -> Any:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SyntaxWarning)
        return rospy.Publisher(topic, message_class, queue_size=None)


def wait_for_connection(pub: Any) -> None:
    deadline = time.monotonic() + TIMEOUT_S
    while pub.get_num_connections() == 0:
        if time.monotonic() > deadline:
            raise SystemExit(f"no subscriber connected to {pub.resolved_name}")
        time.sleep(0.01)


def drive(commands: list[dict[str, Any]]) -> dict[str, Any]:
    motor = publisher("motor", Float64MultiArray)
    action = publisher("action", String)
    wait_for_connection(motor)
    wait_for_connection(action)
    # The bridge advertises its topics before it subscribes motor: the list is complete now.
    has_sensor_data = any(name == "/sensor_data" for name, _ in rospy.get_published_topics())
    topics = STATE_TOPICS if has_sensor_data else STATE_TOPICS[:2]
    recorder = Recorder(topics)
    expected = 1  # the latched state before the first command
    recorder.wait_for(dict.fromkeys(topics, expected))
    for command in commands:
        if command["topic"] == "motor":
            motor.publish(Float64MultiArray(data=command["data"]))
        else:
            action.publish(String(data=command["data"]))
        expected += command["steps"]
        recorder.wait_for(dict.fromkeys(topics, expected))
    time.sleep(0.3)  # a step caused by a message that should have been rejected would show now
    return recorder.result()


def main() -> int:
    mode = sys.argv[1]
    rospy.init_node("ros_probe", anonymous=True, disable_signals=True)
    try:
        if mode == "drive":
            with open(sys.argv[2]) as handle:
                result = drive(json.load(handle))
        elif mode == "listen":
            recorder = Recorder(STATE_TOPICS)
            time.sleep(float(sys.argv[2]))
            result = recorder.result()
        elif mode == "count":
            topic, count = sys.argv[2], int(sys.argv[3])
            recorder = Recorder((topic,))
            recorder.wait_for({topic: count})
            time.sleep(0.3)  # more than expected would show now
            result = recorder.result()
        else:
            raise SystemExit(f"unknown mode {mode!r}")
    finally:
        rospy.signal_shutdown("probe done")
    json.dump(result, sys.stdout)
    return 0


if __name__ == "__main__":
    sys.exit(main())
