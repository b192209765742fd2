"""What the ROS tests share: whether ROS 1 can be used here, and the mark that skips without it."""

from __future__ import annotations

import shutil
import subprocess
import sys

import pytest

__all__ = ["needs_ros", "ros_available"]


def ros_available() -> bool:
    """Whether roscore, roslaunch, rosbag and the Python ROS modules the bridge needs are
    installed."""
    if any(shutil.which(tool) is None for tool in ("roscore", "roslaunch", "rosbag")):
        return False
    check = subprocess.run(
        [sys.executable, "-c", "import rospy, rosbag, std_msgs.msg, rosgraph_msgs.msg"],
        capture_output=True,
        check=False,
    )
    return check.returncode == 0


#: Skips a test where ROS 1 is missing, saying how to install it.
needs_ros = pytest.mark.skipif(
    not ros_available(), reason="ROS 1 is not installed (run 'make ros-deps')"
)
