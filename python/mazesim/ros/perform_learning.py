"""The perform-learning node (the report's Alg. 5): the hierarchical policy driving over ROS.

It subscribes ``sensor_data`` (six Sharp distances in cm and the current checkpoint, published by
a bridge running a robot with Sharp sensors such as ``seed``), asks the policy for a primitive
action and publishes its code on ``action``: one action per reading, which is exactly what a
lockstep bridge waits for. Before it subscribes it waits until the bridge listens on ``action``, so
its first action cannot be lost.

The policy is :mod:`mazesim.learn`'s, loaded with :func:`mazesim.learn.tables.load_policy` (by
default the tables shipped for ``seed-maze``); the node imports it only when it starts. Like the
report's robot, the policy sees only what the topic carries: the odometry of its sub-tasks is
dead-reckoned from the actions it chose, each held for one control step of the bridge. The node
takes that step from the ``control_step_ms`` parameter the bridge sets in its namespace (32 ms for
the ``seed`` robot; the shipped tables were trained with 64 ms steps and reach the goal at 32 ms as
well) and passes it to ``policy.reset(control_step_ms=...)``.

The hooks it relies on, as :class:`mazesim.learn.TrainedPolicy` provides them:

- ``mazesim.learn.tables.load_policy(path: str | None)`` returns a policy; ``None`` means the
  tables shipped with the package.
- ``policy.reset(control_step_ms)`` starts a new episode whose actions each last that long.
- ``policy.act(distances_cm, checkpoint) -> str`` takes the six distances in cm (front, back, left,
  right, left-front, right-front; a float64 array of shape (6,)) and the signed checkpoint id
  (0 if none) and returns one of :data:`mazesim.actions.ACTION_CODES`.

Parameters (private; options of ``mazesim ros perform-learning`` take precedence): ``policy``
(a folder of trained tables; empty for the shipped ones), ``control_step_ms`` (how long each
action runs; 0, the default, reads the bridge's parameter) and ``wait_for_subscribers`` (how many
subscribers of ``action`` to wait for before starting, default 1, the bridge; 2 when a recorder
must not miss the first actions either).
"""

from __future__ import annotations

import math
import threading
import time
from typing import Any

import numpy as np

from mazesim.errors import InvalidArgumentError, MazesimError, _shown
from mazesim.ros import topics
from mazesim.ros._ros import (
    publish_unless_stopping,
    publisher,
    start_node,
    subscriber_count,
    wait_for_subscribers,
)

__all__ = ["load_policy", "run_perform_learning"]

#: Seconds the node waits for the bridge's ``control_step_ms`` once the bridge listens.
CONTROL_STEP_TIMEOUT_S = 10.0


def load_policy(path: str | None) -> Any:
    """Loads the hierarchical policy with :func:`mazesim.learn.tables.load_policy`, imported
    only when the node starts.

    Args:
        path: A folder of trained tables, or ``None`` for the tables shipped with mazesim.

    Raises:
        PolicyFormatError: The folder does not hold a usable policy.
    """
    from mazesim.learn.tables import load_policy as load_tables

    return load_tables(path)


def control_step_value(name: str, value: Any, allow_zero: bool) -> float:
    """Checks a control step in ms read from an option or a parameter.

    Args:
        name: The parameter's name, for the message.
        value: What was read.
        allow_zero: Whether 0 (meaning "the bridge's") is allowed.

    Raises:
        InvalidArgumentError: The value is not a finite number > 0 (or >= 0 with ``allow_zero``).
    """
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if isinstance(value, bool) or not math.isfinite(number) or number < 0.0:
        number = math.nan
    if math.isnan(number) or (number == 0.0 and not allow_zero):
        wanted = "ms >= 0 (0: the bridge's)" if allow_zero else "ms > 0"
        raise InvalidArgumentError(f"expected parameter {name} in {wanted}; found {_shown(value)}")
    return number


