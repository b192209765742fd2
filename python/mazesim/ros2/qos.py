"""The QoS of each kind of topic, as ROS 2's e-puck drivers and tools use them.

Sensor data: reliable, volatile, keep last 5; ``/tf``: keep last 100; ``/tf_static`` and
``ros_discovery_info``: transient local, keep last 1, so a late subscriber still gets them;
commands: keep last 10 (ROS 2's default). All data is plain CDR (XCDR1), as ROS 2 writes it.
"""

from __future__ import annotations

from typing import Any, NamedTuple

__all__ = [
    "CLOCK",
    "COMMAND",
    "GRAPH",
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
