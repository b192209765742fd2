"""A ROS 2 node on Cyclone DDS, without a ROS 2 installation.

:class:`Node` owns one DDS participant, creates readers and writers of ROS 2 topics (``/ps0`` is
the DDS topic ``rt/ps0``) with the distribution's types, QoS and USER_DATA, and announces itself
on ``ros_discovery_info``. Writers send already encoded messages (:mod:`mazesim.ros2.cdr`) and
readers hand back the bytes they received: Cyclone's own Python serializer is used only for the
few messages sent once.
"""

from __future__ import annotations

import time
import uuid
from collections.abc import Callable
from typing import Any

from mazesim.errors import InvalidArgumentError, MazesimIOError, _shown
from mazesim.ros2 import graph, messages, network, parameters, services
from mazesim.ros2._deps import require_ros2
from mazesim.ros2.qos import GRAPH, TopicQos, cyclone_qos
from mazesim.ros2.ros_args import RosArguments

__all__ = ["Node", "Reader", "Writer", "dds_topic_name"]


def dds_topic_name(topic: str) -> str:
    """The DDS topic of a ROS 2 topic: ``/ps0`` -> ``rt/ps0``."""
    return "rt/" + topic.lstrip("/")


#: The longest name of a ROS 2 topic, node or namespace (ROS 2's rmw bound: 255 characters;
#: the graph's discovery messages carry them in strings of that bound, and Cyclone DDS crashed
#: on a DataWriter of a 100,000-character topic).
MOST_NAME_CHARACTERS = 255


def _checked_name(kind: str, name: str) -> str:
    """``name`` if ROS 2 takes a ``kind`` (topic, node, namespace) of its length.

    Raises:
        InvalidArgumentError: It is longer than :data:`MOST_NAME_CHARACTERS`.
    """
    if len(name) > MOST_NAME_CHARACTERS:
        raise InvalidArgumentError(
            f"expected a ROS 2 {kind} name of at most {MOST_NAME_CHARACTERS} characters, found "
            f"one of {len(name)}: {_shown(name)}"
        )
    return name


def _joined(make: Callable[[], Any], what: str) -> Any:
    """What ``make`` makes in Cyclone DDS (a topic, a reader, a writer), or the package's error
    saying what DDS refused (a ``DDSException`` came out as an internal error).

    Raises:
        MazesimIOError: DDS refused it (out of memory, a bad parameter).
    """
    from cyclonedds.core import DDSException

    try:
        return make()
    except DDSException as e:
        raise MazesimIOError(
            f"Cyclone DDS could not make {what} ({e}): expected the memory and the network a "
            "DDS participant needs; check the process's memory limit and `ip link`"
        ) from None


class Writer:
    """Publishes encoded messages of one topic."""

    def __init__(self, topic: str, msgtype: str, writer: Any, qos: TopicQos) -> None:
        from cyclonedds._clayer import ddspy_write

        self.topic = topic
        self.msgtype = msgtype
        self.qos = qos
        self.dds = writer
        self._write = ddspy_write
        self._ref = writer._ref

    def publish(self, data: bytes) -> None:
        """Sends one message, already in CDR with its encapsulation header.

        Raises:
            MazesimIOError: DDS refused it.
        """
        result = self._write(self._ref, data)
        if result < 0:
            raise MazesimIOError(f"expected DDS to take a message on {self.topic}; error {result}")

    def subscribers(self) -> int:
        """How many readers are matched."""
        return len(self.dds.get_matched_subscriptions())

    def matched_readers(self) -> set[int]:
        """The DDS instance handles of the readers matched now (a new subscription's are new)."""
        return set(self.dds.get_matched_subscriptions())

    def reader_participants(self) -> set[Any]:
        """The DDS keys of the participants of the readers matched now."""
        found = (self.dds.get_matched_subscription_data(h) for h in self.matched_readers())
        return {data.participant_key for data in found if data is not None}


