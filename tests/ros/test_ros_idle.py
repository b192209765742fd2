"""The ROS 1 bridge when nobody answers: a bridge no controller drives gives up after its idle
timeout, and a controller that waits for simulated time inside a callback (tf2's
``lookup_transform`` with a timeout sleeps on a ``rospy.Rate`` of simulated time while the
transform of a scan's stamp has not come) gets it, without ``/tf`` going out twice at one stamp
(tf2 warns of that as ``TF_REPEATED_DATA``)."""

from __future__ import annotations

import json
import subprocess
import sys
import time
from pathlib import Path

import pytest

import mazesim
from mazesim.ros import topics
from mazesim.ros.local_master import LocalMaster
from mazesim.ros.lockstep import IDLE_EXIT_STATUS
from ros_support import needs_ros, spawn_bridge

#: A ceiling for a hang: each process below ends on what it waits for, never on a time.
CEILING_S = 300.0


def _bridge_exit(bridge: subprocess.Popen[bytes]) -> int:
    return bridge.wait(timeout=CEILING_S)


def _run_node(master: LocalMaster, script: str, *args: str) -> subprocess.CompletedProcess[str]:
    """Runs a rospy node's ``script`` with ``args`` against ``master``; checks that it succeeded."""
    node = subprocess.run(
        [sys.executable, "-c", script, *args],
        env=master.env,
        capture_output=True,
        text=True,
        timeout=CEILING_S,
        check=False,
    )
    assert node.returncode == 0, node.stderr
    return node


@needs_ros
@pytest.mark.parametrize("mode", ["lockstep", "realtime"])
def test_a_bridge_no_controller_connects_to_gives_up_after_its_idle_timeout(
    master: LocalMaster, mode: str
) -> None:
    # Before, a bridge whose controller never started ran (and in realtime stepped) for ever.
    started = time.monotonic()
    bridge = spawn_bridge(master, "--mode", mode, "--idle-timeout", "1.5")
    assert _bridge_exit(bridge) == IDLE_EXIT_STATUS
    assert time.monotonic() - started >= 1.5
    log = Path(master.log_path("bridge")).read_text(encoding="utf-8")
    assert "no command came and no node had a command topic open for 1.5 s; giving up" in log


CONNECTED = """
import sys, time, rospy
from geometry_msgs.msg import Twist
rospy.init_node('quiet_teleop', disable_signals=True)
cmd_vel = rospy.Publisher('cmd_vel', Twist, queue_size=1)
ceiling = time.monotonic() + 300
while cmd_vel.get_num_connections() == 0:
    assert time.monotonic() < ceiling, 'no bridge'
    time.sleep(0.01)
time.sleep(float(sys.argv[1]))  # connected, sending nothing: a teleop whose user looks away
rospy.signal_shutdown('done')
"""


@needs_ros
def test_a_connected_node_that_sends_nothing_keeps_the_bridge_until_it_leaves(
    master: LocalMaster,
) -> None:
    bridge = spawn_bridge(master, "--idle-timeout", "1")
    _run_node(master, CONNECTED, "3")
    assert bridge.poll() is None  # 3 s connected, three times its idle timeout
    left = time.monotonic()
    assert _bridge_exit(bridge) == IDLE_EXIT_STATUS
    assert time.monotonic() - left >= 0.5  # the timeout counts from when the node left


#: Answers each newer ``odom`` with the next of its commands; at the state of step ``SLEEP_AT``
#: it first sleeps in the callback until 0.05 s of simulated time past that state, as tf2's
#: ``lookup_transform(..., timeout)`` does when the scan's transform comes after the scan.
#: Records every ``/tf`` stamp.
SLEEPER = """
import json, sys, threading, time, rospy
from nav_msgs.msg import Odometry
from std_msgs.msg import Float64MultiArray
from tf2_msgs.msg import TFMessage
commands, sleep_at = json.loads(sys.argv[1]), int(sys.argv[2])
rospy.init_node('sleeper', disable_signals=True)
motor = rospy.Publisher('motor', Float64MultiArray, queue_size=len(commands))
tf_stamps, poses, answered, done = [], [], [0], threading.Event()
newest = [-1]
def on_odom(message):
    stamp = message.header.stamp.to_nsec()
    if stamp <= newest[0] or done.is_set():
        return  # a state sent again, or one answered already
    newest[0] = stamp
    pose = message.pose.pose.position
    poses.append([stamp, pose.x, pose.y])
    if answered[0] == len(commands):
        done.set()
        return
    if answered[0] == sleep_at:
        # 0.05 s of simulated time past the state's stamp (its /clock may come after it)
        until = message.header.stamp + rospy.Duration(0.05)
        while rospy.Time.now() < until:
            rospy.sleep(0.01)
    motor.publish(Float64MultiArray(data=commands[answered[0]]))
    answered[0] += 1
ceiling = time.monotonic() + 300
while motor.get_num_connections() == 0:  # a command sent before that is lost
    assert time.monotonic() < ceiling, 'no bridge'
    time.sleep(0.01)
def on_tf(message):
    tf_stamps.append(message.transforms[0].header.stamp.to_nsec())
rospy.Subscriber('/tf', TFMessage, on_tf)
rospy.Subscriber('odom', Odometry, on_odom, queue_size=1)
assert done.wait(300), ('stalled', answered[0], poses)
time.sleep(0.5)  # every /tf of the last state has come
print(json.dumps({'poses': poses, 'tf': tf_stamps}))
rospy.signal_shutdown('done')
"""


@needs_ros
def test_a_node_sleeping_on_simulated_time_inside_a_callback_gets_the_time(
    master: LocalMaster,
) -> None:
    # Before, the bridge waited for the command and the node for /clock, which moved on
    # commands only: the state went out again every 5 s, with its /tf, and tf2 warned
    # TF_REPEATED_DATA each time. Now /clock runs on its own once that goes unanswered too.
    master.set_param("/use_sim_time", True)
    rng = mazesim.Simulator(mazesim.load_world("seed-maze"), robot="e-puck", seed=5)
    commands = [[2.0 + 0.5 * index, 3.0 - 0.25 * index] for index in range(8)]
    bridge = spawn_bridge(master, "--seed", "5", "--idle-timeout", "60")
    node = _run_node(master, SLEEPER, json.dumps(commands), "3")
    seen = json.loads(node.stdout.strip().splitlines()[-1])
    # Every state is the in-process run's, bit for bit; the stamps from the sleep on are later
    # by the whole steps the clock ran.
    expected = [topics.pose_values(rng)[:2]]
    for left, right in commands:
        rng.step(left, right)
        expected.append(topics.pose_values(rng)[:2])
    assert [pose[1:] for pose in seen["poses"]] == expected
    step_ns = 32_000_000
    stamps = [pose[0] for pose in seen["poses"]]
    assert stamps[:4] == [1] + [step * step_ns for step in range(1, 4)]
    late = stamps[4] // step_ns - 4
    assert late >= 2  # 0.05 s of 32 ms steps
    assert stamps[4:] == [(step + late) * step_ns for step in range(4, 9)]
    # /tf went out once per stamp: the state sent again kept it off the wire.
    assert len(seen["tf"]) == len(set(seen["tf"])) and set(stamps) <= set(seen["tf"])
    log = Path(master.log_path("bridge")).read_text(encoding="utf-8")
    assert "step 3's state, sent again, went unanswered; /clock now runs on its own" in log
    assert "TF_REPEATED_DATA" not in node.stderr
    master.stop_process(bridge)
