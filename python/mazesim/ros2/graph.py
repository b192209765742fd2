"""The ROS graph information that makes a DDS participant a ROS 2 node to ``ros2 node list``.

ROS 2 nodes are not DDS entities: each participant announces its nodes, and the GIDs of each
node's readers and writers, on the DDS topic ``ros_discovery_info``
(``rmw_dds_common/msg/ParticipantEntitiesInfo``, reliable, transient local), and carries
``enclave=/;`` in its USER_DATA. From Iron on, every endpoint's USER_DATA also carries its type's
hash, ``typehash=RIHS01_...;``. A GID is the entity's 16-byte DDS GUID, zero-padded to the
distribution's GID size (24 bytes in Humble, 16 in Jazzy), as ``rmw_cyclonedds_cpp`` makes it.
"""

from __future__ import annotations

import uuid
from collections.abc import Sequence
from typing import Any

from mazesim.ros2 import messages

__all__ = [
    "DISCOVERY_TOPIC",
    "PARTICIPANT_USER_DATA",
    "endpoint_user_data",
    "gid",
    "participant_entities_info",
]

DISCOVERY_TOPIC = "ros_discovery_info"
DISCOVERY_TYPE = "rmw_dds_common/msg/ParticipantEntitiesInfo"
PARTICIPANT_USER_DATA = b"enclave=/;"
#: The distributions whose endpoints carry type hashes in their USER_DATA.
TYPE_HASH_DISTROS = ("jazzy",)


def endpoint_user_data(distro: str, msgtype: str) -> bytes | None:
    """The USER_DATA of a reader or writer of ``msgtype``: its type hash where ``distro`` sends
    one (Jazzy: ``typehash=RIHS01_...;``), else ``None``."""
    if distro not in TYPE_HASH_DISTROS:
        return None
    return f"typehash={messages.type_hash(distro, msgtype)};".encode()


def gid(distro: str, guid: uuid.UUID) -> Any:
    """The ``rmw_dds_common/msg/Gid`` of the entity whose DDS GUID is ``guid``."""
    gid_type = messages.idl_type(distro, "rmw_dds_common/msg/Gid")
    size = 24 if distro == "humble" else 16
    return gid_type(data=list(guid.bytes.ljust(size, b"\x00")))


def participant_entities_info(
    distro: str,
    participant: uuid.UUID,
    nodes: Sequence[tuple[str, str, Sequence[uuid.UUID], Sequence[uuid.UUID]]],
) -> Any:
    """The ``ros_discovery_info`` sample of a participant.

    Args:
        distro: The ROS 2 distribution.
        participant: The participant's GUID.
        nodes: Each node's namespace, name, reader GUIDs and writer GUIDs.
    """
    node_type = messages.idl_type(distro, "rmw_dds_common/msg/NodeEntitiesInfo")
    info_type = messages.idl_type(distro, DISCOVERY_TYPE)
    return info_type(
        gid=gid(distro, participant),
        node_entities_info_seq=[
            node_type(
                node_namespace=namespace,
                node_name=name,
                reader_gid_seq=[gid(distro, reader) for reader in readers],
                writer_gid_seq=[gid(distro, writer) for writer in writers],
            )
            for namespace, name, readers, writers in nodes
        ],
    )
