"""A ROS node for the ROS tests: drives or listens to a bridge and prints what it saw as JSON.

rospy allows one node per process, so the tests run this script in a subprocess (with the master's
environment) and read its standard output.

    ros_probe.py drive COMMANDS_JSON   publish each command, wait for the state it produces
    ros_probe.py drive-from-second COMMANDS_JSON
                                       the same, leaving the first state unanswered (as a
                                       controller that answers only its second message)
    ros_probe.py drive-after-sleep COMMANDS_JSON
                                       the same, after a rospy.sleep(0.5) on simulated time
                                       before the first command (as teleop_twist_keyboard)
    ros_probe.py drive-skipping COMMANDS_JSON
                                       the same, leaving the state after the 10th command
                                       unanswered (as a lifecycle controller paused and resumed)
                                       until it comes again
    ros_probe.py drive-at-rate PERIOD COMMANDS_JSON
                                       publish each command, then rospy.Rate(1 / PERIOD).sleep()
                                       on simulated time, the Rate made once the reset state
                                       and a first /clock have come (a controller on a rate)
    ros_probe.py drive-sleeping PERIOD COMMANDS_JSON
                                       the same with rospy.sleep(PERIOD) after each command: its
                                       times count from whenever the sleep starts
    ros_probe.py drive-letting-a-tick-go PERIOD COMMANDS_JSON INDEX
                                       as drive-at-rate, the tick before command INDEX let go
                                       without a command
    ros_probe.py drive-on-timer PERIOD COMMANDS_JSON STATES
                                       a rospy.Timer(rospy.Duration(PERIOD)) made right after
                                       init_node, before any /clock (its ticks at the multiples
                                       of PERIOD), publishes the next command at each tick;
                                       returns once STATES states of distinct times have come
    ros_probe.py drive-after-goal N   send a goal on move_base_simple/goal once an odom has come
                                       (a click on rviz's 2D Nav Goal), then answer each odom
                                       with a cmd_vel twist, N times; the stamps answered
    ros_probe.py scan-with-odom N     as a Bug planner: a cmd_vel publisher, then subscriptions
                                       of scan and of odom, in that order; answers each scan with a
                                       twist once an odom has come, N times; the stamps of every
                                       scan received and of those answered
    ros_probe.py publisher-after N SECONDS [connected]
                                       subscribe odom, make the cmd_vel publisher SECONDS later
                                       (after the subscription connected, with ``connected``; a
                                       node loading something between the two), answer each odom
                                       with a twist once it exists, N times; the stamps of every
                                       odom received and of those answered
    ros_probe.py map                   rospy.wait_for_message on map (a planner waiting for
                                       map_server's map): its frame, size, origin and occupied cells
    ros_probe.py listen SECONDS        record what the bridge publishes for SECONDS (wall clock)
    ros_probe.py count TOPIC N         receive N messages of TOPIC (e.g. from rosbag play)
    ros_probe.py count-with-clock TOPIC N
                                       the same, and N messages of /clock too (each topic's
                                       connection comes up on its own: one waited for alone can
                                       catch few of the other)
    ros_probe.py standard TWISTS_JSON  publish each [linear.x, angular.z] on cmd_vel, keep the
                                       standard messages (odom, /tf, /tf_static, scan, Range topics)

A drive command is ``{"topic": "motor" | "action", "data": ..., "steps": 0 | 1}``: ``steps`` is
how many control steps it must cause (0 for a message the bridge must reject).
"""

from __future__ import annotations

import json
import math
import sys
import threading
import time
import warnings
from typing import Any

import rospy
from geometry_msgs.msg import PoseStamped, Twist
from nav_msgs.msg import OccupancyGrid, Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan, Range
from std_msgs.msg import Float64MultiArray, String
from tf2_msgs.msg import TFMessage

TIMEOUT_S = 120.0  # a ceiling for a hang: every wait ends on the messages it counts
STATE_TOPICS = ("pose", "sensors", "sensor_data")


