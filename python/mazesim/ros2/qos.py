"""The QoS of each kind of topic, as ROS 2's e-puck drivers and tools use them.

Sensor data: reliable, volatile, keep last 5; ``/tf``: keep last 100; ``/tf_static`` and
``ros_discovery_info``: transient local, keep last 1, so a late subscriber still gets them;
commands: keep last 10 (ROS 2's default). All data is plain CDR (XCDR1), as ROS 2 writes it.
:class:`IncompatibleQos` says when another node's endpoint cannot match the bridge's (a
``TRANSIENT_LOCAL`` reader of a volatile topic, a ``BEST_EFFORT`` command writer).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, NamedTuple

__all__ = [
    "CLOCK",
    "COMMAND",
    "GRAPH",
    "IncompatibleQos",
    "SENSOR",
    "TF",
    "TF_STATIC",
    "TopicQos",
    "cyclone_qos",
]


class TopicQos(NamedTuple):
    """Reliability, durability and history depth of a topic."""

    reliable: bool
    transient_local: bool
    depth: int

    def describe(self) -> str:
        """As the docs' table says it, e.g. ``reliable, volatile, 5``."""
        reliability = "reliable" if self.reliable else "best effort"
        durability = "transient local" if self.transient_local else "volatile"
        return f"{reliability}, {durability}, {self.depth}"


SENSOR = TopicQos(reliable=True, transient_local=False, depth=5)
TF = TopicQos(reliable=True, transient_local=False, depth=100)
TF_STATIC = TopicQos(reliable=True, transient_local=True, depth=1)
CLOCK = TopicQos(reliable=True, transient_local=False, depth=10)
COMMAND = TopicQos(reliable=True, transient_local=False, depth=10)
GRAPH = TopicQos(reliable=True, transient_local=True, depth=1)


def cyclone_qos(profile: TopicQos, user_data: bytes | None = None) -> Any:
    """The Cyclone DDS QoS of ``profile``, with the endpoint's USER_DATA if given."""
    from cyclonedds.core import Policy
    from cyclonedds.qos import Qos

    policies = [
        Policy.Reliability.Reliable(max_blocking_time=1_000_000_000)
        if profile.reliable
        else Policy.Reliability.BestEffort,
        Policy.Durability.TransientLocal if profile.transient_local else Policy.Durability.Volatile,
        Policy.History.KeepLast(profile.depth),
        Policy.DataRepresentation(use_cdrv0_representation=True),
    ]
    if user_data is not None:
        policies.append(Policy.Userdata(user_data))
    return Qos(*policies)


#: DDS's QoS policy ids (``last_policy_id`` of the incompatible-QoS statuses) that ROS 2 sets.
POLICY_NAMES = {2: "durability", 4: "deadline", 8: "liveliness", 11: "reliability"}
#: Cyclone DDS's id of the type-consistency policy: the endpoints' types differ, which
#: :mod:`mazesim.ros2.unpublished` names with the types (a topic the bridge reads in two types,
#: ``/cmd_vel``, has a reader of the other type that no writer matches, rightly).
TYPE_CONSISTENCY = 24


class IncompatibleQos:
    """Reports, once per new occurrence, another node's reader that asked a writer of the
    bridge for QoS it does not offer, or writer that offered a reader of the bridge less than it
    asks: DDS does not match them, and that node receives (or sends) nothing.

    Args:
        writers: The bridge's writers (:class:`mazesim.ros2.node.Writer`).
        readers: The bridge's readers (:class:`mazesim.ros2.node.Reader`).
        report: Called with each message.
    """

    def __init__(
        self, writers: Sequence[Any], readers: Sequence[Any], report: Callable[[str], None]
    ) -> None:
        self.writers = list(writers)
        self.readers = list(readers)
        self.report = report
        self.seen: dict[int, int] = {}

    def _new(self, endpoint: Any, status: Any) -> str | None:
        """The policy of a new incompatibility of ``endpoint``, or ``None``."""
        if status.total_count <= self.seen.get(id(endpoint), 0):
            return None
        self.seen[id(endpoint)] = status.total_count
        policy = status.last_policy_id
        if policy == TYPE_CONSISTENCY:
            return "type"
        return POLICY_NAMES.get(policy, f"policy {policy}")

    def check(self) -> None:
        """Reads every endpoint's incompatible-QoS status and reports the new ones."""
        for endpoints, status_of, says in (
            (
                self.writers,
                lambda endpoint: endpoint.dds.get_offered_incompatible_qos_status(),
                "a node reads {topic} asking for a {policy} the bridge does not offer (it "
                "writes {qos}): that reader receives nothing; give it the bridge's {policy}",
            ),
            (
                self.readers,
                lambda endpoint: endpoint.dds.get_requested_incompatible_qos_status(),
                "a node writes {topic} offering less {policy} than the bridge asks for (it "
                "reads {qos}): nothing it sends arrives; give its writer the bridge's {policy}",
            ),
        ):
            said = set()  # the bridge's two cmd_vel readers (two types) see the same writer
            for endpoint in endpoints:
                policy = self._new(endpoint, status_of(endpoint))
                if policy is not None and policy != "type":
                    message = says.format(
                        topic=endpoint.topic, policy=policy, qos=endpoint.qos.describe()
                    )
                    if message not in said:
                        said.add(message)
                        self.report(message)
