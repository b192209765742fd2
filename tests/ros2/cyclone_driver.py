"""A lockstep driver of the ROS 2 bridge, on Cyclone DDS's own message decoding.

Run as a separate process: it subscribes to the bridge's state topics, sends one ``/cmd_vel`` per
step (``Twist`` or ``TwistStamped`` as the distribution says), decodes every message with Cyclone
DDS's serializer (not mazesim's encoder) and checks every field against an in-process simulator
driven by the same commands. Exit code 0: all steps equal; 1: the first difference or a missing
message, on stderr. ``--answer-from-second-state`` leaves the reset state unanswered, as a node
that answers only from its second message does (Webots' e-puck drive calibrator takes its first
odometry as its start), and waits for the bridge to publish it again.

    python cyclone_driver.py --distro humble --steps 2000 [--robot e-puck] [--seed 0]
"""

from __future__ import annotations

import argparse
import math
import sys
import time
import uuid
import zlib
from typing import Any

import numpy as np

import mazesim
from mazesim.ros import standard, topics
from mazesim.ros.lockstep import RESEND_S
from mazesim.ros2 import messages, network, state
from mazesim.ros2.clock import stamp_nanoseconds
from mazesim.ros2.qos import COMMAND, SENSOR, TF, TF_STATIC, cyclone_qos

WAIT_S = 10.0
#: How long the driver waits at most for what must come (the bridge's /cmd_vel reader, a message
#: on a topic whose writer has matched): a ceiling that only bounds a hang, never a pace.
CEILING_S = 180.0


class Mismatch(Exception):
    pass


def f32(value: float) -> float:
    return float(np.float32(value))


def same(topic: str, field: str, found: Any, expected: Any) -> None:
    if isinstance(expected, float) and isinstance(found, float):
        equal = found == expected or (math.isnan(found) and math.isnan(expected))
    else:
        equal = found == expected
    if not equal:
        raise Mismatch(f"{topic}.{field}: expected {expected!r}, found {found!r}")


