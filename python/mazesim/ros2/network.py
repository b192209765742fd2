"""Where the bridge's DDS discovery reaches: this machine unless the user asks for the network.

ROS 2's own variables are honoured: ``ROS_DOMAIN_ID`` (0 by default), and the discovery range,
``ROS_AUTOMATIC_DISCOVERY_RANGE`` (Jazzy and later: ``LOCALHOST``, ``SUBNET``, ``OFF`` or
``SYSTEM_DEFAULT``) or Humble's ``ROS_LOCALHOST_ONLY`` (``1`` or ``0``). Where neither is set the
bridge stays on this machine (ROS 2's own default is the subnet): it talks over the loopback
interface only, multicast for discovery and 127.0.0.1 as a unicast peer, as ``rmw_cyclonedds_cpp``
does for ``LOCALHOST``. ``--network`` (``SUBNET``) or the variables open it to the network. A
``CYCLONEDDS_URI`` in the environment is a full Cyclone DDS configuration and is used as it is.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from typing import NamedTuple

from mazesim.errors import InvalidArgumentError, _known_name, _shown

__all__ = ["LOCALHOST", "SUBNET", "Discovery", "cyclone_config", "discovery_from_environment"]

LOCALHOST = "LOCALHOST"
SUBNET = "SUBNET"
#: ROS 2's highest domain id on Linux (REP 2005's port arithmetic leaves 232).
MAX_DOMAIN_ID = 232

_LOCALHOST_CONFIG = (
    '<CycloneDDS><Domain Id="any"><General><Interfaces>'
    '<NetworkInterface address="127.0.0.1" multicast="true"/>'
    "</Interfaces></General><Discovery><ParticipantIndex>auto</ParticipantIndex>"
    "<MaxAutoParticipantIndex>32</MaxAutoParticipantIndex>"
    '<Peers><Peer address="127.0.0.1"/></Peers></Discovery></Domain></CycloneDDS>'
)


class Discovery(NamedTuple):
    """The DDS domain and how far discovery reaches (``LOCALHOST`` or ``SUBNET``)."""

    domain_id: int
    reach: str


def discovery_from_environment(
    environment: Mapping[str, str] | None = None, network: bool = False
) -> Discovery:
    """The domain and reach the environment asks for (this machine unless it asks otherwise).

    Args:
        environment: The variables to read; ``os.environ`` by default.
        network: ``--network`` was given: the subnet, whatever the variables say.

    Raises:
        InvalidArgumentError: ``ROS_DOMAIN_ID`` is not a whole number from 0 to 232, or the
            discovery range is not one ROS 2 defines.
    """
    env = os.environ if environment is None else environment
    text = env.get("ROS_DOMAIN_ID", "").strip() or "0"
    if not text.isdigit() or int(text) > MAX_DOMAIN_ID:
        raise InvalidArgumentError(
            f"expected ROS_DOMAIN_ID to be a whole number from 0 to {MAX_DOMAIN_ID}; found "
            f"{_shown(text)}"
        )
    reach = LOCALHOST
    automatic = env.get("ROS_AUTOMATIC_DISCOVERY_RANGE", "").strip().upper()
    if automatic:
        ranges = ("LOCALHOST", "SUBNET", "OFF", "SYSTEM_DEFAULT")
        _known_name(automatic, "ROS_AUTOMATIC_DISCOVERY_RANGE", ranges)
        reach = SUBNET if automatic in ("SUBNET", "SYSTEM_DEFAULT") else LOCALHOST
    elif env.get("ROS_LOCALHOST_ONLY", "").strip() == "0":
        reach = SUBNET
    if network:
        reach = SUBNET
    return Discovery(int(text), reach)


def cyclone_config(discovery: Discovery, environment: Mapping[str, str] | None = None) -> str:
    """The Cyclone DDS configuration for ``discovery``: ``""`` (Cyclone's defaults, or the
    user's ``CYCLONEDDS_URI``) for the subnet, the loopback-only configuration otherwise."""
    env = os.environ if environment is None else environment
    if env.get("CYCLONEDDS_URI") or discovery.reach == SUBNET:
        return ""
    return _LOCALHOST_CONFIG