class Reader:
    """Receives the encoded messages of one topic."""

    def __init__(self, topic: str, msgtype: str, reader: Any, qos: TopicQos) -> None:
        from cyclonedds._clayer import ddspy_take
        from cyclonedds.core import InstanceState, SampleState, ViewState

        self.topic = topic
        self.msgtype = msgtype
        self.qos = qos
        self.dds = reader
        self._take = ddspy_take
        self._mask = SampleState.Any | ViewState.Any | InstanceState.Any

    def take(self, count: int = 64) -> list[bytes]:
        """The messages received since the last call, oldest first (at most ``count``)."""
        return [data for data, _ in self.take_with_writers(count)]

    def take_with_writers(self, count: int = 64) -> list[tuple[bytes, int]]:
        """The messages received since the last call, oldest first, each with the DDS instance
        handle of the writer that sent it."""
        result = self._take(self.dds._ref, self._mask, count)
        if isinstance(result, int):
            raise MazesimIOError(
                f"expected DDS to hand over messages of {self.topic}; error {result}"
            )
        return [(data, info.publication_handle) for data, info in result if info.valid_data]

    def writer_participant(self, handle: int) -> Any:
        """The DDS key of the participant of the matched writer ``handle`` (``None`` if gone)."""
        data = self.dds.get_matched_publication_data(handle)
        return None if data is None else data.participant_key

    def publishers(self) -> int:
        """How many writers are matched."""
        return len(self.dds.get_matched_publications())

    def matched_writers(self) -> set[int]:
        """The DDS instance handles of the writers matched now (a restarted node's are new)."""
        return set(self.dds.get_matched_publications())