def commands(count: int, seed: int) -> list[tuple[float, float]]:
    rng = np.random.default_rng(seed)
    return [(float(v), float(w)) for v, w in rng.uniform((-0.05, -3.0), (0.15, 3.0), (count, 2))]


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--distro", default="humble")
    parser.add_argument("--steps", type=int, default=2000)
    parser.add_argument("--robot", default="e-puck")
    parser.add_argument("--world", default="seed-maze")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument(
        "--wait",
        type=float,
        default=10.0,
        help="seconds a topic that matched no writer may stay silent once the rest of a state "
        "arrived (a topic that matched one gets its message however late)",
    )
    parser.add_argument(
        "--reader-distro", default=None, help="decode the state with another distro's layouts"
    )
    parser.add_argument(
        "--cmd-vel",
        choices=("twist", "twist-stamped"),
        default=None,
        help="the /cmd_vel type to write (the distribution's by default)",
    )
    parser.add_argument(
        "--nan-at", type=int, default=-1, help="the command (from 0) sent with a NaN speed"
    )
    parser.add_argument(
        "--answer-from-second-state",
        action="store_true",
        help="leave the first reset state unanswered and wait for it again",
    )
    parser.add_argument(
        "--sleep-sim",
        type=float,
        default=0.0,
        help="after the reset state, wait for this much simulated time on /clock before the "
        "first command (a start-up sleep on simulated time)",
    )
    parser.add_argument(
        "--skip-answer-at",
        type=int,
        default=-1,
        help="leave the state of this step unanswered and wait for it again",
    )
    parser.add_argument(
        "--late-answer-at",
        type=int,
        default=-1,
        help="answer the state of this step only after the bridge has sent it again (a node "
        "slowed down for longer than the resend wait)",
    )
    parser.add_argument(
        "--timer-period",
        type=float,
        default=0.0,
        help="command on a timer of simulated time with this period in seconds, as rclpy's "
        "create_timer does with use_sim_time (ticks at each multiple of the period, missed ones "
        "skipped), instead of answering each state",
    )
    parser.add_argument(
        "--let-go-tick",
        type=int,
        default=-1,
        help="with --timer-period: let this tick (from 0) go without a command, as a node that "
        "finds a message of the tick not come yet skips it; the last command holds on",
    )
    args = parser.parse_args()
    global WAIT_S
    WAIT_S = args.wait

    from cyclonedds.core import Policy
    from cyclonedds.domain import Domain, DomainParticipant
    from cyclonedds.pub import DataWriter
    from cyclonedds.qos import Qos
    from cyclonedds.sub import DataReader
    from cyclonedds.topic import Topic

    discovery = network.discovery_from_environment()
    config = network.cyclone_config(discovery)
    domain = Domain(discovery.domain_id, config) if config else None
    participant = DomainParticipant(discovery.domain_id, qos=Qos(Policy.Userdata(b"enclave=/;")))
    distro = args.distro
    simulator = mazesim.Simulator(mazesim.load_world(args.world), robot=args.robot, seed=args.seed)
    expected_topics = state.StateTopics(simulator, distro)
    imu_noise = np.random.default_rng(
        np.random.SeedSequence(args.seed, spawn_key=(zlib.crc32(b"/imu"),))
    )
    imu_draws: dict[int, list[float]] = {}
    readers: dict[str, Any] = {}
    for topic in expected_topics.topics:
        kind = messages.idl_type(args.reader_distro or distro, topic.msgtype)
        readers[topic.name] = DataReader(
            participant,
            Topic(participant, "rt/" + topic.name.lstrip("/"), kind),
            qos=cyclone_qos(topic.qos),
        )
    static_type = messages.idl_type(distro, "tf2_msgs/msg/TFMessage")
    static_reader = DataReader(
        participant, Topic(participant, "rt/tf_static", static_type), qos=cyclone_qos(TF_STATIC)
    )
    jazzy = distro != "humble"
    stamped = args.cmd_vel == "twist-stamped" if args.cmd_vel else jazzy
    twist_name = "geometry_msgs/msg/TwistStamped" if stamped else "geometry_msgs/msg/Twist"
    twist_type = messages.idl_type(distro, twist_name)
    vector = messages.idl_type(distro, "geometry_msgs/msg/Vector3")
    inner = messages.idl_type(distro, "geometry_msgs/msg/Twist")
    header = messages.idl_type(distro, "std_msgs/msg/Header")
    time_type = messages.idl_type(distro, "builtin_interfaces/msg/Time")
    cmd_vel = DataWriter(
        participant, Topic(participant, "rt/cmd_vel", twist_type), qos=cyclone_qos(COMMAND)
    )
    _ = (SENSOR, TF, domain)

    graph_type = messages.idl_type(distro, "rmw_dds_common/msg/ParticipantEntitiesInfo")
    graph_reader = DataReader(
        participant,
        Topic(participant, "ros_discovery_info", graph_type),
        qos=cyclone_qos(TF_STATIC),
    )
    pending: dict[str, list[Any]] = {name: [] for name in readers}

    def check_graph() -> None:
        """The bridge is the ROS node ``mazesim_bridge``: its participant's USER_DATA, its
        entry on ros_discovery_info naming the GIDs of its endpoints, and (Jazzy) their hashes."""
        from cyclonedds.builtin import (
            BuiltinDataReader,
            BuiltinTopicDcpsParticipant,
            BuiltinTopicDcpsPublication,
        )

        nodes = {}
        for info in graph_reader.take(16):
            for node in info.node_entities_info_seq:
                nodes[node.node_name] = (info.gid, node)
        if "mazesim_bridge" not in nodes:
            raise Mismatch(f"ros_discovery_info names no mazesim_bridge: {sorted(nodes)}")
        gid, node = nodes["mazesim_bridge"]
        size = 24 if distro == "humble" else 16
        if len(gid.data) != size:
            raise Mismatch(f"expected a GID of {size} bytes; found {len(gid.data)}")
        bridge_key = uuid.UUID(bytes=bytes(gid.data[:16]))
        participants = BuiltinDataReader(participant, BuiltinTopicDcpsParticipant).take(64)
        data = [p.qos[Policy.Userdata] for p in participants if p.key == bridge_key]
        if not data or data[0] is None or data[0].data != b"enclave=/;":
            raise Mismatch(f"the bridge's participant USER_DATA is {data}, not enclave=/;")
        publications = {
            p.key: p
            for p in BuiltinDataReader(participant, BuiltinTopicDcpsPublication).take(256)
            if p.participant_key == bridge_key
        }
        writers = {uuid.UUID(bytes=bytes(g.data[:16])) for g in node.writer_gid_seq}
        named = {publications[key].topic_name for key in writers if key in publications}
        expected_names = {"rt/" + t.name.lstrip("/") for t in expected_topics.topics}
        if not expected_names | {"rt/tf_static"} <= named:
            raise Mismatch(f"the node's writer GIDs miss {sorted(expected_names - named)}")
        for key in writers & publications.keys():
            user = publications[key].qos[Policy.Userdata]
            text = user.data.decode() if user is not None else ""
            if jazzy and not text.startswith("typehash=RIHS01_"):
                raise Mismatch(f"{publications[key].topic_name} carries no type hash: {text!r}")
            if not jazzy and text:
                raise Mismatch(f"a Humble endpoint carries USER_DATA {text!r}")
        if len(node.reader_gid_seq) < 3:
            raise Mismatch(
                f"expected the bridge's 3 command readers; found {len(node.reader_gid_seq)}"
            )

    def check_map() -> None:
        """``/map``, read by a reader made now (after the bridge published it, as a Nav2 node
        started late): latched, the world's walls cell for cell."""
        from mazesim.ros2.occupancy import occupied_cells

        map_reader = DataReader(
            participant,
            Topic(participant, "rt/map", messages.idl_type(distro, "nav_msgs/msg/OccupancyGrid")),
            qos=cyclone_qos(TF_STATIC),
        )
        deadline = time.monotonic() + max(CEILING_S, WAIT_S)  # latched: it comes
        maps = map_reader.take(1)
        while not maps:
            if time.monotonic() > deadline:
                raise Mismatch(f"no /map within {max(CEILING_S, WAIT_S):.0f} s")
            time.sleep(0.01)
            maps = map_reader.take(1)
        grid = maps[0]
        cells, x0, y0 = occupied_cells(simulator.world)
        same("map", "frame_id", grid.header.frame_id, "map")
        same("map", "size", (grid.info.width, grid.info.height), cells.shape[::-1])
        same("map", "origin", (grid.info.origin.position.x, grid.info.origin.position.y), (x0, y0))
        same("map", "data", bytes(np.asarray(grid.data, dtype=np.int8)), cells.tobytes())

    control_step_s = simulator.control_step_ms / 1000.0
    #: Steps /clock ran on its own before the first command (None: to be read off /clock).
    idle: list[int | None] = [0]

    def expected_stamp() -> int | None:
        count = idle[0]
        return None if count is None else stamp_nanoseconds(simulator.time + count * control_step_s)

    def resent_before(stamp_ns: int | None) -> int:
        """How many states older than ``stamp_ns`` wait on ``/clock``: the bridge sent a state
        again while this driver was slow to answer it (lockstep's resend), so every topic holds
        that many messages of states already checked, ahead of the one awaited."""
        if stamp_ns is None:
            return 0
        clocks = (m.clock.sec * 10**9 + m.clock.nanosec for m in pending["/clock"])
        return sum(1 for clock in clocks if clock < stamp_ns)

    def collect(stamp_ns: int | None) -> dict[str, Any]:
        # A topic whose reader has matched a writer gets its message, however late (up to the
        # ceiling). Once the state has begun to arrive, a topic that matched no writer is silent
        # when --wait seconds have gone by with every matched one delivered (a writer of another
        # layout stays unmatched). Copies of states already checked (sent again) are read past.
        ceiling = time.monotonic() + max(CEILING_S, WAIT_S)
        quiet_since: float | None = None
        while True:
            for name, reader in readers.items():
                pending[name].extend(reader.take(16))
            stale = resent_before(stamp_ns)
            missing = sorted(name for name in readers if len(pending[name]) <= stale)
            if not missing:
                for name in readers:
                    del pending[name][:stale]
                break
            now = time.monotonic()
            arriving = len(missing) < len(readers)
            if not arriving or any(readers[name].get_matched_publications() for name in missing):
                quiet_since = None
            elif quiet_since is None:
                quiet_since = now
            if now > ceiling or (quiet_since is not None and now - quiet_since > WAIT_S):
                raise Mismatch(f"no message within {WAIT_S:.0f} s on {', '.join(missing)}")
            time.sleep(0.0002)
        got = {name: pending[name].pop(0) for name in readers}
        if stamp_ns is None:  # the first state after /clock ran on its own: how far it ran
            clock = got["/clock"].clock
            ahead = clock.sec * 10**9 + clock.nanosec - stamp_nanoseconds(simulator.time)
            idle[0] = round(ahead / (control_step_s * 1e9))
            stamp_ns = expected_stamp()
            if idle[0] * control_step_s < args.sleep_sim - 1e-9:
                raise Mismatch(f"/clock ran {idle[0]} steps, short of {args.sleep_sim} s")
        for name, message in got.items():
            stamp = message.clock if name == "/clock" else getattr(message, "header", None)
            if name == "/tf":
                stamp = message.transforms[0].header
            if stamp is not None:
                stamp = stamp.stamp if hasattr(stamp, "stamp") else stamp
                same(name, "stamp", stamp.sec * 1_000_000_000 + stamp.nanosec, stamp_ns)
        return got

    def check(got: dict[str, Any], step_seconds: float, before: tuple[float, float, float]) -> None:
        robot = simulator.robot
        frames = standard.sensor_frames(robot)
        distances = standard.ranges(simulator)
        for frame, distance in zip(frames, distances):
            message = got[f"/{frame.frame}"]
            same(frame.frame, "frame_id", message.header.frame_id, frame.frame)
            same(frame.frame, "range", message.range, f32(distance))
            same(frame.frame, "min_range", message.min_range, f32(frame.min_range))
            same(frame.frame, "max_range", message.max_range, f32(frame.max_range))
            same(frame.frame, "radiation_type", message.radiation_type, 1)
            if jazzy:
                same(frame.frame, "variance", message.variance, 0.0)
            elif hasattr(message, "variance"):
                raise Mismatch("a Humble Range has no variance")
        for index, reading in enumerate(simulator.ground_sensors().tolist()):
            name = expected_topics.ground_names[index]
            table = expected_topics.ground_tables[index]
            same(name, "range", got[f"/{name}"].range, f32(state.ground_distance(table, reading)))
        if expected_topics.has_scan:
            scan = got["/scan"]
            by_name = {frame.frame: d for frame, d in zip(frames, distances)}
            expected = [f32(r) for r in standard.scan_ranges(by_name)]
            same("scan", "ranges", list(scan.ranges), expected)
            same("scan", "frame_id", scan.header.frame_id, "laser_scanner")
            same("scan", "angle_min", scan.angle_min, f32(-math.radians(150)))
        x, y, yaw = simulator.pose
        odom = got["/odom"]
        same("odom", "child_frame_id", odom.child_frame_id, "base_link")
        same("odom", "frame_id", odom.header.frame_id, "odom")
        position = odom.pose.pose.position
        same("odom", "position", (position.x, position.y, position.z), (x, y, 0.0))
        q = odom.pose.pose.orientation
        same("odom", "orientation", (q.x, q.y, q.z, q.w), standard.yaw_quaternion(yaw))
        velocity = standard.body_velocity(before, (x, y, yaw), step_seconds)
        twist = odom.twist.twist
        same("odom", "twist", (twist.linear.x, twist.linear.y, twist.angular.z), tuple(velocity))
        imu = got["/imu"]
        q = imu.orientation
        same("imu", "orientation", (q.x, q.y, q.z, q.w), standard.yaw_quaternion(yaw))
        # Webots' noise: 0.3 % of each value, six normal draws a state from /imu's own stream
        # (a state sent again is the same message: no new draws).
        stamp = imu.header.stamp.sec * 10**9 + imu.header.stamp.nanosec
        if stamp not in imu_draws:
            imu_draws[stamp] = imu_noise.standard_normal(6).tolist()
        draws = imu_draws[stamp]
        turn = velocity.turn + abs(velocity.turn) * 0.003 * draws[2]
        same("imu", "angular_velocity.z", imu.angular_velocity.z, turn)
        same(
            "imu",
            "linear_acceleration.z",
            imu.linear_acceleration.z,
            9.81 + 9.81 * 0.003 * draws[5],
        )
        joints = got["/joint_states"]
        same("joint_states", "name", list(joints.name), list(state.WHEEL_JOINTS))
        encoders = simulator.encoders
        same("joint_states", "position", list(joints.position), list(encoders))
        turns = [
            (a - b) / step_seconds if step_seconds else 0.0 for a, b in zip(encoders, wheels[0])
        ]
        same("joint_states", "velocity", list(joints.velocity), turns)
        wheels[0] = encoders
        transform = got["/tf"].transforms[0]
        same("tf", "child", transform.child_frame_id, "base_link")
        t = transform.transform.translation
        same("tf", "translation", (t.x, t.y, t.z), (x, y, 0.0))
        same("sensors", "data", list(got["/sensors"].data), topics.sensors_values(simulator))
        same("pose", "data", list(got["/pose"].data), topics.pose_values(simulator))
        if "/sensor_data" in got:
            same(
                "sensor_data",
                "data",
                list(got["/sensor_data"].data),
                topics.sensor_data_values(simulator),
            )

    def drive_on_timer(period_s: float) -> int:
        """Commands as a node on a timer of simulated time does (rcl's timers: ticks at the
        multiples of the period from time 0, a tick fires at the first clock at or after it,
        missed ones skipped), the wheels kept between commands; checks every state."""
        period_ns = int(period_s * 1e9)
        fire_at, sent, kept, ticks = period_ns, 0, (0.0, 0.0), 0
        plan = commands(args.steps, args.seed)
        while simulator.steps < args.steps:
            now = stamp_nanoseconds(simulator.time)
            if now >= fire_at and ticks == args.let_go_tick:
                ticks += 1
                fire_at = (now // period_ns + 1) * period_ns
            elif now >= fire_at:
                ticks += 1
                linear, angular = plan[sent]
                sent += 1
                cmd_vel.write(
                    twist_type(
                        linear=vector(x=linear, y=0.0, z=0.0),
                        angular=vector(x=0.0, y=0.0, z=angular),
                    )
                )
                kept = standard.twist_wheel_speeds(linear, angular, simulator.robot)
                fire_at = (now // period_ns + 1) * period_ns
            before = simulator.pose
            simulator.step(*kept)
            check(collect(expected_stamp()), simulator.control_step_ms / 1000.0, before)
        return sent

    deadline = time.monotonic() + CEILING_S
    while not cmd_vel.get_matched_subscriptions():
        if time.monotonic() > deadline:
            print("driver: no bridge on /cmd_vel", file=sys.stderr)
            return 1
        time.sleep(0.01)
    wheels = [simulator.encoders]  # the encoders at the last state checked

    def check_published_once() -> None:
        """The graph, ``/map`` and ``/tf_static``. Checked once the first command is out (the
        timer's driver: before it), so their waits never hold the first answer back past the
        bridge's resend of the reset state."""
        check_graph()
        check_map()
        statics = static_reader.take(4)
        if not statics:
            raise Mismatch("no /tf_static")
        frames = {t.child_frame_id for t in statics[0].transforms}
        expected_frames = {f.frame for f in standard.sensor_frames(simulator.robot)}
        if not expected_frames <= frames:
            raise Mismatch(f"/tf_static lacks {sorted(expected_frames - frames)}")

    try:
        before = simulator.pose
        check(collect(stamp_nanoseconds(0.0)), 0.0, before)
        if args.answer_from_second_state:
            check(collect(stamp_nanoseconds(0.0)), 0.0, before)
        if args.sleep_sim > 0.0:
            # Sleeps on simulated time: waits for /clock, dropping what else comes.
            deadline = time.monotonic() + max(CEILING_S, WAIT_S)
            clock_ns = 0
            while clock_ns < args.sleep_sim * 1e9:
                for name, reader in readers.items():
                    for message in reader.take(64):
                        if name == "/clock":
                            clock_ns = max(
                                clock_ns, message.clock.sec * 10**9 + message.clock.nanosec
                            )
                if time.monotonic() > deadline:
                    raise Mismatch(f"/clock stayed at {clock_ns} ns for {CEILING_S:.0f} s")
                time.sleep(0.001)
            for name in pending:
                pending[name].clear()
            idle[0] = None
        robot = simulator.robot
        started = time.monotonic()
        kept = (0.0, 0.0)  # the wheel speeds a refused command keeps
        if args.timer_period > 0.0 or args.steps == 0:
            check_published_once()
        if args.timer_period > 0.0:
            sent = drive_on_timer(args.timer_period)
            print(f"driver: {sent} commands on a timer", flush=True)
        for index, (linear, angular) in enumerate(
            commands(0 if args.timer_period > 0.0 else args.steps, args.seed)
        ):
            nan = index == args.nan_at
            linear_v = vector(x=math.nan if nan else linear, y=0.0, z=0.0)
            angular_v = vector(x=0.0, y=0.0, z=angular)
            if stamped:
                now = stamp_nanoseconds(simulator.time)
                sample = twist_type(
                    header=header(
                        stamp=time_type(sec=now // 10**9, nanosec=now % 10**9), frame_id="base_link"
                    ),
                    twist=inner(linear=linear_v, angular=angular_v),
                )
            else:
                sample = twist_type(linear=linear_v, angular=angular_v)
            if index == args.late_answer_at:
                time.sleep(RESEND_S + 1.0)
            cmd_vel.write(sample)
            if index == 0:
                check_published_once()
            before = simulator.pose
            if not nan:
                kept = standard.twist_wheel_speeds(linear, angular, robot)
            simulator.step(*kept)
            got = collect(expected_stamp())
            check(got, simulator.control_step_ms / 1000.0, before)
            if index + 1 == args.skip_answer_at:  # the same state again, as it went out
                again = collect(expected_stamp())
                same("pose", "again", list(again["/pose"].data), topics.pose_values(simulator))
                same("sensors", "again", list(again["/sensors"].data), list(got["/sensors"].data))
        elapsed = time.monotonic() - started
    except Mismatch as error:
        print(f"driver: step {simulator.steps}: {error}", file=sys.stderr, flush=True)
        return 1
    print(
        f"driver: {args.steps} steps, every field equal ({args.steps / elapsed:.0f} steps/s)",
        flush=True,
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
