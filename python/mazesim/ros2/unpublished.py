"""Topics a node reads that the bridge does not publish, and why, said once each.

A node written for Webots' e-puck (``webots_ros2_epuck`` in cyberbotics/webots_ros2, whose world
simulates ``E-puck { version "2" }`` with its time-of-flight sensor, camera and light sensors) may
wait for a topic the simulated robot does not have: ``/tof`` from the e-puck, which has no
time-of-flight sensor, waits forever; so does a node waiting for a map elsewhere than ``/map``,
where the bridge publishes the world's. In a world of several robots, each robot's
topics are in its namespace: a node that names them absolutely (Webots' drive calibrator reads
``/odom`` and writes ``/cmd_vel``, so ``-r __ns:=/west`` leaves them as they are) reads and writes
where no robot is. :class:`UnpublishedTopics` watches the readers and writers DDS discovers on
other participants and names each such topic once, with what to do. It also says, once, when
another node publishes one of the bridge's own state topics or ``/clock``: a second bridge (or
simulator, or ``ros2 bag play``) on the same domain, whose messages every node then receives mixed
with the bridge's, and whose lockstep steps on the same commands. And it says when a node reads or
writes one of the bridge's topics as another message type (``/cmd_vel`` as
``std_msgs/msg/String``): DDS matches endpoints of one type only, so that node receives or sends
nothing.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Mapping, Sequence
from typing import Any

from mazesim.ros2.parameters import PARAMETER_SERVICES

__all__ = [
    "UnpublishedTopics",
    "also_published",
    "in_robot_namespaces",
    "other_type",
    "outside_a_namespace",
    "why_no_service",
    "why_unpublished",
]

#: The transforms' topics, which ``--frame-prefix`` puts outside the robots' namespaces.
_TF = ("/tf", "/tf_static")

#: What Webots' e-puck driver publishes and the bridge does not, by topic (its last name token).
_WEBOTS_EPUCK_ONLY = (
    (re.compile(r"tof"), "the {robot} has no time-of-flight sensor; the e-puck2 has one "
     "(--robot e-puck2, as Webots' webots_ros2_epuck simulates)"),
    (re.compile(r"ls[0-7]"), "mazesim does not simulate the e-puck's light sensors"),
    (re.compile(r"(image_raw|camera_info|camera(/.*)?)"), "the bridge publishes no camera images"),
    (re.compile(r"map"), "the bridge publishes the world's map on /map and in each robot's "
     "namespace (/NAMESPACE/map) only: remap the node's to one of them, or run a map server "
     "(Nav2's map_server) or a SLAM node (slam_toolbox, from /scan and /odom) beside it"),
)  # fmt: skip


def in_robot_namespaces(
    topic: str, endpoints: Iterable[str], namespaces: Sequence[str]
) -> str | None:
    """Why a node's ``topic`` (a ROS name outside every robot's namespace) reaches no robot when
    each robot of a world of several has it in its own namespace (``endpoints``: the ROS names
    of the bridge's topics of that direction); ``None`` when ``topic`` is not such a one."""
    endpoints = set(endpoints)
    if topic in endpoints or any(topic.startswith(ns + "/") for ns in namespaces):
        return None
    own = [ns + topic for ns in namespaces if ns + topic in endpoints]
    if not own:
        return None
    tf = " or run the bridge with --frame-prefix (every robot's on /tf)," if topic in _TF else ""
    return (
        f"each robot of this world has its own ({', '.join(own)}): remap the node's to its "
        f"robot's (--ros-args -r {topic}:={own[0]}),{tf} or start the node in the robot's "
        f"namespace (-r __ns:={own[0][: -len(topic)]}) if it names the topic without a "
        "leading slash"
    )


def outside_a_namespace(
    topic: str, endpoints: Iterable[str], namespaces: Sequence[str]
) -> str | None:
    """Why a node's ``topic`` in a namespace (``/epuck0/odom``) reaches no robot when the bridge
    runs one robot in none and has the topic there (``/odom``; ``endpoints``: the ROS names of
    the bridge's topics of that direction); ``None`` otherwise."""
    endpoints = set(endpoints)
    if namespaces or topic in endpoints:
        return None
    for slash in range(1, len(topic)):
        if topic[slash] == "/" and topic[slash:] in endpoints:
            own, namespace = topic[slash:], topic[:slash]
            return (
                f"the robot of this bridge has it in no namespace ({own}): run the bridge with "
                f"--namespace {namespace[1:]}, or remap the node's (--ros-args -r {topic}:={own})"
            )
    return None


def also_published(topic: str, published: Iterable[str]) -> str | None:
    """What goes wrong when another node writes ``topic``, a topic the bridge publishes (the
    transforms' topics aside, which many nodes write); ``None`` when it is not one of those."""
    if topic in _TF or topic not in set(published):
        return None
    return (
        f"another node publishes {topic}, as this bridge does: every node reading it receives "
        "both, and in lockstep both step on the same commands (a second bridge or simulator, or "
        "a bag played, on this domain?); give each simulation its own ROS_DOMAIN_ID"
    )


def other_type(
    does: str, topic: str, dds_type: str, types: Mapping[str, Sequence[str]]
) -> str | None:
    """What goes wrong when a node ``does`` (``reads``, ``writes``) ``topic`` with the DDS type
    name ``dds_type`` (``std_msgs::msg::dds_::String_``) while the bridge has the topic in the ROS
    types ``types[topic]`` only; ``None`` when the bridge has no such topic or has that type."""
    own = types.get(topic)
    if not own or not dds_type:
        return None
    ros_type = dds_type.replace("::dds_::", "::").rstrip("_").replace("::", "/")
    if ros_type in own:
        return None
    outcome = "that reader receives nothing" if does == "reads" else "nothing it sends arrives"
    return (
        f"a node {does} {topic} as {ros_type}; the bridge has it as {' or '.join(own)} only, and "
        f"DDS matches endpoints of one type: {outcome}"
    )


def why_no_service(service: str, node: str) -> str | None:
    """Why a node calling the ROS 2 service ``service`` (``/mazesim_bridge/get_loggers``) gets
    no answer when it is a service of the bridge's node ``node`` (its full name) that the bridge
    does not offer (its services are the resets and its parameter services); ``None`` for
    another node's service or one the bridge offers."""
    prefix = node.rstrip("/") + "/"
    if not service.startswith(prefix) or service[len(prefix) :] in PARAMETER_SERVICES:
        return None
    return (
        f"a node calls the service {service}, which this bridge does not offer: its services "
        "are /reset_simulation and /reset_world (std_srvs/srv/Empty) and its parameter "
        f"services ({node.rstrip('/')}/list_parameters, get_parameters, set_parameters...: "
        "ros2 param), its settings read-only parameters named after its command-line options "
        "(--world, --seed, --mode...): restart it to change them"
    )


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
    """Watches the readers and writers of other participants and reports, once per topic, those
    that wait for a topic of Webots' e-puck driver the bridge does not publish, and in a world of
    several robots those outside every robot's namespace where each robot has its own.

    Args:
        participant: The bridge's Cyclone DDS participant.
        published: The ROS names of the topics the bridge publishes.
        robot: The simulated robot's profile name, for the message.
        report: Called with each message.
        read: The ROS names of the topics the bridge reads.
        namespaces: The robots' namespaces in a world of several robots (none for one).
        types: The ROS message types the bridge has on each of its topics, read or written.
        node: The bridge node's full name (``/mazesim_bridge``), whose services a node may call.
    """

    def __init__(
        self,
        participant: Any,
        published: Iterable[str],
        robot: str,
        report: Callable[[str], None],
        read: Iterable[str] = (),
        namespaces: Sequence[str] = (),
        types: Mapping[str, Sequence[str]] | None = None,
        node: str = "/mazesim_bridge",
    ) -> None:
        from cyclonedds.builtin import (
            BuiltinDataReader,
            BuiltinTopicDcpsPublication,
            BuiltinTopicDcpsSubscription,
        )

        self.own = participant.guid
        self.published = set(published)
        self.read = set(read)
        self.namespaces = list(namespaces)
        self.types = dict(types or {})
        self.robot = robot
        self.node = node
        #: The ROS names of the services other nodes' clients call (request writers), since the
        #: last look.
        self.calls: list[str] = []
        self.report = report
        self.reported: set[tuple[str, str]] = set()
        self.said_also_published = False
        self._readers = BuiltinDataReader(participant, BuiltinTopicDcpsSubscription)
        self._writers = BuiltinDataReader(participant, BuiltinTopicDcpsPublication)

    def _topics(self, builtin: Any) -> list[tuple[str, str]]:
        """The ROS names and DDS type names of the endpoints of other participants discovered
        since the last look."""
        topics = []
        for endpoint in builtin.take(64):
            name = getattr(endpoint, "topic_name", None)
            if not name or endpoint.participant_key == self.own:
                continue
            if name.startswith("rt/"):
                topics.append(("/" + name[3:], getattr(endpoint, "type_name", "") or ""))
            elif builtin is self._writers and name.startswith("rq/") and name.endswith("Request"):
                self.calls.append("/" + name[3 : -len("Request")])
        return topics

    def check(self) -> None:
        """Reads the endpoints discovered since the last call and reports the new topics."""
        for topic, dds_type in self._topics(self._readers):
            self._say_once("reads", topic, other_type("reads", topic, dds_type, self.types))
            reason = (
                why_unpublished(topic, self.published, self.robot)
                or in_robot_namespaces(topic, self.published, self.namespaces)
                or outside_a_namespace(topic, self.published, self.namespaces)
            )
            self._say("reads", topic, "publish", reason)
        for topic, dds_type in self._topics(self._writers):
            self._say_once("writes", topic, other_type("writes", topic, dds_type, self.types))
            reason = in_robot_namespaces(topic, self.read, self.namespaces) or outside_a_namespace(
                topic, self.read, self.namespaces
            )
            self._say("writes", topic, "read", reason)
            twice = also_published(topic, self.published)
            if twice is not None and not self.said_also_published:
                self.said_also_published = True
                self.report(twice)
        calls, self.calls = self.calls, []
        for service in calls:
            self._say_once("calls", service, why_no_service(service, self.node))

    def _say(self, does: str, topic: str, bridge_does: str, reason: str | None) -> None:
        if reason is not None:
            self._say_once(
                does,
                topic,
                f"a node {does} {topic}, which this bridge does not {bridge_does}: " + reason,
            )

    def _say_once(self, does: str, topic: str, message: str | None) -> None:
        if message is not None and (does, topic) not in self.reported:
            self.reported.add((does, topic))
            self.report(message)