class Recorder:
    """Keeps every message of some Float64MultiArray topics (and when it came), and /clock."""

    def __init__(self, topics: tuple[str, ...]) -> None:
        self.lock = threading.Condition()
        self.data: dict[str, list[list[float]]] = {topic: [] for topic in topics}
        self.wall: dict[str, list[float]] = {topic: [] for topic in topics}
        self.labels: dict[str, str] = {}
        self.clock: list[float] = []
        for topic in topics:
            rospy.Subscriber(
                topic, Float64MultiArray, self.on_array, callback_args=topic, tcp_nodelay=True
            )
        rospy.Subscriber("/clock", Clock, self.on_clock, tcp_nodelay=True)

    def on_array(self, message: Float64MultiArray, topic: str) -> None:
        with self.lock:
            self.data[topic].append(list(message.data))
            self.wall[topic].append(time.monotonic())
            if message.layout.dim:
                self.labels[topic] = message.layout.dim[0].label
            self.lock.notify_all()

    def on_clock(self, message: Clock) -> None:
        with self.lock:
            self.clock.append(message.clock.to_sec())
            self.lock.notify_all()

    def wait_for(self, counts: dict[str, int], clock: int = 0, timeout: float = TIMEOUT_S) -> None:
        """Waits until each topic of ``counts`` has that many messages, and ``/clock`` ``clock``."""
        with self.lock:
            done = self.lock.wait_for(
                lambda: (
                    len(self.clock) >= clock
                    and all(len(self.data[topic]) >= n for topic, n in counts.items())
                ),
                timeout,
            )
        if not done:
            have = {topic: len(self.data[topic]) for topic in counts}
            raise SystemExit(
                f"timed out waiting for {counts}, {clock} /clock; have {have}, "
                f"{len(self.clock)} /clock"
            )

    def result(self) -> dict[str, Any]:
        with self.lock:
            return {
                "data": self.data,
                "wall": self.wall,
                "labels": self.labels,
                "clock": self.clock,
            }


def publisher(topic: str, message_class: Any) -> Any:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SyntaxWarning)
        return rospy.Publisher(topic, message_class, queue_size=None)


def wait_for_connection(pub: Any) -> None:
    deadline = time.monotonic() + TIMEOUT_S
    while pub.get_num_connections() == 0:
        if time.monotonic() > deadline:
            raise SystemExit(f"no subscriber connected to {pub.resolved_name}")
        time.sleep(0.01)


def drive(
    commands: list[dict[str, Any]],
    first_answered: int = 1,
    sleep_s: float = 0.0,
    skip_after: int = 0,
) -> dict[str, Any]:
    """Publishes the commands, each after the state before it; ``first_answered`` is the state
    message the first command answers (2: the reset state must come twice); ``sleep_s``, a
    ``rospy.sleep`` before the first command; ``skip_after``, leave the state after that many
    commands unanswered until it comes again (0: none)."""
    motor = publisher("motor", Float64MultiArray)
    action = publisher("action", String)
    wait_for_connection(motor)
    wait_for_connection(action)
    # The bridge advertises its topics before it subscribes motor: the list is complete now.
    has_sensor_data = any(name == "/sensor_data" for name, _ in rospy.get_published_topics())
    topics = STATE_TOPICS if has_sensor_data else STATE_TOPICS[:2]
    recorder = Recorder(topics)
    expected = first_answered  # the latched state before the first command
    recorder.wait_for(dict.fromkeys(topics, expected))
    if sleep_s:
        if rospy.rostime.is_wallclock():
            raise SystemExit("expected /use_sim_time: rospy.sleep would not wait for /clock")
        rospy.sleep(sleep_s)
    for command in commands:
        if command["topic"] == "motor":
            motor.publish(Float64MultiArray(data=command["data"]))
        else:
            action.publish(String(data=command["data"]))
        expected += command["steps"]
        recorder.wait_for(dict.fromkeys(topics, expected))
        if skip_after and len(recorder.data[topics[0]]) - first_answered == skip_after:
            expected += 1  # the same state, sent again
            recorder.wait_for(dict.fromkeys(topics, expected))
    time.sleep(0.3)  # a step caused by a message that should have been rejected would show now
    return recorder.result()


def _yaw(rotation: Any) -> float:
    return 2.0 * math.atan2(rotation.z, rotation.w)


