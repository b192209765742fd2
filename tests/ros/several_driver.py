"""A rospy node driving every robot of a ROS 1 bridge on a world of several robots: one node
per run, one command per robot for each state it gets, as a controller per robot would.

Usage: several_driver.py NAMESPACES_JSON COMMANDS_JSON [standard]; COMMANDS_JSON holds, per step,
one ``[topic, value]`` per robot (``["motor", [l, r]]``, ``["action", "00"]``, ``["cmd_vel", [v,
w]]``) or ``null`` for a robot nobody drives. Prints, as its last line, the JSON of every robot's
pose messages in the order they came; with ``standard``, an object of those (``poses``), every
robot's ``odom`` messages (``odom``: frames, x, y, quaternion z and w, stamp in ns), what tf2 gives
for ``<robot>/odom`` -> ``<robot>/base_link`` at each one's stamp (``tf``: x, y, z and w) and the
static frames (``static``: ``map`` -> ``<robot>/odom`` and ``<robot>/base_link`` -> each of its
sensor frames named in the fourth argument's JSON, x, y, z and w).
"""

from __future__ import annotations

import json
import sys
import threading
import time

import rospy
import tf2_ros
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from std_msgs.msg import Float64MultiArray, String

TIMEOUT_S = 120.0


def main() -> int:
    namespaces: list[str] = json.loads(sys.argv[1])
    with open(sys.argv[2]) as handle:
        steps: list[list[list | None]] = json.load(handle)
    standard = len(sys.argv) > 3
    rospy.init_node("several_driver", disable_signals=True)
    odoms: list[list[list]] = [[] for _ in namespaces]
    listeners = []
    if standard:
        buffer = tf2_ros.Buffer()
        listener = tf2_ros.TransformListener(buffer, tcp_nodelay=True)
        listeners = [listener.tf_sub, listener.tf_static_sub]

        def on_odom(message: Odometry, index: int) -> None:
            pose = message.pose.pose
            stamp = message.header.stamp.to_nsec()
            frames = [message.header.frame_id, message.child_frame_id]
            if odoms[index] and odoms[index][-1][-1] == stamp:
                return  # a state sent again (its odom too) is kept once, as its pose is
            odoms[index].append(
                [*frames, pose.position.x, pose.position.y, *_zw(pose.orientation), stamp]
            )

        listeners += [
            rospy.Subscriber(f"{ns}/odom", Odometry, on_odom, i, tcp_nodelay=True)
            for i, ns in enumerate(namespaces)
        ]
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
        s.get_num_connections() == 0 for s in subscribers + listeners
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
        # Its odom too, before it is answered: an odom that went out before its subscription
        # connected comes again with the state while the state goes unanswered.
        while standard and any(len(robot_odoms) < count for robot_odoms in odoms):
            assert time.monotonic() < deadline + step * TIMEOUT_S, f"no odom of state {step}"
            time.sleep(0.02)
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
    if not standard:
        print(json.dumps(poses))
    else:
        # Each topic comes on a connection of its own: every state's odom too, before tf2 is
        # asked at their stamps; the wait has a time limit of its own (the steps before may
        # have taken most of the first one on a loaded machine).
        deadline = time.monotonic() + TIMEOUT_S
        while any(len(robot_odoms) <= len(steps) for robot_odoms in odoms):
            assert time.monotonic() < deadline, "not every odom came"
            time.sleep(0.02)
        print(json.dumps(_standard(buffer, namespaces, poses, odoms, json.loads(sys.argv[3]))))
    rospy.signal_shutdown("done")
    return 0


def _zw(rotation: object) -> list[float]:
    return [rotation.z, rotation.w]  # type: ignore[attr-defined]


def _standard(
    buffer: tf2_ros.Buffer,
    namespaces: list[str],
    poses: list[list[list[float]]],
    odoms: list[list[list]],
    sensors: list[str],
) -> dict[str, object]:
    """What tf2 gives for every robot's moving and static frames, with the messages."""
    timeout = rospy.Duration(TIMEOUT_S)

    def looked_up(parent: str, child: str, at: rospy.Time) -> list[float]:
        found = buffer.lookup_transform(parent, child, at, timeout).transform
        return [found.translation.x, found.translation.y, *_zw(found.rotation)]

    moved = []
    static = []
    for namespace, robot_odoms in zip(namespaces, odoms):
        name = namespace.strip("/")
        # At each odom message's stamp (step 0's is 1 ns: a stamp of 0 would be "the latest").
        moved.append(
            [
                looked_up(f"{name}/odom", f"{name}/base_link", rospy.Time(0, odom[-1]))
                for odom in robot_odoms
            ]
        )
        static.append(
            [looked_up("map", f"{name}/odom", rospy.Time(0))]
            + [looked_up(f"{name}/base_link", f"{name}/{s}", rospy.Time(0)) for s in sensors]
        )
    return {"poses": poses, "odom": odoms, "tf": moved, "static": static}


if __name__ == "__main__":
    sys.exit(main())
