"""A lockstep driver of the ROS 2 bridge on a world of several robots, on Cyclone DDS's own
message decoding.

Run as a separate process: it sends each robot its own ``/<name>/cmd_vel`` every step (robot 0
drives straight on, the others turn on the spot), reads each robot's ``/<name>/pose`` and
``/<name>/ps0`` and the one ``/clock``, and checks them against an in-process simulator of the
same world driven by the same commands. It also checks that nobody reads the single robot's
``/cmd_vel``. With ``--frame-prefix`` (the bridge's too) it reads ``/tf`` as well: each step,
every robot's ``<name>/odom`` -> ``<name>/base_link`` at its pose, and ``<name>/ps0`` frames.
Exit code 0: every step equal (the last line is the final poses as JSON); 1: the first difference
or a missing message, on stderr.

    python swarm_driver.py --world WORLD.toml --steps 100 [--distro humble] [--frame-prefix]
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from typing import Any

import numpy as np

import mazesim
from mazesim.ros import standard
from mazesim.ros2 import messages, network
from mazesim.ros2.clock import stamp_nanoseconds
from mazesim.ros2.qos import CLOCK, COMMAND, SENSOR, TF, cyclone_qos
from mazesim.ros2.robots import RobotOf, robot_namespaces

#: Each robot's command: robot 0 forward, the others turning on the spot.
FORWARD = (0.1, 0.0)
TURN = (0.0, 2.0)


class Mismatch(Exception):
    pass


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--world", required=True)
    parser.add_argument("--steps", type=int, default=100)
    parser.add_argument("--distro", default="humble")
    # A ceiling that only bounds a hang: each wait ends on what it waits for.
    parser.add_argument("--wait", type=float, default=180.0)
    parser.add_argument("--frame-prefix", action="store_true")
    args = parser.parse_args()

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
    simulator = mazesim.Simulator(mazesim.load_world(args.world), seed=0)
    count = simulator.num_robots
    robots = [RobotOf(simulator, index) for index in range(count)]
    namespaces = robot_namespaces(simulator.robot_names)
    array = messages.idl_type(args.distro, "std_msgs/msg/Float64MultiArray")
    range_type = messages.idl_type(args.distro, "sensor_msgs/msg/Range")
    clock_type = messages.idl_type(args.distro, "rosgraph_msgs/msg/Clock")
    twist_type = messages.idl_type(args.distro, "geometry_msgs/msg/Twist")
    vector = messages.idl_type(args.distro, "geometry_msgs/msg/Vector3")
    tf_type = messages.idl_type(args.distro, "tf2_msgs/msg/TFMessage")
    prefixes = [ns[1:] + "/" if args.frame_prefix else "" for ns in namespaces]

    def reader(topic: str, kind: Any, qos: Any) -> Any:
        return DataReader(participant, Topic(participant, "rt" + topic, kind), qos=cyclone_qos(qos))

    readers: dict[str, Any] = {"/clock": reader("/clock", clock_type, CLOCK)}
    for ns in namespaces:
        readers[f"{ns}/pose"] = reader(f"{ns}/pose", array, SENSOR)
        readers[f"{ns}/ps0"] = reader(f"{ns}/ps0", range_type, SENSOR)
    tf_reader = reader("/tf", tf_type, TF) if args.frame_prefix else None
    transforms: list[Any] = []
    #: Transforms on /tf each step: one per robot, with a frame prefix.
    per_step = count if tf_reader is not None else 0
    writers = [
        DataWriter(
            participant, Topic(participant, f"rt{ns}/cmd_vel", twist_type), qos=cyclone_qos(COMMAND)
        )
        for ns in namespaces
    ]
    single = DataWriter(
        participant, Topic(participant, "rt/cmd_vel", twist_type), qos=cyclone_qos(COMMAND)
    )
    _ = domain
    pending: dict[str, list[Any]] = {name: [] for name in readers}

    def collect() -> dict[str, Any]:
        deadline = time.monotonic() + args.wait
        while True:
            for name, dds in readers.items():
                pending[name].extend(dds.take(16))
            if tf_reader is not None:
                transforms.extend(tf_reader.take(16))
            if all(pending[name] for name in readers) and len(transforms) >= per_step:
                got = {name: pending[name].pop(0) for name in readers}
                got["/tf"] = [transforms.pop(0) for _ in range(per_step)]
                return got
            if time.monotonic() > deadline:
                missing = sorted(name for name in readers if not pending[name]) or ["/tf"]
                raise Mismatch(f"no message within {args.wait:.0f} s on {', '.join(missing)}")
            time.sleep(0.0005)

    def check(got: dict[str, Any]) -> None:
        clock = got["/clock"].clock
        found = clock.sec * 10**9 + clock.nanosec
        if found != stamp_nanoseconds(simulator.time):
            raise Mismatch(f"/clock: expected {stamp_nanoseconds(simulator.time)}, found {found}")
        for ns, robot in zip(namespaces, robots):
            pose = list(got[f"{ns}/pose"].data)
            if pose != [*robot.pose, robot.time]:
                raise Mismatch(f"{ns}/pose: expected {[*robot.pose, robot.time]}, found {pose}")
            distance = float(np.float32(standard.ranges(robot, robot.robot)[0]))  # type: ignore[arg-type]
            if got[f"{ns}/ps0"].range != distance:
                raise Mismatch(f"{ns}/ps0: expected {distance}, found {got[f'{ns}/ps0'].range}")
        for ns, prefix in zip(namespaces, prefixes):
            frame = got[f"{ns}/ps0"].header.frame_id
            if frame != prefix + "ps0":
                raise Mismatch(f"{ns}/ps0: expected frame {prefix}ps0, found {frame}")
        by_child = {
            sample.transforms[0].child_frame_id: sample.transforms[0] for sample in got["/tf"]
        }
        for robot, prefix in zip(robots if per_step else [], prefixes):
            transform = by_child.get(prefix + "base_link")
            if transform is None or transform.header.frame_id != prefix + "odom":
                raise Mismatch(f"/tf: no {prefix}odom -> {prefix}base_link in {sorted(by_child)}")
            place = transform.transform.translation
            if [place.x, place.y] != list(robot.pose[:2]):
                raise Mismatch(f"/tf {prefix}base_link: expected {robot.pose[:2]}, found {place}")

    deadline = time.monotonic() + args.wait
    while not all(writer.get_matched_subscriptions() for writer in writers):
        if time.monotonic() > deadline:
            print("swarm driver: no bridge on every robot's cmd_vel", file=sys.stderr)
            return 1
        time.sleep(0.01)
    try:
        check(collect())
        if single.get_matched_subscriptions():
            raise Mismatch("the bridge reads /cmd_vel outside the robots' namespaces")
        wheels = np.zeros((count, 2))
        for _ in range(args.steps):
            for index, writer in enumerate(writers):
                linear, angular = FORWARD if index == 0 else TURN
                writer.write(
                    twist_type(
                        linear=vector(x=linear, y=0.0, z=0.0),
                        angular=vector(x=0.0, y=0.0, z=angular),
                    )
                )
                wheels[index] = standard.twist_wheel_speeds(linear, angular, robots[index].robot)
            simulator.step_robots(wheels)
            check(collect())
    except Mismatch as error:
        print(f"swarm driver: step {simulator.steps}: {error}", file=sys.stderr, flush=True)
        return 1
    where = " and on /tf" if tf_reader is not None else ""
    print(
        f"swarm driver: {args.steps} steps, every robot equal on its own topics{where}", flush=True
    )
    print(json.dumps({ns: list(robot.pose) for ns, robot in zip(namespaces, robots)}), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
