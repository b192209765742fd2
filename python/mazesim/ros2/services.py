"""ROS 2 services on Cyclone DDS, as ``rmw_cyclonedds_cpp`` lays them out on the wire.

A ROS 2 service ``/reset_simulation`` is two DDS topics: requests on
``rq/reset_simulationRequest`` and replies on ``rr/reset_simulationReply``, of the DDS types
``std_srvs::srv::dds_::Empty_Request_`` and ``std_srvs::srv::dds_::Empty_Response_``
(reliable, volatile, keep last 10: ROS 2's service QoS). ``rmw_cyclonedds_cpp`` puts a 16-byte
header before each request's fields, the client's id (8 bytes) and the request's sequence
number (8 bytes), and a server's reply carries the same header, by which the client knows its
answer. ``std_srvs/srv/Empty``'s request and response hold no field, so each carries the one
byte ROS 2 gives an empty structure (``structure_needs_at_least_one_member``).
"""

from __future__ import annotations

import functools
from typing import Any

from mazesim.ros2 import cdr
from mazesim.ros2.qos import TopicQos

__all__ = ["EMPTY", "SERVICE_QOS", "ServiceServer", "request_topic", "reply_topic"]

#: ``std_srvs/srv/Empty``.
EMPTY = "std_srvs/srv/Empty"
#: ROS 2's QoS of services (``rmw_qos_profile_services_default``).
SERVICE_QOS = TopicQos(reliable=True, transient_local=False, depth=10)
#: The header ``rmw_cyclonedds_cpp`` puts before a request's fields and echoes in the reply.
HEADER_BYTES = 16


def request_topic(service: str) -> str:
    """The DDS topic of a service's requests: ``/reset_world`` -> ``rq/reset_worldRequest``."""
    return f"rq/{service.lstrip('/')}Request"


def reply_topic(service: str) -> str:
    """The DDS topic of a service's replies: ``/reset_world`` -> ``rr/reset_worldReply``."""
    return f"rr/{service.lstrip('/')}Reply"


@functools.cache
def idl_types(srvtype: str) -> tuple[Any, Any]:
    """The Cyclone DDS request and response types of a service without fields (``std_srvs/srv/
    Empty``), named as ROS 2 names them (``std_srvs::srv::dds_::Empty_Request_``)."""
    import cyclonedds.idl.types as idl_types_module
    from cyclonedds.idl import make_idl_struct

    package, kind, name = srvtype.split("/")
    made = []
    for part in ("Request", "Response"):
        class_name = f"{name}_{part}_"
        made.append(
            make_idl_struct(
                class_name,
                f"{package}::{kind}::dds_::{class_name}",
                {"structure_needs_at_least_one_member": idl_types_module.uint8},
            )
        )
    return made[0], made[1]


class ServiceServer:
    """The server side of one service whose request and response have no fields.

    Args:
        service: The service's ROS name (``/reset_simulation``).
        requests: The reader of its request topic.
        replies: The writer of its reply topic.
    """

    def __init__(self, service: str, requests: Any, replies: Any) -> None:
        self.service = service
        self.requests = requests
        self.replies = replies

    def take(self) -> list[bytes]:
        """The headers of the requests received since the last call, oldest first; a request
        too short to carry one is dropped."""
        return [
            bytes(data[4 : 4 + HEADER_BYTES])
            for data in self.requests.take()
            if len(data) >= 4 + HEADER_BYTES
        ]

    def reply(self, header: bytes) -> None:
        """Answers the request of ``header`` with the empty response."""
        self.replies.publish(cdr.CDR_LE + header + b"\x00\x00\x00\x00")
