"""Another node's endpoint that DDS cannot match with the bridge's is named, with the policy: a
``TRANSIENT_LOCAL`` reader of ``/odom`` (the bridge's writer is volatile), a ``BEST_EFFORT``
writer of ``/cmd_vel`` (the bridge reads reliably). The bridge's own report of them is checked
with the topics it does not publish (``test_ros2_unpublished.py``)."""

from __future__ import annotations

from types import SimpleNamespace
from typing import Any

from mazesim.ros2.qos import COMMAND, SENSOR, IncompatibleQos


def _endpoint(topic: str, qos: Any, count: int, policy: int) -> SimpleNamespace:
    status = SimpleNamespace(total_count=count, last_policy_id=policy)
    dds = SimpleNamespace(
        get_offered_incompatible_qos_status=lambda: status,
        get_requested_incompatible_qos_status=lambda: status,
    )
    return SimpleNamespace(topic=topic, qos=qos, dds=dds, status=status)


def test_each_new_incompatibility_is_reported_once_with_its_policy() -> None:
    odom = _endpoint("/odom", SENSOR, 0, 0)
    cmd_vel = _endpoint("/cmd_vel", COMMAND, 1, 11)
    said: list[str] = []
    watch = IncompatibleQos([odom], [cmd_vel], said.append)
    watch.check()
    assert len(said) == 1
    assert "a node writes /cmd_vel offering less reliability" in said[0]
    assert "reliable, volatile, 10" in said[0]
    watch.check()
    assert len(said) == 1  # nothing new
    odom.status.total_count, odom.status.last_policy_id = 1, 2
    watch.check()
    assert len(said) == 2
    assert "a node reads /odom asking for a durability" in said[1]
    assert "reliable, volatile, 5" in said[1]