class StandardRecorder:
    """Keeps the standard messages: odom, /tf, /tf_static and scan as plain rows, Range per
    topic."""

    def __init__(self, range_topics: list[str]) -> None:
        self.lock = threading.Condition()
        self.odom: list[dict[str, Any]] = []
        self.tf: list[dict[str, Any]] = []
        self.tf_static: list[dict[str, Any]] = []
        self.scan: list[dict[str, Any]] = []
        self.ranges: dict[str, list[dict[str, Any]]] = {topic: [] for topic in range_topics}
        rospy.Subscriber("odom", Odometry, self.on_odom, tcp_nodelay=True)
        rospy.Subscriber("/tf", TFMessage, self.on_tf, callback_args=self.tf, tcp_nodelay=True)
        rospy.Subscriber("/tf_static", TFMessage, self.on_tf, callback_args=self.tf_static)
        rospy.Subscriber("scan", LaserScan, self.on_scan, tcp_nodelay=True)
        for topic in range_topics:
            rospy.Subscriber(topic, Range, self.on_range, callback_args=topic, tcp_nodelay=True)

    def on_odom(self, message: Odometry) -> None:
        pose, twist = message.pose.pose, message.twist.twist
        row = {
            "stamp": message.header.stamp.to_sec(),
            "frame": message.header.frame_id,
            "child": message.child_frame_id,
            "pose": [pose.position.x, pose.position.y, _yaw(pose.orientation)],
            "z": [pose.position.z, pose.orientation.x, pose.orientation.y],
            "twist": [twist.linear.x, twist.linear.y, twist.angular.z],
        }
        with self.lock:
            self.odom.append(row)
            self.lock.notify_all()

    def on_tf(self, message: TFMessage, rows: list[dict[str, Any]]) -> None:
        with self.lock:
            for transform in message.transforms:
                rows.append(
                    {
                        "stamp": transform.header.stamp.to_sec(),
                        "parent": transform.header.frame_id,
                        "child": transform.child_frame_id,
                        "pose": [
                            transform.transform.translation.x,
                            transform.transform.translation.y,
                            _yaw(transform.transform.rotation),
                        ],
                        "height": transform.transform.translation.z,
                    }
                )
            self.lock.notify_all()

    def on_scan(self, message: LaserScan) -> None:
        row = {
            "stamp": message.header.stamp.to_sec(),
            "frame": message.header.frame_id,
            "angles": [message.angle_min, message.angle_max, message.angle_increment],
            "limits": [message.range_min, message.range_max],
            "ranges": list(message.ranges),
        }
        with self.lock:
            self.scan.append(row)
            self.lock.notify_all()

    def on_range(self, message: Range, topic: str) -> None:
        row = {
            "stamp": message.header.stamp.to_sec(),
            "frame": message.header.frame_id,
            "radiation_type": message.radiation_type,
            "min_range": message.min_range,
            "max_range": message.max_range,
            "range": message.range,
        }
        with self.lock:
            self.ranges[topic].append(row)
            self.lock.notify_all()

    def wait_for(self, steps: int) -> None:
        def arrived() -> bool:
            return (
                bool(self.tf_static)  # latched, sent once: it comes on connection, at any time
                and len(self.odom) >= steps
                and len(self.tf) >= steps
                and len(self.scan) >= steps
                and all(len(rows) >= steps for rows in self.ranges.values())
            )

        with self.lock:
            if not self.lock.wait_for(arrived, TIMEOUT_S):
                raise SystemExit(f"timed out waiting for {steps} steps of the standard topics")


def standard(twists: list[list[float]]) -> dict[str, Any]:
    cmd_vel = publisher("cmd_vel", Twist)
    wait_for_connection(cmd_vel)
    types = dict(rospy.get_published_topics())
    range_topics = sorted(name for name, kind in types.items() if kind == "sensor_msgs/Range")
    recorder = StandardRecorder(range_topics)
    recorder.wait_for(1)  # the latched state before the first command
    for step, (linear, angular) in enumerate(twists, start=2):
        message = Twist()
        message.linear.x, message.angular.z = linear, angular
        cmd_vel.publish(message)
        recorder.wait_for(step)
    time.sleep(0.3)  # nothing more may come
    with recorder.lock:
        return {
            "odom": recorder.odom,
            "tf": recorder.tf,
            "tf_static": recorder.tf_static,
            "scan": recorder.scan,
            "ranges": recorder.ranges,
        }


def drive_at_rate(
    period: float, commands: list[dict[str, Any]], sleeping: bool = False, let_go: int = -1
) -> dict[str, Any]:
    """Publishes each command, then sleeps on a ``rospy.Rate`` of simulated time, as a
    controller commanding at a rate does (``sleeping``: ``rospy.sleep(period)``, counted from
    whenever it starts; ``let_go``: the tick before that command goes by without one, as a node
    that finds a message of the tick not come yet skips it); returns once the last command's
    hold is over (the clock at the rate's next tick, every state of it received)."""
    if rospy.rostime.is_wallclock():
        raise SystemExit("expected /use_sim_time: rospy.Rate would not count simulated time")
    motor = publisher("motor", Float64MultiArray)
    wait_for_connection(motor)
    recorder = Recorder(STATE_TOPICS[:2])
    recorder.wait_for(dict.fromkeys(STATE_TOPICS[:2], 1))
    deadline = time.monotonic() + TIMEOUT_S
    while rospy.get_rostime().is_zero():  # the first /clock: rospy's time starts there
        if time.monotonic() > deadline:
            raise SystemExit("no /clock came")
        time.sleep(0.01)
    rate = rospy.Rate(1.0 / period)
    for index, command in enumerate(commands):
        if index == let_go:
            rate.sleep()
        motor.publish(Float64MultiArray(data=command["data"]))
        if sleeping:
            rospy.sleep(period)
        else:
            rate.sleep()
    # Every state up to the clock's now: the reset state and one a control step.
    step_ns = int(round(float(rospy.get_param("control_step_ms")) * 1e6))
    steps = round(rospy.get_rostime().to_nsec() / step_ns)
    recorder.wait_for(dict.fromkeys(STATE_TOPICS[:2], steps + 1))
    return recorder.result()


