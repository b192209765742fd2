"""The ROS 1 bridge's reset services, ``/gazebo/reset_simulation`` and ``/gazebo/reset_world``
(``std_srvs/Empty``, as Gazebo's node offers them, and Stage's ``/reset_positions``), called by a
rospy node as Gazebo's users call them: ``rospy.wait_for_service``, then a ``ServiceProxy``."""

from __future__ import annotations

import subprocess
import sys

from mazesim.ros.local_master import LocalMaster
from reset_runs import STEPS, client_run
from ros_support import needs_ros, spawn_bridge

CLIENT = f"""
import threading, time
import rospy
from std_msgs.msg import Float64MultiArray
from std_srvs.srv import Empty

rospy.init_node('reset_caller', disable_signals=True)
seen, ready = [], threading.Condition()
def on_pose(message):
    with ready:
        seen.append(list(message.data))
        ready.notify_all()
rospy.Subscriber('pose', Float64MultiArray, on_pose)
motor = rospy.Publisher('motor', Float64MultiArray, queue_size={STEPS})
ceiling = time.monotonic() + 300
while motor.get_num_connections() == 0:
    assert time.monotonic() < ceiling, 'no bridge'
    time.sleep(0.01)

def pose_at(step):
    # The first pose of simulated time step * 32 ms since the wait began (a state sent again
    # after 5 s is the same message).
    with ready:
        while True:
            for pose in seen:
                if abs(pose[3] - step * 0.032) < 1e-9:
                    seen.clear()
                    return pose
            assert time.monotonic() < ceiling, ('no pose of step', step, seen)
            ready.wait(0.1)

def send(left, right):
    motor.publish(Float64MultiArray(data=[left, right]))

# Stage's /reset_positions too, as nodes written for stage_ros wait for it.
for name in ('/gazebo/reset_simulation', '/gazebo/reset_world', '/reset_positions'):
    rospy.wait_for_service(name, timeout=300)
def reset(name):
    rospy.ServiceProxy('/gazebo/' + name, Empty)()
"""


@needs_ros
def test_a_rospy_client_resets_the_lockstep_run_and_the_world(master: LocalMaster) -> None:
    bridge = spawn_bridge(master, "--duration", str(2 * STEPS * 0.032))
    result = subprocess.run(
        [sys.executable, "-c", CLIENT + client_run() + "rospy.signal_shutdown('done')\n"],
        env=master.env,
        capture_output=True,
        text=True,
        timeout=600,  # a ceiling for a hang: the client ends on the messages it waits for
        check=False,
    )
    assert result.returncode == 0, result.stdout + result.stderr
    assert "reset_simulation: the run again, bit for bit" in result.stdout
    assert "reset_world: at the start, the clock going on" in result.stdout
    assert bridge.wait(timeout=600) == 0
