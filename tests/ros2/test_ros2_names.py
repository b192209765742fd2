"""ROS 2 names have a bound (255 characters, rmw's): a node, a namespace or a topic longer is
refused with the package's error before Cyclone DDS sees it (a 100,000-character namespace
crashed Cyclone DDS in a DataWriter; a few hundred failed to encode the graph's message) (#35)."""

from __future__ import annotations

import pytest

from mazesim.errors import InvalidArgumentError
from ros2_support import needs_ros2

pytestmark = [needs_ros2]


def test_a_node_or_namespace_name_beyond_ros2_s_bound_is_refused_before_dds() -> None:
    from mazesim.ros2.node import MOST_NAME_CHARACTERS, Node, _checked_name

    with pytest.raises(InvalidArgumentError, match="node name of at most 255 characters"):
        Node("n" * 300)
    with pytest.raises(InvalidArgumentError, match="found one of 100001"):
        Node("ok", namespace="/" + "a" * 100_000)
    assert _checked_name("topic", "t" * MOST_NAME_CHARACTERS) == "t" * MOST_NAME_CHARACTERS
    with pytest.raises(InvalidArgumentError, match="topic name of at most 255"):
        _checked_name("topic", "t" * (MOST_NAME_CHARACTERS + 1))


def test_the_bridge_refuses_a_namespace_its_topics_would_take_beyond_the_bound() -> None:
    from mazesim.ros2.bridge import MOST_NAMESPACE_CHARACTERS, BridgeSettings

    BridgeSettings(namespace="/" + "a" * (MOST_NAMESPACE_CHARACTERS - 1)).validate()
    with pytest.raises(InvalidArgumentError, match="at most 191 characters"):
        BridgeSettings(namespace="a" * 100_000).validate()
