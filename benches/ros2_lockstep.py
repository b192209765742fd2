"""Lockstep control steps per second over ROS 2 (DDS), with the full topic set, beside ROS 1's
(a benchmark, not a test: run it by hand).

The bridge (``mazesim ros2 bridge``, lockstep, e-puck in seed-maze: 8 Range, 3 ground Range,
LaserScan, Odometry, TF, sensors, pose and Clock each step) runs as its own process; this process
is the controller, a ROS 2 node subscribed to every state topic (so the whole set goes over the
wire each step) answering every ``/sensors`` message with the avoid-collision rule on ``/motor``.
One control step is one full round trip. Then, where the time goes: the bridge's own work per
step (simulate, encode every message, hand them to DDS with no reader) measured in this process.
Last, in the same sitting, where ROS 1 is installed, ``benches/ros_lockstep.py`` measures the
ROS 1 bridge the same way.

    .venv/bin/python benches/ros2_lockstep.py [--steps N] [--repeats K] [--distro humble|jazzy]
        [--goal STEPS_PER_S] [--no-ros1]

It exits 1 when the best repeat is below the goal (2,000 lockstep steps/s by default).
"""

from __future__ import annotations

import argparse
import importlib.util
import subprocess
import sys
import time
from pathlib import Path

import mazesim
from mazesim.controllers import AvoidCollision
from mazesim.ros2 import cdr
from mazesim.ros2.node import Node
from mazesim.ros2.qos import COMMAND, SENSOR
from mazesim.ros2.state import StateTopics

FLOAT64_ARRAY = "std_msgs/msg/Float64MultiArray"
#: The issue's goal for full-topic-set lockstep round trips over ROS 2, in steps per second.
GOAL = 2000


def ros2_rates(steps: int, repeats: int, distro: str) -> list[float]:
    """Round trips per second of each repeat against a bridge process."""
    bridge = subprocess.Popen(
        [sys.executable, "-m", "mazesim", "ros2", "bridge", "--ros-distro", distro],
        stderr=subprocess.DEVNULL,
    )
    try:
        node = Node("ros2_lockstep_bench", distro)
        # Every state topic is subscribed, so the bridge delivers the full set each step.
        simulator = mazesim.Simulator(mazesim.load_world("seed-maze"), robot="e-puck", seed=0)
        others = [
            node.reader(topic.name, topic.msgtype, topic.qos)
            for topic in StateTopics(simulator, distro).topics
            if topic.name != "/sensors"
        ]
        sensors = node.reader("/sensors", FLOAT64_ARRAY, SENSOR)
        motor = node.writer("/motor", FLOAT64_ARRAY, COMMAND)
        node.announce()
        controller = AvoidCollision()
        from cyclonedds.core import InstanceState, ReadCondition, SampleState, ViewState, WaitSet

        waitset = WaitSet(node.participant)
        mask = SampleState.Any | ViewState.Any | InstanceState.Any
        waitset.attach(ReadCondition(sensors.dds, mask))

        def answer(timeout: float) -> None:
            deadline = time.monotonic() + timeout
            while True:
                waitset.wait(100_000_000)
                received = sensors.take()
                for reader in others:
                    reader.take()
                if received:
                    values = cdr.decode_float64_array(received[-1])
                    left, right = controller(values[:8])
                    motor.publish(cdr.encode_float64_multi_array((), [left, right]))
                    return
                if time.monotonic() > deadline:
                    raise SystemExit("the bridge did not answer")

        answer(60.0)  # the reset state, once the bridge has seen the motor writer
        rates = []
        for repeat in range(repeats):
            started = time.perf_counter()
            for _ in range(steps):
                answer(30.0)
            elapsed = time.perf_counter() - started
            rates.append(steps / elapsed)
            print(f"ROS 2 {distro}, repeat {repeat + 1}: {steps} round trips in {elapsed:.3f} s, "
                  f"{rates[-1]:,.0f} control steps/s", flush=True)  # fmt: skip
        node.close()
        return rates
    finally:
        bridge.terminate()
        bridge.wait(10)


def bridge_costs(steps: int, distro: str) -> dict[str, float]:
    """Microseconds per step of the bridge's own work, measured in this process."""
    simulator = mazesim.Simulator(mazesim.load_world("seed-maze"), robot="e-puck", seed=0)
    state = StateTopics(simulator, distro)
    node = Node("ros2_cost_bench", distro)
    writers = [node.writer(t.name, t.msgtype, t.qos) for t in state.topics]
    controller = AvoidCollision()
    timings = {"simulate": 0.0, "encode": 0.0, "write": 0.0}
    for step in range(steps):
        started = time.perf_counter()
        simulator.step(*controller(simulator.distance_sensors()))
        encoding = time.perf_counter()
        encoded = state.messages(cdr.stamp_of(step + 1), 0.032)
        writing = time.perf_counter()
        for writer, data in zip(writers, encoded):
            writer.publish(data)
        done = time.perf_counter()
        timings["simulate"] += encoding - started
        timings["encode"] += writing - encoding
        timings["write"] += done - writing
    node.close()
    return {name: total / steps * 1e6 for name, total in timings.items()}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=5000, help="round trips per repeat")
    parser.add_argument("--repeats", type=int, default=3, help="number of repeats")
    parser.add_argument("--distro", default="humble", choices=("humble", "jazzy"))
    parser.add_argument(
        "--goal", type=float, default=GOAL, help=f"steps/s the best repeat must reach ({GOAL:,})"
    )
    parser.add_argument("--no-ros1", action="store_true", help="leave out the ROS 1 comparison")
    args = parser.parse_args()
    rates = ros2_rates(args.steps, args.repeats, args.distro)
    best = max(rates)
    print(f"best: {best:,.0f} lockstep control steps/s over ROS 2 ({args.distro}, DDS)")
    costs = bridge_costs(args.steps, args.distro)
    print("bridge per step: " + ", ".join(f"{k} {v:.0f} µs" for k, v in costs.items()))
    if not args.no_ros1 and importlib.util.find_spec("rospy") is not None:
        ros1 = Path(__file__).with_name("ros_lockstep.py")
        subprocess.run(
            [sys.executable, str(ros1), "--steps", str(args.steps), "--repeats", str(args.repeats)],
            check=False,
        )
    elif not args.no_ros1:
        print("ROS 1 is not installed here: make ros-deps to compare with the ROS 1 bridge")
    if best < args.goal:
        print(f"below the goal: {best:,.0f} < {args.goal:,.0f} lockstep steps/s")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
