"""`rosbag play` of recorded twists into the lockstep ROS 1 bridge: one step per twist, when it
waits for the bridge's connection and plays the command topic only."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from mazesim.ros.local_master import LocalMaster
from ros_support import needs_ros, spawn_bridge

# A bag as `rosbag record -a` leaves it: the twists on /cmd_vel and the bridge's own /pose.
MAKE_BAG = """
import sys
import rosbag, rospy
from geometry_msgs.msg import Twist
from std_msgs.msg import Float64MultiArray
with rosbag.Bag(sys.argv[1], 'w') as bag:
    for i in range(40):
        twist = Twist()
        twist.angular.z = (i + 1) / 100
        bag.write('/cmd_vel', twist, rospy.Time(1000 + i * 0.1))
        bag.write('/pose', Float64MultiArray(data=[i]), rospy.Time(1000 + i * 0.1))
"""


@needs_ros
def test_rosbag_play_of_recorded_twists_steps_once_per_twist(
    master: LocalMaster, tmp_path: Path
) -> None:
    # rosbag play publishes once its -d delay is over, connected or not, and a twist sent
    # before the bridge's connection is lost; --wait-for-subscribers waits for a subscriber of
    # every topic it plays (forever for /pose, which nobody reads), so --topics /cmd_vel too.
    bag = tmp_path / "run.bag"
    made = subprocess.run(
        [sys.executable, "-c", MAKE_BAG, str(bag)],
        env=master.env,
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )
    assert made.returncode == 0, made.stderr
    bridge = spawn_bridge(master, "--duration", str(40 * 0.032))
    play = subprocess.run(
        ["rosbag", "play", "-q", str(bag), "--wait-for-subscribers", "--topics", "/cmd_vel"],
        env=master.env,
        capture_output=True,
        text=True,
        timeout=600,  # a ceiling for a hang: play ends when its 40 twists went out
        check=False,
    )
    assert play.returncode == 0, play.stdout + play.stderr
    assert bridge.wait(timeout=600) == 0  # it stops at its 40th step: every twist took one
    log = Path(master.log_path("bridge")).read_text(encoding="utf-8", errors="replace")
    assert "stopped: 40 steps" in log
