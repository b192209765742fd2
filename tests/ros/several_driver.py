"""A rospy node driving every robot of a ROS 1 bridge on a world of several robots: one node
per run, one command per robot for each state it gets, as a controller per robot would.

Usage: several_driver.py NAMESPACES_JSON COMMANDS_JSON; COMMANDS_JSON holds, per step, one
``[topic, value]`` per robot (``["motor", [l, r]]``, ``["action", "00"]``, ``["cmd_vel",
[v, w]]``) or ``null`` for a robot nobody drives. Prints, as its last line, the JSON of every
robot's pose messages in the order they came.
"""

from __future__ import annotations

import json
import sys
import threading
import time

import rospy
from geometry_msgs.msg import Twist
from std_msgs.msg import Float64MultiArray, String

TIMEOUT_S = 120.0


def main() -> int:
    namespaces: list[str] = json.loads(sys.argv[1])
    with open(sys.argv[2]) as handle:
        steps: list[list[list | None]] = json.load(handle)
    rospy.init_node("several_driver", disable_signals=True)
    kinds = {"motor": Float64MultiArray, "action": String, "cmd_vel": Twist}
    publishers = {}
    for index, namespace in enumerate(namespaces):
        for topic in {entry[index][0] for entry in steps if entry[index] is not None}:
            publishers[(index, topic)] = rospy.Publisher(
                f"{namespace}/{topic}", kinds[topic], queue_size=None, tcp_nodelay=True
            )
    poses: list[list[list[float]]] = [[] for _ in namespaces]
    arrived = threading.Condition()

    def on_pose(message: Float64MultiArray, index: int) -> None:
        with arrived:
            # A state sent again (the bridge resends one nobody answered) is kept once.
            if not poses[index] or poses[index][-1][3] != message.data[3]:
                poses[index].append(list(message.data))
            arrived.notify_all()

    subscribers = [
        rospy.Subscriber(f"{ns}/pose", Float64MultiArray, on_pose, i, tcp_nodelay=True)
        for i, ns in enumerate(namespaces)
    ]
    deadline = time.monotonic() + TIMEOUT_S
    while any(p.get_num_connections() == 0 for p in publishers.values()) or any(
        s.get_num_connections() == 0 for s in subscribers
    ):
        assert time.monotonic() < deadline, "the bridge did not connect"
        time.sleep(0.02)
    for step, entry in enumerate(steps):
        with arrived:
            # The state of step `step` (the reset state first) has come for every robot.
            count = step + 1
            assert arrived.wait_for(
                lambda count=count: all(len(p) >= count for p in poses), timeout=TIMEOUT_S
            ), f"no state {step}"
        for index, command in enumerate(entry):
            if command is None:
                continue
            topic, value = command
            if topic == "motor":
                message = Float64MultiArray(data=value)
            elif topic == "action":
                message = String(data=value)
            else:
                message = Twist()
                message.linear.x, message.angular.z = value
            publishers[(index, topic)].publish(message)
    with arrived:
        assert arrived.wait_for(lambda: all(len(p) > len(steps) for p in poses), TIMEOUT_S)
    print(json.dumps(poses))
    rospy.signal_shutdown("done")
    return 0


if __name__ == "__main__":
    sys.exit(main())
