"""A node waiting for a topic of Webots' e-puck driver that the bridge does not publish hears why:
``/tof`` from the e-puck (Webots' ``webots_ros2_epuck`` world simulates an e-puck2), the light
sensors, the inertial unit, the camera; and the bridge names a reader or writer whose QoS DDS
cannot match with its own (``mazesim.ros2.qos.IncompatibleQos``), or whose message type is not
the bridge's on that topic."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from mazesim.ros2.unpublished import (
    also_published,
    in_robot_namespaces,
    other_type,
    outside_a_namespace,
    why_unpublished,
)
from ros2_support import (
    AWAIT_BACKGROUND,
    MAZESIM,
    TWO_ROBOTS,
    needs_namespace,
    needs_ros2,
    run_in_namespace,
)

PUBLISHED = ["/ps0", "/scan", "/odom", "/clock"]


@pytest.mark.parametrize(
    "topic, words",
    [
        ("/tof", "e-puck2"),
        ("/west/tof", "e-puck2"),
        ("/ls3", "light sensors"),
        ("/camera/image_raw", "camera"),
        ("/camera_info", "camera"),
        # A Nav2-style node waiting for a map (transient local, as map_server and slam_toolbox
        # publish it) heard nothing, and nothing said why; the bridge's is on /map.
        ("/robot1/map", "in each robot's namespace"),
        ("/robot1/map", "slam_toolbox"),
    ],
)
def test_a_topic_of_webots_e_puck_driver_the_bridge_lacks_is_explained(
    topic: str, words: str
) -> None:
    reason = why_unpublished(topic, PUBLISHED, "e-puck")
    assert reason is not None and words in reason


@pytest.mark.parametrize("topic", ["/ps0", "/maps", "/cmd_vel", "/tofu", "/ls8", "/imu"])
def test_other_topics_are_left_alone(topic: str) -> None:
    assert why_unpublished(topic, PUBLISHED, "e-puck") is None


def test_a_published_tof_is_left_alone() -> None:
    assert why_unpublished("/tof", [*PUBLISHED, "/tof"], "e-puck2") is None


NAMESPACES = ["/west", "/east_1"]
PUBLISHED_BY_TWO = [f"{ns}/{name}" for ns in NAMESPACES for name in ("odom", "ps0", "tf")]


def test_a_topic_each_robot_has_in_its_namespace_is_explained_outside_them() -> None:
    reason = in_robot_namespaces("/odom", PUBLISHED_BY_TWO, NAMESPACES)
    assert reason is not None
    assert "(/west/odom, /east_1/odom)" in reason and "-r /odom:=/west/odom" in reason
    assert "__ns:=/west" in reason and "--frame-prefix" not in reason
    tf = in_robot_namespaces("/tf", PUBLISHED_BY_TWO, NAMESPACES)
    assert tf is not None and "--frame-prefix" in tf
    commands = in_robot_namespaces("/cmd_vel", ["/west/cmd_vel", "/east_1/cmd_vel"], NAMESPACES)
    assert commands is not None and "-r /cmd_vel:=/west/cmd_vel" in commands


@pytest.mark.parametrize("topic", ["/west/odom", "/map", "/west/map", "/clock"])
def test_topics_in_a_namespace_or_that_no_robot_has_are_left_alone(topic: str) -> None:
    published = [*PUBLISHED_BY_TWO, "/clock"]
    assert in_robot_namespaces(topic, published, NAMESPACES) is None
    # A world of one robot has no namespaces: nothing to say.
    assert in_robot_namespaces(topic, ["/odom", "/clock"], []) is None


def test_a_namespaced_topic_the_robot_has_in_no_namespace_is_explained() -> None:
    # A formation controller for e-pucks /epuck0 .. run with one robot reads /epuck0/odom.
    reason = outside_a_namespace("/epuck0/odom", PUBLISHED, [])
    assert reason is not None and "(/odom)" in reason
    assert "--namespace epuck0" in reason and "-r /epuck0/odom:=/odom" in reason
    deep = outside_a_namespace("/team/epuck0/cmd_vel", ["/cmd_vel"], [])
    assert deep is not None and "--namespace team/epuck0" in deep


@pytest.mark.parametrize("topic", ["/odom", "/epuck0/map", "/odometry", "/epuck0/odometry"])
def test_topics_the_bridge_has_or_no_robot_has_are_left_alone_outside_a_namespace(
    topic: str,
) -> None:
    assert outside_a_namespace(topic, PUBLISHED, []) is None
    # A world of several robots: in_robot_namespaces speaks instead.
    assert outside_a_namespace("/epuck0/odom", PUBLISHED, ["/west"]) is None


TYPES = {
    "/odom": ["nav_msgs/msg/Odometry"],
    "/cmd_vel": ["geometry_msgs/msg/Twist", "geometry_msgs/msg/TwistStamped"],
}


def test_a_node_with_another_type_on_a_topic_of_the_bridge_is_explained() -> None:
    reads = other_type("reads", "/odom", "geometry_msgs::msg::dds_::Twist_", TYPES)
    assert reads is not None and "as geometry_msgs/msg/Twist" in reads
    assert "nav_msgs/msg/Odometry only" in reads and "receives nothing" in reads
    writes = other_type("writes", "/cmd_vel", "std_msgs::msg::dds_::String_", TYPES)
    assert writes is not None and "nothing it sends arrives" in writes
    assert "geometry_msgs/msg/Twist or geometry_msgs/msg/TwistStamped only" in writes


@pytest.mark.parametrize(
    "topic, dds_type",
    [
        ("/cmd_vel", "geometry_msgs::msg::dds_::Twist_"),
        ("/cmd_vel", "geometry_msgs::msg::dds_::TwistStamped_"),
        ("/odom", "nav_msgs::msg::dds_::Odometry_"),
        ("/map", "nav_msgs::msg::dds_::OccupancyGrid_"),
        ("/odom", ""),
    ],
)
def test_the_bridge_s_own_types_and_other_topics_are_left_alone(topic: str, dds_type: str) -> None:
    assert other_type("writes", topic, dds_type, TYPES) is None


@pytest.mark.parametrize("topic", ["/clock", "/odom", "/ps0"])
def test_another_publisher_of_the_bridge_s_topics_is_explained(topic: str) -> None:
    reason = also_published(topic, PUBLISHED)
    assert reason is not None and f"another node publishes {topic}" in reason
    assert "ROS_DOMAIN_ID" in reason


@pytest.mark.parametrize("topic", ["/tf", "/tf_static", "/map", "/cmd_vel"])
def test_the_transforms_and_topics_the_bridge_does_not_publish_are_left_alone(topic: str) -> None:
    # Many nodes write /tf (a localiser's map -> odom, robot_state_publisher's /tf_static).
    assert also_published(topic, [*PUBLISHED, "/tf", "/tf_static"]) is None


@needs_ros2
@needs_namespace
def test_two_bridges_on_one_domain_each_say_so_once() -> None:
    # Two simulations on one domain: a node reading /odom got both robots' odometry, and its
    # commands stepped both, and nothing said why.
    # The two bridges run until each has said so (however late a loaded machine starts one).
    bridge = [*MAZESIM, "ros2", "bridge", "--mode", "free"]
    said = "as this bridge does: every node reading it receives both"
    both = AWAIT_BACKGROUND + f"await_background(0, {said!r})\nawait_background(1, {said!r})\n"
    result = run_in_namespace(
        [bridge, [*bridge, "--world", "arena"]], [sys.executable, "-c", both], grace=1.0
    )
    assert result.returncode == 0, result.stderr
    assert result.stderr.count("as this bridge does: every node reading it receives both") == 2
    assert "give each simulation its own ROS_DOMAIN_ID" in result.stderr


USER_NODE = (
    "from mazesim.ros2.node import Node\n"
    "from mazesim.ros2.qos import SENSOR, TopicQos\n"
    "node = Node('user_node')\n"
    "node.reader('/tof', 'sensor_msgs/msg/Range', SENSOR)\n"
    "node.reader('/odom', 'nav_msgs/msg/Odometry', TopicQos(True, True, 1))\n"
    "node.writer('/cmd_vel', 'geometry_msgs/msg/Twist', TopicQos(False, False, 10))\n"
    "node.reader('/pose', 'geometry_msgs/msg/Twist', SENSOR)\n"
    "node.writer('/motor', 'std_msgs/msg/String', TopicQos(True, False, 10))\n"
    + AWAIT_BACKGROUND
    + "await_background(0, 'a node reads /tof', 'a node reads /odom', 'a node writes /cmd_vel',"
    " 'a node reads /pose', 'a node writes /motor')\n"
)


@needs_ros2
@needs_namespace
def test_the_bridge_says_once_why_a_node_gets_nothing_or_sends_in_vain() -> None:
    # A node of a random walk waiting for /tof from the e-puck, which reads /odom transient
    # local and writes /cmd_vel best effort: DDS matches neither with the bridge's endpoints.
    result = run_in_namespace(
        [[*MAZESIM, "ros2", "bridge", "--mode", "free"]],
        [sys.executable, "-c", USER_NODE],
        grace=1.0,
    )
    assert result.returncode == 0, result.stderr
    message = "a node reads /tof, which this bridge does not publish: the e-puck has no"
    assert result.stderr.count(message) == 1, result.stderr
    assert "--robot e-puck2" in result.stderr
    assert result.stderr.count("a node reads /odom asking for a durability") == 1
    assert result.stderr.count("a node writes /cmd_vel offering less reliability") == 1
    # And it reads /pose, writes /motor as types the bridge does not have there: Cyclone DDS
    # reports that as an incompatible QoS (policy 24), once passed on as "offering less policy
    # 24"; the bridge names the types.
    reads = "a node reads /pose as geometry_msgs/msg/Twist; the bridge has it as std_msgs/msg/"
    assert result.stderr.count(reads) == 1, result.stderr
    writes = "a node writes /motor as std_msgs/msg/String; the bridge has it as std_msgs/msg/Float"
    assert result.stderr.count(writes) == 1, result.stderr
    assert "policy" not in result.stderr


#: Webots' drive calibrator (webots_ros2_epuck/drive_calibrator.py in cyberbotics/webots_ros2)
#: reads /odom (depth 1) and writes /cmd_vel (depth 10), absolute names that -r __ns:=/west
#: leaves as they are.
CALIBRATOR = (
    "from mazesim.ros2.node import Node\n"
    "from mazesim.ros2.qos import COMMAND, SENSOR\n"
    "node = Node('drive_calibrator')\n"
    "node.reader('/odom', 'nav_msgs/msg/Odometry', SENSOR._replace(depth=1))\n"
    "node.writer('/cmd_vel', 'geometry_msgs/msg/Twist', COMMAND)\n"
    + AWAIT_BACKGROUND
    + "await_background(0, 'a node reads /odom', 'a node writes /cmd_vel')\n"
)


@needs_ros2
@needs_namespace
def test_the_bridge_says_where_each_robot_has_the_topic_a_node_names_absolutely(
    tmp_path: Path,
) -> None:
    world = tmp_path / "two.toml"
    world.write_text(TWO_ROBOTS)
    result = run_in_namespace(
        [
            [
                *MAZESIM,
                "ros2",
                "bridge",
                "--world",
                str(world),
                "--mode",
                "free",
            ]
        ],
        [sys.executable, "-c", CALIBRATOR],
        grace=1.0,
    )
    assert result.returncode == 0, result.stderr
    reads = "a node reads /odom, which this bridge does not publish: each robot of this world"
    assert result.stderr.count(reads) == 1, result.stderr
    writes = "a node writes /cmd_vel, which this bridge does not read: each robot of this world"
    assert result.stderr.count(writes) == 1, result.stderr
    assert "-r /cmd_vel:=/west/cmd_vel" in result.stderr