def drive_on_timer(period: float, commands: list[dict[str, Any]]) -> dict[str, Any]:
    """Publishes the next command at each tick of a ``rospy.Timer`` made before anything else
    (as a node does in its constructor, on simulated time still at zero), the state topics
    recorded on the side; returns once the last command's hold is over."""
    if rospy.rostime.is_wallclock():
        raise SystemExit("expected /use_sim_time: rospy.Timer would not count simulated time")
    motor = publisher("motor", Float64MultiArray)
    queue = list(commands)
    sent = threading.Event()

    def tick(event: Any) -> None:
        if queue and motor.get_num_connections():
            motor.publish(Float64MultiArray(data=queue.pop(0)["data"]))
            if not queue:
                sent.set()

    timer = rospy.Timer(rospy.Duration(period), tick)
    recorder = Recorder(STATE_TOPICS[:2])
    if not sent.wait(TIMEOUT_S):
        raise SystemExit(f"the timer sent {len(commands) - len(queue)} of {len(commands)}")
    timer.shutdown()
    # Every state up to the end of the last command's hold (the reset state may come twice),
    # and the /clock of the last one: it comes on a connection of its own, served by a thread of
    # its own, and under load came after the last pose and sensors.
    states = int(sys.argv[4])
    with recorder.lock:
        if not recorder.lock.wait_for(
            lambda: (
                len({pose[3] for pose in recorder.data["pose"]}) >= states
                and len(recorder.data["sensors"]) >= len(recorder.data["pose"])
                and bool(recorder.clock)
                and recorder.clock[-1] >= recorder.data["pose"][-1][3] - 1e-9
            ),
            TIMEOUT_S,
        ):
            raise SystemExit(f"expected {states} states; have {len(recorder.data['pose'])}")
    return recorder.result()


def drive_after_goal(count: int) -> dict[str, Any]:
    """Sends a goal on ``move_base_simple/goal`` once an ``odom`` has come, then answers each
    ``odom`` with a twist, ``count`` times, as a goal follower without actionlib does; returns
    the stamps of the odometry answered."""
    cmd_vel = publisher("cmd_vel", Twist)
    goal = publisher("move_base_simple/goal", PoseStamped)
    seen = threading.Condition()
    odometry: list[Odometry] = []
    answered: list[float] = []
    going = threading.Event()

    def on_odom(message: Odometry) -> None:
        with seen:
            odometry.append(message)
            if going.is_set() and len(answered) < count:
                cmd_vel.publish(Twist())
                answered.append(message.header.stamp.to_sec())
            seen.notify_all()

    rospy.Subscriber("odom", Odometry, on_odom, tcp_nodelay=True)
    with seen:
        if not seen.wait_for(lambda: odometry, TIMEOUT_S):
            raise SystemExit("no odom came")
    wait_for_connection(goal)
    wait_for_connection(cmd_vel)
    going.set()  # from here each odometry is answered; the one waiting was not
    goal.publish(PoseStamped())
    with seen:
        if not seen.wait_for(lambda: len(answered) >= count, TIMEOUT_S):
            raise SystemExit(f"answered {len(answered)} of {count}")
    return {"answered": answered}


