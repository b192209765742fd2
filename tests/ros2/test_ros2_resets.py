"""The bridge's reset services, ``/reset_simulation`` and ``/reset_world`` (``std_srvs/srv/Empty``,
as Gazebo's ``gazebo_ros_init`` names them), called from another process as ``ros2 service call``
calls a service over ``rmw_cyclonedds_cpp``: a writer of ``rq/<name>Request`` and a reader of
``rr/<name>Reply``, matched before the call (``wait_for_service``), each request led by the
client's id and a sequence number that the reply carries back."""

from __future__ import annotations

import sys

from reset_runs import STEPS, client_run, wheel_speeds
from ros2_support import MAZESIM, needs_namespace, needs_ros2, run_in_namespace

# The client: its service types written out here as ROS 2 names them on the wire (not taken
# from mazesim); mazesim's Node only for /pose and /motor.
CLIENT = """
import os, struct, time
from cyclonedds._clayer import ddspy_take, ddspy_write
from cyclonedds.core import InstanceState, SampleState, ViewState
from cyclonedds.idl import make_idl_struct
import cyclonedds.idl.types as idl
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
from mazesim.ros2 import cdr
from mazesim.ros2.node import Node
from mazesim.ros2.qos import COMMAND, SENSOR, TopicQos, cyclone_qos

node = Node('reset_caller')
poses = node.reader('/pose', 'std_msgs/msg/Float64MultiArray', TopicQos(True, False, 100))
motor = node.writer('/motor', 'std_msgs/msg/Float64MultiArray', COMMAND)
field = {'structure_needs_at_least_one_member': idl.uint8}
Request = make_idl_struct('Empty_Request_', 'std_srvs::srv::dds_::Empty_Request_', field)
Response = make_idl_struct('Empty_Response_', 'std_srvs::srv::dds_::Empty_Response_', field)
qos = cyclone_qos(TopicQos(True, False, 10))
mask = SampleState.Any | ViewState.Any | InstanceState.Any
clients = {}
for name in ('reset_simulation', 'reset_world', 'reset_positions'):
    part = node.participant
    writer = DataWriter(part, Topic(part, f'rq/{name}Request', Request), qos=qos)
    reader = DataReader(part, Topic(part, f'rr/{name}Reply', Response), qos=qos)
    clients[name] = (writer, reader)
ceiling = time.monotonic() + 300
seen = []

def take_poses():
    seen.extend(cdr.decode_float64_array(data) for data in poses.take(100))

def pose_at(step):
    # The first /pose of simulated time step * 32 ms since the wait began (a state sent again
    # after 5 s is the same message).
    while True:
        take_poses()
        for pose in seen:
            if abs(pose[3] - step * 0.032) < 1e-9:
                seen.clear()
                return pose
        assert time.monotonic() < ceiling, ('no pose of step', step, seen)
        time.sleep(0.001)

def call(name, sequence):
    writer, reader = clients[name]
    # wait_for_service: the bridge's request reader and reply writer matched.
    while not (writer.get_matched_subscriptions() and reader.get_matched_publications()):
        assert time.monotonic() < ceiling, 'no service ' + name
        time.sleep(0.01)
    header = os.urandom(8) + struct.pack('<q', sequence)
    assert ddspy_write(writer._ref, cdr.CDR_LE + header + bytes(4)) >= 0
    while True:
        result = ddspy_take(reader._ref, mask, 8)
        replies = [] if isinstance(result, int) else [d for d, info in result if info.valid_data]
        for data in replies:
            assert data[4:20] == header, (data, header)
            return
        assert time.monotonic() < ceiling, 'no reply from ' + name
        time.sleep(0.001)

def send(left, right):
    motor.publish(cdr.encode_float64_multi_array([], [left, right]))

sequence = 0
def reset(name):
    global sequence
    sequence += 1
    call(name, sequence)
"""


@needs_ros2
@needs_namespace
def test_a_client_resets_the_lockstep_run_and_the_world() -> None:
    bridge = [*MAZESIM, "ros2", "bridge", "--stop-after", str(2 * STEPS)]
    result = run_in_namespace([bridge], [sys.executable, "-c", CLIENT + client_run()])
    assert result.returncode == 0, result.stderr
    assert "reset_simulation: the run again, bit for bit" in result.stdout
    assert "reset_world: at the start, the clock going on" in result.stdout
    assert "/reset_simulation: everything as at the start" in result.stderr
    assert "/reset_world: every robot at its start" in result.stderr


