"""The bridge's reset services, ``/reset_simulation`` and ``/reset_world`` (``std_srvs/srv/Empty``,
as Gazebo's ``gazebo_ros_init`` names them), called from another process as ``ros2 service call``
calls a service over ``rmw_cyclonedds_cpp``: a writer of ``rq/<name>Request`` and a reader of
``rr/<name>Reply``, matched before the call (``wait_for_service``), each request led by the
client's id and a sequence number that the reply carries back."""

from __future__ import annotations

import sys

from reset_runs import STEPS, client_run
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
for name in ('reset_simulation', 'reset_world'):
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
