"""The perform-learning node (the report's Alg. 5): the hierarchical policy driving over ROS.

It subscribes ``sensor_data`` (six Sharp distances in cm and the current checkpoint, published by
a bridge running a robot with Sharp sensors such as ``seed``), asks the policy for a primitive
action and publishes its code on ``action``: one action per reading, as a lockstep bridge expects.

The policy itself belongs to :mod:`mazesim.hrl`, which this node imports only when it starts. The
hook it relies on, which :mod:`mazesim.hrl` is to provide:

- ``mazesim.hrl.load_policy(path: str | None)`` returns a policy; ``None`` means the tables shipped
  with the package.
- ``policy.reset()`` starts a new episode.
- ``policy.act(distances_cm, checkpoint) -> str`` takes the six distances in cm (front, back, left,
  right, left-front, right-front; a float64 array of shape (6,)) and the signed checkpoint id
  (0 if none) and returns one of :data:`mazesim.actions.ACTION_CODES`.

Parameters (private; options of ``mazesim ros perform-learning`` take precedence): ``policy``
(a folder of trained tables; empty for the shipped ones).
"""

from __future__ import annotations

import importlib
import math
import threading
from typing import Any

import numpy as np

from mazesim.errors import MissingDependencyError
from mazesim.ros import topics
from mazesim.ros._ros import (
    install_shutdown_handlers,
    publisher,
    require_ros,
    wait_for_master,
)

__all__ = ["load_policy", "run_perform_learning"]

#: Seconds a node waits for the ROS master before giving up.
MASTER_TIMEOUT_S = 10.0


def _hrl_module() -> Any:
    """Imports :mod:`mazesim.hrl`, or says clearly that this installation lacks it."""
    try:
        hrl = importlib.import_module("mazesim.hrl")
    except ModuleNotFoundError as error:
        if error.name != "mazesim.hrl":
            raise
        raise MissingDependencyError(
            "the perform-learning node needs mazesim.hrl (the hierarchical Q-learning policy), "
            "which this installation of mazesim does not have"
        ) from error
    if not callable(getattr(hrl, "load_policy", None)):
        raise MissingDependencyError(
            "the perform-learning node needs mazesim.hrl.load_policy(path), "
            "which this installation of mazesim.hrl does not provide"
        )
    return hrl


def load_policy(path: str | None) -> Any:
    """Loads the hierarchical policy through :mod:`mazesim.hrl`'s ``load_policy`` hook.

    Args:
        path: A folder of trained tables, or ``None`` for the tables shipped with mazesim.

    Raises:
        MissingDependencyError: This installation of mazesim has no :mod:`mazesim.hrl`.
    """
    return _hrl_module().load_policy(path)


def run_perform_learning(
    options: dict[str, Any], remappings: list[str], node_name: str = "perform_learning"
) -> int:
    """Runs the perform-learning node until it is stopped.

    Args:
        options: ``policy`` from the command line, or ``None`` to use the private ROS parameter.
        remappings: ROS remapping arguments such as ``action:=/robot1/action``.
        node_name: The node's name unless a ``__name:=`` remapping overrides it.

    Returns:
        The exit code, 0 once the node has stopped.
    """
    ros = require_ros()
    rospy = ros.rospy
    _hrl_module()  # fail before touching ROS when the policy is missing
    wait_for_master(ros, MASTER_TIMEOUT_S)
    rospy.init_node(
        node_name, argv=["mazesim-ros-perform-learning", *remappings], disable_signals=True
    )
    policy_path = options.get("policy")
    if policy_path is None:
        policy_path = str(rospy.get_param("~policy", ""))
    try:
        policy = load_policy(policy_path or None)
    except Exception:
        rospy.signal_shutdown("the policy could not be loaded")
        raise
    stop = threading.Event()
    install_shutdown_handlers(stop)
    policy.reset()
    action = publisher(ros, topics.ACTION_TOPIC, ros.String, synchronous=True)

    def on_sensor_data(message: Any) -> None:
        values = message.data
        if len(values) != 7 or not all(math.isfinite(value) for value in values):
            rospy.logwarn_throttle(
                5.0, "ignored sensor_data without 6 distances and a checkpoint: %r", values
            )
            return
        code = policy.act(np.asarray(values[:6], dtype=np.float64), int(values[6]))
        action.publish(ros.String(data=code))

    while action.get_num_connections() == 0 and not stop.is_set():
        stop.wait(0.01)
    rospy.Subscriber(
        topics.SENSOR_DATA_TOPIC,
        ros.Float64MultiArray,
        on_sensor_data,
        queue_size=1,
        tcp_nodelay=True,
    )
    while not stop.wait(0.1) and not rospy.is_shutdown():
        pass
    rospy.signal_shutdown("perform-learning stopped")
    return 0