# After a reset the client makes a new /pose reader, as rclpy.wait_for_message does: a volatile
# reader receives nothing sent before it matched, so the state after the reset (sent before the
# call was answered) never reaches it; it waited for the state sent again after 5 s.
_WAIT_AFTER_RESET = """
start = pose_at(0)
for left, right in speeds[:3]:
    send(left, right)
pose_at(3)
reset('reset_positions')  # stage_ros's name for reset_world
waiting = node.reader('/pose', 'std_msgs/msg/Float64MultiArray', TopicQos(True, False, 1))
while not (found := waiting.take(1)):
    assert time.monotonic() < ceiling, 'no pose for a reader made after the reset'
    time.sleep(0.005)
after = cdr.decode_float64_array(found[0])
assert after[:3] == start[:3] and abs(after[3] - 3 * 0.032) < 1e-9, (after, start)
send(*speeds[3])
assert pose_at(4)[3] > after[3]
print('a reader made after the reset got the state after it')
"""


@needs_ros2
@needs_namespace
def test_a_reader_made_after_a_reset_gets_the_state_after_it() -> None:
    bridge = [*MAZESIM, "ros2", "bridge", "--stop-after", "4"]
    speeds = f"speeds = {wheel_speeds()!r}\n"
    result = run_in_namespace([bridge], [sys.executable, "-c", CLIENT + speeds + _WAIT_AFTER_RESET])
    assert result.returncode == 0, result.stderr
    assert "a reader made after the reset got the state after it" in result.stdout
    assert "state reader matched after the last state went out" in result.stderr
    assert "/reset_positions: every robot at its start" in result.stderr
    assert "stopped after 4 steps" in result.stderr


# Free-running, the bridge steps on its own with the last command: reset_simulation takes the
# clock back to its start and the robot to its start at rest (it holds no command), and
# reset_world takes the robot back while the clock goes on.
_FREE_RESETS = """
def until(condition, what):
    # The first pose, in the order they went out, for which the condition holds.
    while True:
        take_poses()
        while seen:
            pose = seen.pop(0)
            if condition(pose):
                return pose
        assert time.monotonic() < ceiling, what
        time.sleep(0.002)

start = until(lambda pose: True, 'a first pose')  # at rest until the first command
while not motor.subscribers():  # free-running, a command sent before the bridge's reader is lost
    assert time.monotonic() < ceiling, 'the bridge never read /motor'
    time.sleep(0.01)
send(3.0, 2.0)
until(lambda pose: pose[3] > 1.0 and pose[:2] != start[:2], 'the robot moving')
reset('reset_simulation')
# Each pose goes out in its step; the one after the reset is back at the start, time 0.
again = until(lambda pose: pose[3] < 1.0, 'the clock going back')
assert again[:3] == start[:3] and again[3] == 0.0, (again, start)
# No command held: the robot stands at its start as the clock runs on.
still = until(lambda pose: pose[3] > 0.5, 'the clock running again')
assert still[:3] == start[:3], (still, start)
print('free-running reset_simulation: the clock back to 0, the robot at its start at rest')
send(3.0, 2.0)
moved = until(lambda pose: pose[:2] != start[:2], 'the robot moving again')
reset('reset_world')
after = until(lambda pose: pose[:3] == start[:3], 'the robot back at its start')
assert after[3] >= moved[3], (after, moved)
print('free-running reset_world: the robot at its start, the clock going on')
"""


@needs_ros2
@needs_namespace
def test_the_resets_free_running() -> None:
    bridge = [*MAZESIM, "ros2", "bridge", "--mode", "free", "--speed", "4"]
    result = run_in_namespace([bridge], [sys.executable, "-c", CLIENT + _FREE_RESETS], grace=1.0)
    assert result.returncode == 0, result.stderr
    assert "free-running reset_simulation: the clock back to 0" in result.stdout
    assert "free-running reset_world: the robot at its start" in result.stdout
    assert "/reset_simulation: everything as at the start" in result.stderr
    assert "/reset_world: every robot at its start" in result.stderr
