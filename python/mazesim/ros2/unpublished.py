"""Topics a node reads that the bridge does not publish, and why, said once each.

A node written for Webots' e-puck (``webots_ros2_epuck`` in cyberbotics/webots_ros2, whose world
simulates ``E-puck { version "2" }`` with its time-of-flight sensor, camera and light sensors)
may wait for a topic the simulated robot does not have: ``/tof`` from the e-puck, which has no
time-of-flight sensor, waits forever. :class:`UnpublishedTopics` watches the readers DDS
discovers on other participants and names each such topic once, with what to do.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable
from typing import Any

__all__ = ["UnpublishedTopics", "why_unpublished"]

#: What Webots' e-puck driver publishes and the bridge does not, by topic (its last name token).
_WEBOTS_EPUCK_ONLY = (
    (re.compile(r"tof"), "the {robot} has no time-of-flight sensor; the e-puck2 has one "
     "(--robot e-puck2, as Webots' webots_ros2_epuck simulates)"),
    (re.compile(r"ls[0-7]"), "mazesim does not simulate the e-puck's light sensors"),
    (re.compile(r"imu"), "mazesim does not simulate the e-puck's inertial unit"),
    (re.compile(r"(image_raw|camera_info|camera(/.*)?)"), "the bridge publishes no camera images"),
)  # fmt: skip


def why_unpublished(topic: str, published: Iterable[str], robot: str) -> str | None:
    """Why a node reading ``topic`` (a ROS name) gets nothing, when it is one of the topics of
    Webots' e-puck driver that the bridge does not publish; ``None`` otherwise."""
    if topic in set(published):
        return None
    token = topic.rstrip("/").rsplit("/", 1)[-1]
    whole = topic.lstrip("/")
    for pattern, reason in _WEBOTS_EPUCK_ONLY:
        if pattern.fullmatch(token) or pattern.fullmatch(whole):
            return reason.format(robot=robot)
    return None


class UnpublishedTopics:
    """Watches the readers of other participants and reports, once per topic, those that wait
    for a topic of Webots' e-puck driver the bridge does not publish.

    Args:
        participant: The bridge's Cyclone DDS participant.
        published: The ROS names of the topics the bridge publishes.
        robot: The simulated robot's profile name, for the message.
        report: Called with each message.
    """

    def __init__(
        self, participant: Any, published: Iterable[str], robot: str, report: Callable[[str], None]
    ) -> None:
        from cyclonedds.builtin import BuiltinDataReader, BuiltinTopicDcpsSubscription

        self.own = participant.guid
        self.published = set(published)
        self.robot = robot
        self.report = report
        self.reported: set[str] = set()
        self._reader = BuiltinDataReader(participant, BuiltinTopicDcpsSubscription)

    def check(self) -> None:
        """Reads the readers discovered since the last call and reports the new topics."""
        for endpoint in self._reader.take(64):
            name = getattr(endpoint, "topic_name", None)
            if not name or not name.startswith("rt/") or endpoint.participant_key == self.own:
                continue
            topic = "/" + name[3:]
            if topic in self.reported:
                continue
            reason = why_unpublished(topic, self.published, self.robot)
            if reason is not None:
                self.reported.add(topic)
                self.report(f"a node reads {topic}, which this bridge does not publish: {reason}")
