"""A node waiting for a topic of Webots' e-puck driver that the bridge does not publish hears why:
``/tof`` from the e-puck (Webots' ``webots_ros2_epuck`` world simulates an e-puck2), the light
sensors, the inertial unit, the camera; and the bridge names a reader or writer whose QoS DDS
cannot match with its own (``mazesim.ros2.qos.IncompatibleQos``)."""

from __future__ import annotations

import sys

import pytest

from mazesim.ros2.unpublished import why_unpublished
from ros2_support import MAZESIM, needs_namespace, needs_ros2, run_in_namespace

PUBLISHED = ["/ps0", "/scan", "/odom", "/clock"]


@pytest.mark.parametrize(
    "topic, words",
    [
        ("/tof", "e-puck2"),
        ("/west/tof", "e-puck2"),
        ("/ls3", "light sensors"),
        ("/imu", "inertial unit"),
        ("/camera/image_raw", "camera"),
        ("/camera_info", "camera"),
    ],
)
def test_a_topic_of_webots_e_puck_driver_the_bridge_lacks_is_explained(
    topic: str, words: str
) -> None:
    reason = why_unpublished(topic, PUBLISHED, "e-puck")
    assert reason is not None and words in reason


@pytest.mark.parametrize("topic", ["/ps0", "/map", "/cmd_vel", "/tofu", "/ls8"])
def test_other_topics_are_left_alone(topic: str) -> None:
    assert why_unpublished(topic, PUBLISHED, "e-puck") is None


def test_a_published_tof_is_left_alone() -> None:
    assert why_unpublished("/tof", [*PUBLISHED, "/tof"], "e-puck2") is None


USER_NODE = (
    "import time\n"
    "from mazesim.ros2.node import Node\n"
    "from mazesim.ros2.qos import SENSOR, TopicQos\n"
    "node = Node('user_node')\n"
    "node.reader('/tof', 'sensor_msgs/msg/Range', SENSOR)\n"
    "node.reader('/odom', 'nav_msgs/msg/Odometry', TopicQos(True, True, 1))\n"
    "node.writer('/cmd_vel', 'geometry_msgs/msg/Twist', TopicQos(False, False, 10))\n"
    "time.sleep(4)\n"
)


@needs_ros2
@needs_namespace
def test_the_bridge_says_once_why_a_node_gets_nothing_or_sends_in_vain() -> None:
    # A node of a random walk waiting for /tof from the e-puck, which reads /odom transient
    # local and writes /cmd_vel best effort: DDS matches neither with the bridge's endpoints.
    result = run_in_namespace(
        [[*MAZESIM, "ros2", "bridge", "--mode", "free", "--stop-after", "150"]],
        [sys.executable, "-c", USER_NODE],
        timeout=60,
    )
    assert result.returncode == 0, result.stderr
    message = "a node reads /tof, which this bridge does not publish: the e-puck has no"
    assert result.stderr.count(message) == 1, result.stderr
    assert "--robot e-puck2" in result.stderr
    assert result.stderr.count("a node reads /odom asking for a durability") == 1
    assert result.stderr.count("a node writes /cmd_vel offering less reliability") == 1