class Node:
    """One ROS 2 node in its own DDS participant.

    Args:
        name: The node's name, as ``ros2 node list`` shows it.
        distro: The ROS 2 distribution whose layouts, hashes and GIDs to use.
        discovery: The domain and the discovery reach (this machine by default).
        namespace: The node's namespace.
        ros_arguments: The ``--ros-args`` section of its command line: its remappings rename
            its topics, as ROS 2's do.
    """

    def __init__(
        self,
        name: str,
        distro: str = "humble",
        discovery: network.Discovery | None = None,
        namespace: str = "/",
        ros_arguments: RosArguments | None = None,
    ) -> None:
        require_ros2()
        from cyclonedds.core import DDSException, Policy
        from cyclonedds.domain import Domain, DomainParticipant
        from cyclonedds.qos import Qos
        from cyclonedds.topic import Topic

        self._topic_class = Topic
        self.name = _checked_name("node", name)
        self.namespace = _checked_name("namespace", namespace)
        self.ros_arguments = ros_arguments or RosArguments()
        self.distro = messages.check_distro(distro)
        self.discovery = discovery or network.discovery_from_environment()
        config = network.cyclone_config(self.discovery)
        try:
            self._domain = Domain(self.discovery.domain_id, config) if config else None
            self.participant: Any = DomainParticipant(
                self.discovery.domain_id, qos=Qos(Policy.Userdata(graph.PARTICIPANT_USER_DATA))
            )
        except DDSException as e:
            raise MazesimIOError(
                f"Cyclone DDS could not join ROS 2 domain {self.discovery.domain_id} ({e}): "
                "expected a usable network interface (the loopback interface 'lo' up, or the "
                "network with --network); check `ip link`, or the CYCLONEDDS_URI you set"
            ) from None
        self._topics: dict[tuple[str, str], Any] = {}
        self.readers: list[Reader] = []
        self.writers: list[Writer] = []
        #: The service servers of the node (:meth:`service_server`).
        self.services: list[Any] = []
        self._graph_writer = self._dds_writer(
            graph.DISCOVERY_TOPIC, graph.DISCOVERY_TYPE, GRAPH, ros_topic=False
        )

    def _topic(self, dds_name: str, msgtype: str, idl: Any = None) -> Any:
        # One DDS topic per name and type: a name may carry two types (``cmd_vel``: Twist and
        # TwistStamped), and DDS matches each reader only with writers of its own type.
        key = (dds_name, msgtype)
        if key not in self._topics:
            _checked_name("topic", dds_name.removeprefix("rt/"))
            self._topics[key] = _joined(
                lambda: self._topic_class(
                    self.participant, dds_name, idl or messages.idl_type(self.distro, msgtype)
                ),
                f"the topic {dds_name} of {msgtype}",
            )
        return self._topics[key]

    def _dds_writer(self, topic: str, msgtype: str, qos: TopicQos, ros_topic: bool = True) -> Any:
        from cyclonedds.pub import DataWriter

        name = dds_topic_name(topic) if ros_topic else topic
        user_data = graph.endpoint_user_data(self.distro, msgtype) if ros_topic else None
        dds_topic = self._topic(name, msgtype)
        return _joined(
            lambda: DataWriter(self.participant, dds_topic, qos=cyclone_qos(qos, user_data)),
            f"a writer of {name}",
        )

    def resolve(self, topic: str) -> str:
        """The name the node's topic ``topic`` has after its remappings."""
        return self.ros_arguments.remap(topic, self.name, self.namespace)

    def writer(self, topic: str, msgtype: str, qos: TopicQos) -> Writer:
        """A writer of the ROS 2 topic ``topic`` (``/ps0``) of ``msgtype`` (``pkg/msg/Name``),
        under the name its remappings give it."""
        topic = self.resolve(topic)
        writer = Writer(topic, msgtype, self._dds_writer(topic, msgtype, qos), qos)
        self.writers.append(writer)
        return writer

    def reader(self, topic: str, msgtype: str, qos: TopicQos) -> Reader:
        """A reader of the ROS 2 topic ``topic`` of ``msgtype``, under the name its remappings
        give it."""
        from cyclonedds.sub import DataReader

        topic = self.resolve(topic)
        user_data = graph.endpoint_user_data(self.distro, msgtype)
        dds_topic = self._topic(dds_topic_name(topic), msgtype)
        dds = _joined(
            lambda: DataReader(self.participant, dds_topic, qos=cyclone_qos(qos, user_data)),
            f"a reader of {topic}",
        )
        reader = Reader(topic, msgtype, dds, qos)
        self.readers.append(reader)
        return reader

    def service_server(self, service: str, srvtype: str = services.EMPTY) -> services.ServiceServer:
        """A server of the ROS 2 service ``service`` (``/reset_simulation``) of ``srvtype``, a
        service without fields (:mod:`mazesim.ros2.services`) or a parameter service
        (:mod:`mazesim.ros2.parameters`), under the name its remappings give it."""
        from cyclonedds.pub import DataWriter
        from cyclonedds.sub import DataReader

        service = self.resolve(service)
        request, response = (
            services.idl_types(srvtype)
            if srvtype == services.EMPTY
            else parameters.idl_types(self.distro, srvtype)
        )
        qos = cyclone_qos(services.SERVICE_QOS)
        requests = DataReader(
            self.participant,
            self._topic(services.request_topic(service), srvtype + "_Request", request),
            qos=qos,
        )
        replies = DataWriter(
            self.participant,
            self._topic(services.reply_topic(service), srvtype + "_Response", response),
            qos=qos,
        )
        server = services.ServiceServer(
            service,
            Reader(service, srvtype, requests, services.SERVICE_QOS),
            Writer(service, srvtype, replies, services.SERVICE_QOS),
        )
        self.services.append(server)
        return server

    def announce(self) -> None:
        """Publishes the node and its endpoints on ``ros_discovery_info``. Its services'
        endpoints are among them where the distribution sends no type hashes (Humble): a
        service's endpoints carry the service type's hash from Jazzy on, which this node does not
        compute; there they are left out (``ros2 service list`` and a client's
        ``wait_for_service`` find a service through DDS discovery, not through this topic)."""
        services_listed = [] if self.distro in graph.TYPE_HASH_DISTROS else self.services
        sample = graph.participant_entities_info(
            self.distro,
            self.participant.guid,
            [
                (
                    self.namespace,
                    self.name,
                    [reader.dds.guid for reader in self.readers]
                    + [server.requests.dds.guid for server in services_listed],
                    [writer.dds.guid for writer in self.writers]
                    + [server.replies.dds.guid for server in services_listed],
                )
            ],
        )
        self._graph_writer.write(sample)

    def guid(self) -> uuid.UUID:
        """The participant's DDS GUID."""
        return uuid.UUID(str(self.participant.guid))

    def close(self) -> None:
        """Leaves the DDS domain (other nodes see the participant go at once)."""
        self.participant = None
        self._topics.clear()
        self.readers.clear()
        self.writers.clear()
        self.services.clear()
        self._graph_writer = None
        self._domain = None
        time.sleep(0)
