"""``mazesim ros demo``: bridge + avoid-collision in lockstep on a private master, in a bag.

The demo starts a master on a free loopback port (so it never disturbs a running ROS system),
``rosbag record``, the bridge in lockstep with a ``duration`` and the avoid-collision node; when the
bridge has simulated that long it stops the graph, reads the bag back and plots the trajectory
recorded on ``pose``.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from typing import Any, TextIO

import numpy as np

import mazesim
from mazesim.errors import MazesimError, MissingDependencyError
from mazesim.ros.local_master import LocalMaster

__all__ = ["RECORDED_TOPICS", "read_poses", "run_demo"]

#: The topics the demo records.
RECORDED_TOPICS = ("/clock", "/pose", "/sensors", "/motor")
#: Wall-clock seconds the demo allows per simulated second before it gives up.
WALL_SECONDS_PER_SIMULATED_SECOND = 2.0


def read_poses(bag_path: str) -> Any:
    """Reads the ``/pose`` messages of a bag: an array of shape (N, 4), rows [x, y, yaw, time]."""
    try:
        import rosbag
    except ImportError as error:
        raise MissingDependencyError(
            f"reading a bag needs ROS 1's rosbag package ({error}); on Debian 'make ros-deps'"
        ) from error
    with rosbag.Bag(bag_path) as bag:
        rows = [list(message.data) for _, message, _ in bag.read_messages(topics=["/pose"])]
    return np.array(rows, dtype=np.float64).reshape(-1, 4)


def run_demo(args: argparse.Namespace, out: TextIO) -> int:
    """Runs the demo; see the module's description."""
    from mazesim.plotting import save_trajectory_png

    world = mazesim.load_world(args.world)  # fail early on a bad world
    out_dir = os.path.abspath(args.out)
    os.makedirs(out_dir, exist_ok=True)
    bag_path = os.path.join(out_dir, "maze.bag")
    if os.path.exists(bag_path):
        os.remove(bag_path)
    mazesim_command = [sys.executable, "-m", "mazesim", "ros"]
    started = time.monotonic()
    master = LocalMaster(home=os.path.join(out_dir, "logs"))
    master.start()
    try:
        # The recorder stamps messages with the wall clock: on simulated time it would wait for a
        # valid (non-zero) /clock and miss the first steps of a lockstep run.
        master.set_param("/use_sim_time", False)
        bridge = master.spawn(
            "bridge",
            [
                *mazesim_command,
                "bridge",
                "--world",
                args.world,
                "--seed",
                str(args.seed),
                "--mode",
                "lockstep",
                "--duration",
                repr(args.seconds),
                "__name:=bridge",
            ],
        )
        recorder = master.spawn(
            "rosbag-record",
            ["rosbag", "record", "--quiet", "-O", bag_path, *RECORDED_TOPICS, "__name:=recorder"],
        )
        # Nothing moves before the recorder listens: the bridge steps on the controller's first
        # command, and the controller waits for both the bridge and the recorder on /motor.
        master.wait_for_connections("/bridge", ["/clock", "/pose", "/sensors"], "/recorder")
        master.spawn(
            "avoid-collision", [*mazesim_command, "avoid-collision", "--wait-for-subscribers", "2"]
        )
        deadline = time.monotonic() + 30.0 + WALL_SECONDS_PER_SIMULATED_SECOND * args.seconds
        while bridge.poll() is None and time.monotonic() < deadline:
            time.sleep(0.05)
        if bridge.poll() is None:
            raise MazesimError(
                f"the bridge did not finish {args.seconds:g} simulated seconds in time; "
                f"see the logs in {master.home}"
            )
        if bridge.returncode != 0:
            raise MazesimError(
                f"the bridge failed (exit code {bridge.returncode}); "
                f"see {master.log_path('bridge')}"
            )
        time.sleep(0.3)  # let the recorder read the last messages off its sockets
        LocalMaster.stop_process(recorder)
    finally:
        left_behind = master.close()
    wall_clock = time.monotonic() - started
    for pid, command in left_behind:
        out.write(f"warning: ended a process left behind: {pid} {command}\n")

    poses = read_poses(bag_path)
    if len(poses) == 0:
        raise MazesimError(f"the bag {bag_path} holds no /pose message")
    picture = os.path.join(out_dir, "trajectory.png")
    save_trajectory_png(
        world,
        poses[:, 0],
        poses[:, 1],
        picture,
        title=f"{world.name} over ROS: avoid-collision in lockstep, {poses[-1, 3]:.0f} s",
    )
    steps = len(poses) - 1
    out.write(
        f"world              {world.name} (robot e-puck, seed {args.seed}, lockstep)\n"
        f"simulated time     {poses[-1, 3]:.2f} s ({steps} control steps over ROS)\n"
        f"wall-clock time    {wall_clock:.2f} s (master, nodes and recorder included)\n"
        f"bag                {bag_path} ({len(poses)} pose messages)\n"
        f"trajectory         {picture}\n"
        f"logs               {master.home}\n"
        f"play it back with  rosbag info {bag_path}; rosbag play {bag_path}\n"
    )
    return 0
