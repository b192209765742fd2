"""ROS launch: the report's chapter 4 set-up over a real ROS 1 master, started with roslaunch.

A private master (``roscore``) starts on a free loopback port; ``roslaunch mazesim_ros
learning.launch`` then starts the bridge (the ``seed`` robot in seed-maze, lockstep) and the
perform-learning node (Alg. 5 with the shipped hierarchical tables). The bridge stops at the goal,
and the launch with it; the script prints the bridge's goal line and stops the master.

It needs ROS 1 (``make ros-deps`` on Debian or Ubuntu) and this repository's ``ros/`` folder.
The master gives every process it starts this interpreter's folder first on ``PATH``, so the node
scripts (``#!/usr/bin/env python3``) run with the Python that runs this script::

    .venv/bin/python examples/ros_launch.py [SEED]
"""

import re
import sys
from pathlib import Path

from mazesim.ros.local_master import LocalMaster

ROS_PACKAGE_PATH = Path(__file__).resolve().parent.parent / "ros"  # holds mazesim_ros
seed = sys.argv[1] if len(sys.argv) > 1 else "0"

with LocalMaster() as master:  # roscore -p PORT on 127.0.0.1; stopped at the end
    print(f"master at {master.uri}")
    launch = master.spawn(
        "roslaunch",
        ["roslaunch", "mazesim_ros", "learning.launch", f"seed:={seed}"],
        env={"ROS_PACKAGE_PATH": str(ROS_PACKAGE_PATH)},
    )
    status = launch.wait(timeout=120)
    log = Path(master.log_path("roslaunch")).read_text()

goal = re.search(r"goal reached at step \d+[^\n]*", log)
if status != 0 or goal is None:
    sys.exit(f"roslaunch ended with status {status} before the goal; its log:\n{log}")
print(f"roslaunch learning.launch seed:={seed}: {goal[0]}")
