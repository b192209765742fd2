"""``mazesim ros demo``: bridge + a controller node in lockstep on a private master, in a bag.

The demo starts a master on a free loopback port (so it never disturbs a running ROS system),
the bridge in lockstep with a ``duration``, writing its own bag (every step by construction, see
:mod:`mazesim.ros.bag`), and a controller node:

- ``hrl`` (the default): the ``seed`` robot and the perform-learning node (the report's Alg. 5,
  the hierarchical policy shipped for ``seed-maze``); the bridge stops at the goal, or after
  ``duration`` if the robot does not get there;
- ``avoid-collision``: the e-puck and the avoid-collision node (Listing 3.2), for ``duration``.

When the bridge has stopped it stops the graph, reads the bag back and plots the trajectory
recorded on ``pose``.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from typing import Any, TextIO

import numpy as np

import mazesim
from mazesim._paths import make_output_folder
from mazesim.errors import (
    InvalidArgumentError,
    MazesimError,
    PolicyFormatError,
    _known_name,
    _shown,
)
from mazesim.ros.bridge import refuse_several_robots
from mazesim.ros.local_master import LocalMaster
from mazesim.ros.topics import demo_robot

__all__ = [
    "CONTROLLERS",
    "goal_step",
    "read_poses",
    "run_demo",
]

#: The demo's controller nodes.
CONTROLLERS = ("hrl", "avoid-collision")
#: Wall-clock seconds the demo allows per simulated second before it gives up.
WALL_SECONDS_PER_SIMULATED_SECOND = 2.0


def read_poses(bag_path: str) -> Any:
    """Reads the ``/pose`` messages of a bag: an array of shape (N, 4), rows [x, y, yaw, time]."""
    from mazesim.replay.ros_bag import read_topics

    rows = read_topics(bag_path, ("/pose",))["/pose"]
    return np.array(rows, dtype=np.float64).reshape(-1, 4)


def goal_step(world: Any, poses: Any) -> int | None:
    """The first row of ``poses`` (``[x, y, yaw, time]``) inside the world's goal disc, if any."""
    if world.goal is None or len(poses) == 0:
        return None
    goal_x, goal_y, radius = world.goal
    inside = np.flatnonzero(np.hypot(poses[:, 0] - goal_x, poses[:, 1] - goal_y) <= radius)
    return int(inside[0]) if inside.size else None


def run_demo(args: argparse.Namespace, out: TextIO) -> int:
    """Runs the demo (``args``: controller, world, seed, seconds, out); see the module's text."""
    from mazesim.plotting import save_trajectory_png

    controller = getattr(args, "controller", "hrl")
    _known_name(controller, "the controller", CONTROLLERS)
    hrl = controller == "hrl"
    world = mazesim.load_world(args.world)  # fail early on a bad world
    refuse_several_robots(world)
    if hrl:
        from mazesim.ros.perform_learning import load_policy

        # The node drives with the shipped tables: their higher level knows one world only.
        try:
            load_policy(None).check_world(world)
        except PolicyFormatError as error:
            raise InvalidArgumentError(
                f"{error}; the hrl demo drives with the tables shipped for seed-maze "
                f"(or run --controller avoid-collision in {_shown(world.name)})"
            ) from None
    robot = demo_robot(controller, getattr(args, "robot", None))
    out_dir = os.path.abspath(args.out)
    make_output_folder(out_dir)
    bag_path = os.path.join(out_dir, "maze.bag")
    for stale in (bag_path, bag_path + ".active"):
        if os.path.exists(stale):
            os.remove(stale)
    mazesim_command = [sys.executable, "-m", "mazesim", "ros"]
    started = time.monotonic()
    master = LocalMaster(home=os.path.join(out_dir, "logs"))
    master.start()
    try:
        master.set_param("/use_sim_time", False)
        bridge = master.spawn(
            "bridge",
            [
                *mazesim_command,
                "bridge",
                "--world",
                args.world,
                "--robot",
                robot,
                "--seed",
                str(args.seed),
                "--mode",
                "lockstep",
                "--duration",
                repr(args.seconds),
                *(["--stop-at-goal"] if hrl else []),
                "--bag",
                bag_path,
                "__name:=bridge",
            ],
        )
        node = "perform-learning" if hrl else "avoid-collision"
        master.spawn(node, [*mazesim_command, node, "--wait-for-subscribers", "1"])
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
    finally:
        left_behind = master.close()
    wall_clock = time.monotonic() - started
    for pid, command in left_behind:
        out.write(f"warning: ended a process left behind: {pid} {command}\n")

    poses = read_poses(bag_path)
    if len(poses) == 0:
        raise MazesimError(f"the bag {bag_path} holds no /pose message")
    # Steps are counted by simulated time.
    gaps = np.diff(poses[:, 3])
    step_s = float(gaps[gaps > 0].min()) if np.any(gaps > 0) else math.nan
    steps = round(poses[-1, 3] / step_s) if len(poses) > 1 else 0
    arrived = goal_step(world, poses)
    if world.goal is None:
        goal = "none in this world"
    elif arrived is None:
        goal = f"not reached in {poses[-1, 3]:.2f} s"
    else:
        at = round(poses[arrived, 3] / step_s) if arrived > 0 else 0
        goal = f"reached at step {at} ({poses[arrived, 3]:.2f} s simulated)"
    name = "hierarchical policy (perform-learning)" if hrl else "avoid-collision"
    picture = os.path.join(out_dir, "trajectory.png")
    outcome = ""
    if hrl:
        outcome = ", goal reached" if arrived is not None else ", goal not reached"
    save_trajectory_png(
        world,
        poses[:, 0],
        poses[:, 1],
        picture,
        title=f"{world.name} over ROS: {controller} in lockstep, {poses[-1, 3]:.1f} s{outcome}",
    )
    step_ms = 1000.0 * step_s
    views = _write_views(args, bag_path, world, robot, controller, step_ms)
    out.write(
        f"world              {world.name} (robot {robot}, seed {args.seed}, lockstep)\n"
        f"controller         {name}\n"
        f"simulated time     {poses[-1, 3]:.2f} s ({steps} control steps of {step_ms:.0f} ms "
        f"over ROS)\n"
        f"goal               {goal}\n"
        f"wall-clock time    {wall_clock:.2f} s (master and nodes included)\n"
        f"bag                {bag_path} ({len(poses)} pose messages)\n"
        f"trajectory         {picture}\n"
        f"logs               {master.home}\n"
        f"play it back with  rosbag info {bag_path}; rosbag play {bag_path}\n"
    )
    for view in views:
        out.write(f"wrote              {view}\n")
    return 0


def _write_views(
    args: argparse.Namespace, bag_path: str, world: Any, robot: str, controller: str, step_ms: float
) -> list[str]:
    """The ``--html``, ``--video`` and ``--record`` outputs, from the bag."""
    from mazesim.replay.views import recording_requested, write_views

    if not recording_requested(args) or not math.isfinite(step_ms):
        return []
    from mazesim.replay.ros_bag import run_from_bag

    profile = mazesim.RobotProfile.load(robot)
    run = run_from_bag(bag_path, world, profile, controller, args.seed, step_ms)
    return write_views(args, run, f"{world.name} over ROS: {controller}, seed {args.seed}")
