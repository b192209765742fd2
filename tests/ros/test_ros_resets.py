"""The ROS 1 bridge's reset services, ``/gazebo/reset_simulation`` and ``/gazebo/reset_world``
(``std_srvs/Empty``, as Gazebo's node offers them), called by a rospy node as Gazebo's users
call them: ``rospy.wait_for_service``, then a ``ServiceProxy``."""

from __future__ import annotations

import subprocess
import sys

from mazesim.ros.local_master import LocalMaster
from ros_support import needs_ros, spawn_bridge

STEPS = 12

CLIENT = f"""
import threading, time
import numpy as np
import rospy
import mazesim
from mazesim.ros import topics
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

rng = np.random.default_rng(5)
speeds = rng.uniform(-6.0, 6.28, ({STEPS}, 2)).tolist()
def drive(first_step):
    out = []
    for index, (left, right) in enumerate(speeds):
        motor.publish(Float64MultiArray(data=[left, right]))
        out.append(pose_at(first_step + index + 1))
    return out

start = pose_at(0)
first = drive(0)
sim = mazesim.Simulator(mazesim.load_world('seed-maze'), robot='e-puck', seed=0)
expected = []
for left, right in speeds:
    sim.step(left, right)
    expected.append(topics.pose_values(sim))
assert first == expected, (first, expected)
for name in ('/gazebo/reset_simulation', '/gazebo/reset_world'):
    rospy.wait_for_service(name, timeout=300)
rospy.ServiceProxy('/gazebo/reset_simulation', Empty)()
assert pose_at(0) == start
again = drive(0)
assert again == first, (again, first)
print('reset_simulation: the run again, bit for bit')
rospy.ServiceProxy('/gazebo/reset_world', Empty)()
after = pose_at({STEPS})
assert after[:3] == start[:3], (after, start)
moved = drive({STEPS})
assert moved[-1][3] > after[3] and moved[-1][:2] != after[:2]
print('reset_world: at the start, the clock going on')
rospy.signal_shutdown('done')
"""


@needs_ros
def test_a_rospy_client_resets_the_lockstep_run_and_the_world(master: LocalMaster) -> None:
    bridge = spawn_bridge(master, "--duration", str(2 * STEPS * 0.032))
    result = subprocess.run(
        [sys.executable, "-c", CLIENT],
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
