"""The avoid-collision controller node (the report's Listing 3.2, Alg. 4).

It subscribes ``sensors``, runs :class:`mazesim.controllers.AvoidCollision` (Alg. 1) on the first
eight values (the e-puck's ``ps0`` .. ``ps7``) and publishes the wheel speeds on ``motor``, one
command per reading, which is exactly what a lockstep bridge waits for. Before it subscribes it
waits until the bridge listens on ``motor``, so its first command cannot be lost.

Parameters (private; options of ``mazesim ros avoid-collision`` take precedence): ``threshold``
(raw proximity reading that means an obstacle, default 80), ``max_speed`` (rad/s, 6.28) and
``wait_for_subscribers`` (how many subscribers of ``motor`` to wait for before starting, default 1,
the bridge; 2 when a recorder must not miss the first commands either).
"""

from __future__ import annotations

import math
from typing import Any

from mazesim.controllers import AvoidCollision
from mazesim.errors import InvalidArgumentError, _shown
from mazesim.ros import topics
from mazesim.ros._ros import (
    publish_unless_stopping,
    publisher,
    start_node,
    subscriber_count,
    wait_for_subscribers,
)

__all__ = ["run_avoid_collision"]

#: The names of the values the controller reads, first on ``sensors``.
PS_NAMES = [f"ps{index}" for index in range(8)]


def _positive(rospy: Any, name: str, option: float | None, default: float) -> float:
    value = option if option is not None else rospy.get_param("~" + name, default)
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if not (math.isfinite(number) and number > 0.0):
        raise InvalidArgumentError(f"expected parameter {name} > 0; found {_shown(value)}")
    return number


def run_avoid_collision(
    options: dict[str, Any], remappings: list[str], node_name: str = "avoid_collision"
) -> int:
    """Runs the avoid-collision node until it is stopped.

    Args:
        options: ``threshold`` and ``max_speed`` from the command line, or ``None`` to use the
            private ROS parameters (then the defaults 80 and 6.28).
        remappings: ROS remapping arguments such as ``motor:=/robot1/motor``.
        node_name: The node's name unless a ``__name:=`` remapping overrides it.

    Returns:
        The exit code, 0 once the node has stopped.
    """
    ros, stop = start_node("mazesim-ros-avoid-collision", node_name, remappings)
    rospy = ros.rospy
    try:
        threshold = _positive(rospy, "threshold", options.get("threshold"), 80.0)
        max_speed = _positive(
            rospy, "max_speed", options.get("max_speed"), AvoidCollision.MAX_SPEED
        )
        subscribers = subscriber_count(rospy, options.get("wait_for_subscribers"))
    except InvalidArgumentError as error:
        rospy.signal_shutdown(f"bad parameters: {error}")
        raise
    controller = AvoidCollision(threshold=threshold, max_speed=max_speed)
    # Synchronous: one command per reading, never dropped (see mazesim.ros._ros.publisher).
    motor = publisher(ros, topics.MOTOR_TOPIC, ros.Float64MultiArray, synchronous=True)

    def on_sensors(message: Any) -> None:
        readings = message.data[:8]
        # The bridge labels the values; a publisher that does not is taken at its word.
        labels = message.layout.dim[0].label.split(",")[:8] if message.layout.dim else PS_NAMES
        if (
            labels != PS_NAMES
            or len(readings) < 8
            or not all(math.isfinite(value) for value in readings)
        ):
            rospy.logwarn_throttle(
                5.0,
                "ignored sensors data without the e-puck's ps0..ps7 as 8 finite numbers "
                "(found %d values labelled %s); run the bridge with robot e-puck",
                len(message.data),
                ",".join(labels) or "(none)",
            )
            return
        left, right = controller(readings)
        publish_unless_stopping(rospy, motor, ros.Float64MultiArray(data=[left, right]), stop)

    wait_for_subscribers(rospy, motor, subscribers, stop)
    rospy.Subscriber(
        topics.SENSORS_TOPIC,
        ros.Float64MultiArray,
        on_sensors,
        queue_size=1,
        tcp_nodelay=True,
    )
    rospy.loginfo(
        "avoid-collision: threshold %g, max speed %g rad/s; %s -> %s",
        threshold,
        max_speed,
        rospy.resolve_name(topics.SENSORS_TOPIC),
        motor.resolved_name,
    )
    while not stop.wait(0.1) and not rospy.is_shutdown():
        pass
    rospy.signal_shutdown("avoid-collision stopped")
    return 0