def _bridge_control_step(rospy: Any, stop: threading.Event) -> float:
    """Waits for the ``control_step_ms`` parameter the bridge sets, and returns it."""
    name = rospy.resolve_name(topics.CONTROL_STEP_PARAM)
    deadline = time.monotonic() + CONTROL_STEP_TIMEOUT_S
    while not rospy.has_param(name):
        if time.monotonic() >= deadline:
            raise MazesimError(
                f"no control step: the parameter {name} was not set within "
                f"{CONTROL_STEP_TIMEOUT_S:g} s (a mazesim bridge in this namespace sets it); "
                "give it with --control-step-ms or the private parameter ~control_step_ms"
            )
        if stop.wait(0.05):
            return 0.0
    return control_step_value(name, rospy.get_param(name), allow_zero=False)


def run_perform_learning(
    options: dict[str, Any], remappings: list[str], node_name: str = "perform_learning"
) -> int:
    """Runs the perform-learning node until it is stopped.

    Args:
        options: ``policy``, ``control_step_ms`` and ``wait_for_subscribers`` from the command
            line, each ``None`` to use the private ROS parameter (then the defaults).
        remappings: ROS remapping arguments such as ``action:=/robot1/action``.
        node_name: The node's name unless a ``__name:=`` remapping overrides it.

    Returns:
        The exit code, 0 once the node has stopped.
    """
    ros, stop = start_node("mazesim-ros-perform-learning", node_name, remappings)
    rospy = ros.rospy
    try:
        policy_path = options.get("policy")
        if policy_path is None:
            policy_path = str(rospy.get_param("~policy", ""))
        step_option = options.get("control_step_ms")
        if step_option is None:
            step_option = rospy.get_param("~control_step_ms", 0.0)
        control_step_ms = control_step_value("control_step_ms", step_option, allow_zero=True)
        subscribers = subscriber_count(rospy, options.get("wait_for_subscribers"))
        policy = load_policy(policy_path or None)
    except MazesimError as error:
        rospy.signal_shutdown(f"bad parameters: {error}")
        raise
    # Synchronous: one action per reading, never dropped (see mazesim.ros._ros.publisher).
    action = publisher(ros, topics.ACTION_TOPIC, ros.String, synchronous=True)
    wait_for_subscribers(rospy, action, subscribers, stop)
    if control_step_ms == 0.0 and not stop.is_set():
        try:
            control_step_ms = _bridge_control_step(rospy, stop)
        except MazesimError as error:
            rospy.signal_shutdown(f"no control step: {error}")
            raise
    if stop.is_set():
        rospy.signal_shutdown("perform-learning stopped")
        return 0
    policy.reset(control_step_ms=control_step_ms)
    published = 0

    def on_sensor_data(message: Any) -> None:
        nonlocal published
        values = message.data
        if len(values) != 7 or not all(math.isfinite(value) for value in values):
            rospy.logwarn_throttle(
                5.0,
                "ignored sensor_data without 6 distances in cm and a checkpoint as 7 finite "
                "numbers (found %d values)",
                len(values),
            )
            return
        code = policy.act(np.asarray(values[:6], dtype=np.float64), int(values[6]))
        publish_unless_stopping(rospy, action, ros.String(data=code), stop)
        published += 1

    rospy.Subscriber(
        topics.SENSOR_DATA_TOPIC,
        ros.Float64MultiArray,
        on_sensor_data,
        queue_size=1,
        tcp_nodelay=True,
    )
    rospy.loginfo(
        "perform-learning: policy %s (world %s), actions of %g ms; %s -> %s",
        getattr(policy, "source", None) or policy_path or "shipped",
        getattr(policy, "world_name", "?"),
        control_step_ms,
        rospy.resolve_name(topics.SENSOR_DATA_TOPIC),
        action.resolved_name,
    )
    while not stop.wait(0.1) and not rospy.is_shutdown():
        pass
    rospy.loginfo("perform-learning stopped: %d actions published", published)
    rospy.signal_shutdown("perform-learning stopped")
    return 0
