"""Lockstep control steps per second over ROS 1 (a benchmark, not a test: run it by hand).

It starts a ROS master on a free loopback port and the bridge (``mazesim ros bridge``, lockstep,
e-puck in seed-maze) as its own process; this process is the controller: it answers every
``sensors`` message with the avoid-collision rule on ``motor``, as the avoid-collision node does.
One control step is one full round trip: command to the bridge, one simulated step, state back.

    .venv/bin/python benches/ros_lockstep.py [--steps N] [--repeats K]

It prints the steps per second of each repeat and the best, and the in-process rate of the same
loop without ROS for comparison.
"""

from __future__ import annotations

import argparse
import sys
import threading
import time
import warnings

import mazesim
from mazesim.controllers import AvoidCollision
from mazesim.ros.local_master import LocalMaster


def in_process_rate(steps: int) -> float:
    """Control steps per second of the same controller loop without ROS."""
    simulator = mazesim.Simulator(mazesim.load_world("seed-maze"), robot="e-puck", seed=0)
    controller = AvoidCollision()
    started = time.perf_counter()
    for _ in range(steps):
        simulator.step(*controller(simulator.distance_sensors()))
        simulator.ground_sensors()
        simulator.pose  # noqa: B018 (read as the bridge does)
    return steps / (time.perf_counter() - started)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=5000, help="round trips per repeat")
    parser.add_argument("--repeats", type=int, default=3, help="number of repeats")
    args = parser.parse_args()

    import os

    with LocalMaster() as master:
        os.environ["ROS_MASTER_URI"] = master.uri
        os.environ["ROS_IP"] = "127.0.0.1"
        os.environ["ROS_HOME"] = master.home
        master.spawn(
            "bridge",
            [sys.executable, "-m", "mazesim", "ros", "bridge", "--mode", "lockstep"],
        )
        import rospy
        from std_msgs.msg import Float64MultiArray

        rospy.init_node("ros_lockstep_bench", disable_signals=True)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", SyntaxWarning)
            motor = rospy.Publisher("motor", Float64MultiArray, queue_size=None)
        controller = AvoidCollision()
        received = 0
        target = 0
        done = threading.Event()

        def on_sensors(message: Float64MultiArray) -> None:
            nonlocal received
            received += 1
            if received > target:
                done.set()
                return
            left, right = controller(message.data[:8])
            motor.publish(Float64MultiArray(data=[left, right]))

        deadline = time.monotonic() + 30.0
        while motor.get_num_connections() == 0:
            if time.monotonic() > deadline:
                raise SystemExit(f"the bridge did not subscribe motor; see {master.home}")
            time.sleep(0.01)
        rates = []
        for repeat in range(args.repeats):
            done.clear()
            received = 0
            target = args.steps
            if repeat == 0:
                # The latched first state arrives on subscription and starts the loop.
                rospy.Subscriber("sensors", Float64MultiArray, on_sensors, tcp_nodelay=True)
            else:
                motor.publish(Float64MultiArray(data=[0.0, 0.0]))
            started = time.perf_counter()
            if not done.wait(120.0):
                raise SystemExit(f"stalled after {received} round trips; see {master.home}")
            elapsed = time.perf_counter() - started
            rates.append(args.steps / elapsed)
            print(
                f"repeat {repeat + 1}: {args.steps} round trips in {elapsed:.3f} s, "
                f"{rates[-1]:,.0f} control steps/s"
            )
        rospy.signal_shutdown("benchmark done")
    print(
        f"best: {max(rates):,.0f} lockstep control steps/s over ROS "
        f"(in process, without ROS: {in_process_rate(args.steps):,.0f} steps/s)"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