def scan_with_odom(count: int) -> dict[str, Any]:
    """Answers each ``scan`` with a twist, once an ``odom`` has come (skipping the scans before),
    ``count`` times, its ``scan`` subscription made before its ``odom`` one, as a Bug planner
    on one thread does; returns the stamps of every scan received and of those answered."""
    cmd_vel = publisher("cmd_vel", Twist)
    seen = threading.Condition()
    odometry: list[Odometry] = []
    scans: list[float] = []
    answered: list[float] = []

    def on_scan(message: LaserScan) -> None:
        with seen:
            scans.append(message.header.stamp.to_sec())
            if odometry and len(answered) < count:
                cmd_vel.publish(Twist())
                answered.append(message.header.stamp.to_sec())
            seen.notify_all()

    def on_odom(message: Odometry) -> None:
        with seen:
            odometry.append(message)

    rospy.Subscriber("scan", LaserScan, on_scan, tcp_nodelay=True)
    rospy.Subscriber("odom", Odometry, on_odom, tcp_nodelay=True)
    with seen:
        if not seen.wait_for(lambda: len(answered) >= count, TIMEOUT_S):
            raise SystemExit(f"answered {len(answered)} of {count}")
    return {"scans": scans, "answered": answered}


def publisher_after(count: int, delay_s: float, connected: bool = False) -> dict[str, Any]:
    """Subscribes ``odom``, makes its ``cmd_vel`` publisher ``delay_s`` later (after the
    subscription has connected, with ``connected``) and answers each odometry with a twist once
    it has one, ``count`` times; returns the stamps of every odometry received and of those
    answered."""
    seen = threading.Condition()
    made: list[Any] = []
    odometry: list[float] = []
    answered: list[float] = []

    def on_odom(message: Odometry) -> None:
        with seen:
            odometry.append(message.header.stamp.to_sec())
            if made and len(answered) < count:
                made[0].publish(Twist())
                answered.append(message.header.stamp.to_sec())
            seen.notify_all()

    subscription = rospy.Subscriber("odom", Odometry, on_odom, tcp_nodelay=True)
    while connected and not subscription.get_num_connections():
        time.sleep(0.001)
    time.sleep(delay_s)
    cmd_vel = publisher("cmd_vel", Twist)
    with seen:
        made.append(cmd_vel)
        if not seen.wait_for(lambda: len(answered) >= count, TIMEOUT_S):
            raise SystemExit(f"answered {len(answered)} of {count}")
    return {"odometry": odometry, "answered": answered}


def main() -> int:
    mode = sys.argv[1]
    rospy.init_node("ros_probe", anonymous=True, disable_signals=True)
    try:
        if mode in ("drive", "drive-from-second", "drive-after-sleep", "drive-skipping"):
            with open(sys.argv[2]) as handle:
                result = drive(
                    json.load(handle),
                    2 if mode == "drive-from-second" else 1,
                    0.5 if mode == "drive-after-sleep" else 0.0,
                    10 if mode == "drive-skipping" else 0,
                )
        elif mode in ("drive-at-rate", "drive-sleeping", "drive-letting-a-tick-go"):
            with open(sys.argv[3]) as handle:
                result = drive_at_rate(
                    float(sys.argv[2]),
                    json.load(handle),
                    mode == "drive-sleeping",
                    int(sys.argv[4]) if mode == "drive-letting-a-tick-go" else -1,
                )
        elif mode == "drive-on-timer":
            with open(sys.argv[3]) as handle:
                result = drive_on_timer(float(sys.argv[2]), json.load(handle))
        elif mode == "drive-after-goal":
            result = drive_after_goal(int(sys.argv[2]))
        elif mode == "map":
            grid = rospy.wait_for_message("map", OccupancyGrid, timeout=TIMEOUT_S)
            result = {
                "frame": grid.header.frame_id,
                "resolution": grid.info.resolution,
                "width": grid.info.width,
                "height": grid.info.height,
                "origin": [grid.info.origin.position.x, grid.info.origin.position.y],
                "occupied": sum(1 for cell in grid.data if cell == 100),
            }
        elif mode == "scan-with-odom":
            result = scan_with_odom(int(sys.argv[2]))
        elif mode == "publisher-after":
            connected = sys.argv[4:5] == ["connected"]
            result = publisher_after(int(sys.argv[2]), float(sys.argv[3]), connected)
        elif mode == "listen":
            recorder = Recorder(STATE_TOPICS)
            time.sleep(float(sys.argv[2]))
            result = recorder.result()
        elif mode == "standard":
            with open(sys.argv[2]) as handle:
                result = standard(json.load(handle))
        elif mode in ("count", "count-with-clock"):
            topic, count = sys.argv[2], int(sys.argv[3])
            recorder = Recorder((topic,))
            recorder.wait_for({topic: count}, count if mode == "count-with-clock" else 0)
            time.sleep(0.3)  # more than expected would show now
            result = recorder.result()
        else:
            raise SystemExit(f"unknown mode {mode!r}")
    finally:
        rospy.signal_shutdown("probe done")
    json.dump(result, sys.stdout)
    return 0


if __name__ == "__main__":
    sys.exit(main())
