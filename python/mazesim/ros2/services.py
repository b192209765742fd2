"""ROS 2 services on Cyclone DDS, as ``rmw_cyclonedds_cpp`` lays them out on the wire.

A ROS 2 service ``/reset_simulation`` is two DDS topics: requests on
``rq/reset_simulationRequest`` and replies on ``rr/reset_simulationReply``, of the DDS types
``std_srvs::srv::dds_::Empty_Request_`` and ``std_srvs::srv::dds_::Empty_Response_``
(reliable, volatile, keep last 10: ROS 2's service QoS). ``rmw_cyclonedds_cpp`` puts a 16-byte
header before each request's fields, the client's id (8 bytes) and the request's sequence
number (8 bytes), and a server's reply carries the same header, by which the client knows its
answer. ``std_srvs/srv/Empty``'s request and response hold no field, so each carries the one
byte ROS 2 gives an empty structure (``structure_needs_at_least_one_member``). The bridge's
parameter services (:mod:`mazesim.ros2.parameters`) are served the same way.
"""

from __future__ import annotations

import functools
import time
from typing import Any, NamedTuple

from mazesim.ros2 import cdr
from mazesim.ros2.qos import TopicQos

__all__ = ["EMPTY", "SERVICE_QOS", "Request", "ServiceServer", "request_topic", "reply_topic"]

#: ``std_srvs/srv/Empty``.
EMPTY = "std_srvs/srv/Empty"
#: ROS 2's QoS of services (``rmw_qos_profile_services_default``).
SERVICE_QOS = TopicQos(reliable=True, transient_local=False, depth=10)
#: ``std_srvs/srv/Empty``'s response: its one byte, padded.
EMPTY_RESPONSE = cdr.CDR_LE + b"\x00\x00\x00\x00"
#: Seconds a reply waits for its client's reply reader to match before it goes anyway.
REPLY_WAIT_S = 1.0
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


class Request(NamedTuple):
    """One request: its header (the client's id and sequence number), its fields (CDR with the
    encapsulation header, without the service header, so aligned as a message) and the DDS key
    of the client's participant (``None`` when unknown)."""

    header: bytes
    fields: bytes
    client: Any


class ServiceServer:
    """The server side of one service.

    A client's request writer and reply reader are discovered one by one: a request may come
    before the server has matched the reader its reply goes to, and a reply sent then reaches
    no one (the client waits for ever). A reply therefore waits until a reply reader of the
    client's participant has matched, :data:`REPLY_WAIT_S` at most (``rmw_cyclonedds_cpp`` makes
    the same check, ``check_for_response_reader``, matching the request writer's participant).

    Args:
        service: The service's ROS name (``/reset_simulation``).
        requests: The reader of its request topic.
        replies: The writer of its reply topic.
    """

    def __init__(self, service: str, requests: Any, replies: Any) -> None:
        self.service = service
        self.requests = requests
        self.replies = replies
        #: Replies waiting for their client's reader: its participant, until when, the bytes.
        self._waiting: list[tuple[Any, float, bytes]] = []

    def take_requests(self) -> list[Request]:
        """The requests received since the last call, oldest first; a request too short to
        carry a header is dropped."""
        return [
            Request(
                bytes(data[4 : 4 + HEADER_BYTES]),
                bytes(data[:4] + data[4 + HEADER_BYTES :]),
                self.requests.writer_participant(writer),
            )
            for data, writer in self.requests.take_with_writers()
            if len(data) >= 4 + HEADER_BYTES
        ]

    def reply(self, request: Request, response: bytes = EMPTY_RESPONSE) -> None:
        """Answers ``request`` with ``response`` (CDR with its encapsulation header; the empty
        response by default), once the client's reply reader has matched."""
        data = response[:4] + request.header + response[4:]
        self._waiting.append((request.client, time.monotonic() + REPLY_WAIT_S, data))
        self.flush()

    def flush(self) -> None:
        """Sends the replies whose client's reader has matched, or that waited long enough."""
        if not self._waiting:
            return
        now = time.monotonic()
        present = self.replies.reader_participants()
        waiting, self._waiting = self._waiting, []
        for client, until, data in waiting:
            if client is None or client in present or now >= until:
                self.replies.publish(data)
            else:
                self._waiting.append((client, until, data))
