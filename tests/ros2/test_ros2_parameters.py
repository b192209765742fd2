"""The bridge's parameter services, called as ``ros2 param list``, ``get``, ``set`` and
``describe`` call them over ``rmw_cyclonedds_cpp``: a writer of ``rq/<node>/<service>Request``
and a reader of ``rr/<node>/<service>Reply``, matched before the call, each request led by the
client's id and a sequence number that the reply carries back. The requests are encoded, and
the replies decoded, by ``rosbags``' serializer from the services' definitions written out here
(``rcl_interfaces/srv``), not by mazesim's encoder."""

from __future__ import annotations

import sys

from mazesim.ros2.parameters import BridgeParameters, Parameter
from ros2_support import MAZESIM, needs_namespace, needs_ros2, run_in_namespace

CLIENT = """
import os, struct, time
import numpy as np
from cyclonedds._clayer import ddspy_take, ddspy_write
from cyclonedds.core import InstanceState, SampleState, ViewState
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
from rosbags.typesys import Stores, get_typestore, get_types_from_msg
from mazesim.ros2.node import Node
from mazesim.ros2.parameters import idl_types
from mazesim.ros2.qos import TopicQos, cyclone_qos

# rcl_interfaces/srv, as ROS 2 defines them (the same in Humble and Jazzy).
SERVICES = {
    'ListParameters': ('string[] prefixes\\nuint64 depth',
                       'rcl_interfaces/msg/ListParametersResult result'),
    'GetParameters': ('string[] names', 'rcl_interfaces/msg/ParameterValue[] values'),
    'SetParameters': ('rcl_interfaces/msg/Parameter[] parameters',
                      'rcl_interfaces/msg/SetParametersResult[] results'),
    'SetParametersAtomically': ('rcl_interfaces/msg/Parameter[] parameters',
                                'rcl_interfaces/msg/SetParametersResult result'),
    'DescribeParameters': ('string[] names',
                           'rcl_interfaces/msg/ParameterDescriptor[] descriptors'),
    'GetParameterTypes': ('string[] names', 'uint8[] types'),
}
store = get_typestore(Stores.ROS2_HUMBLE)
for name, parts in SERVICES.items():
    for part, text in zip(('Request', 'Response'), parts):
        (definition,) = get_types_from_msg(text, 'rcl_interfaces/msg/X').values()
        store.register({f'rcl_interfaces/srv/{name}_{part}': definition})

def value(kind=0, boolean=False, integer=0, double=0.0, text=''):
    return store.types['rcl_interfaces/msg/ParameterValue'](
        kind, boolean, integer, double, text, np.zeros(0, np.uint8), np.zeros(0, bool),
        np.zeros(0, np.int64), np.zeros(0, np.float64), [])

def parameter(name, given):
    return store.types['rcl_interfaces/msg/Parameter'](name, given)

node = Node('param_client')
part = node.participant
qos = cyclone_qos(TopicQos(True, False, 10))
mask = SampleState.Any | ViewState.Any | InstanceState.Any
ceiling = time.monotonic() + 120
sequence = 0

def call(node_name, service, srv, *fields):
    global sequence
    sequence += 1
    request_type, response_type = idl_types('humble', 'rcl_interfaces/srv/' + srv)
    writer = DataWriter(part, Topic(part, f'rq{node_name}/{service}Request', request_type),
                        qos=qos)
    reader = DataReader(part, Topic(part, f'rr{node_name}/{service}Reply', response_type),
                        qos=qos)
    while not (writer.get_matched_subscriptions() and reader.get_matched_publications()):
        assert time.monotonic() < ceiling, 'no service ' + service
        time.sleep(0.01)
    message = store.types[f'rcl_interfaces/srv/{srv}_Request'](*fields)
    data = bytes(store.serialize_cdr(message, f'rcl_interfaces/srv/{srv}_Request'))
    header = os.urandom(8) + struct.pack('<q', sequence)
    assert ddspy_write(writer._ref, data[:4] + header + data[4:]) >= 0
    while True:
        result = ddspy_take(reader._ref, mask, 8)
        for reply, info in ([] if isinstance(result, int) else result):
            if info.valid_data and reply[4:20] == header:
                return store.deserialize_cdr(reply[:4] + reply[20:],
                                             f'rcl_interfaces/srv/{srv}_Response')
        assert time.monotonic() < ceiling, 'no reply from ' + service
        time.sleep(0.005)

SIM = '/robot/sim'
listed = call(SIM, 'list_parameters', 'ListParameters', [], 0).result
assert listed.names == sorted(listed.names) and 'use_sim_time' in listed.names, listed
assert {'world', 'seed', 'mode', 'ros_distro', 'command_period'} <= set(listed.names), listed
print('listed', len(listed.names))

values = call(SIM, 'get_parameters', 'GetParameters',
              ['use_sim_time', 'world', 'seed', 'speed', 'unknown']).values
got = [(v.type, v.bool_value, v.integer_value, v.double_value, v.string_value) for v in values]
assert got == [(1, True, 0, 0.0, ''), (4, False, 0, 0.0, 'seed-maze'), (2, False, 7, 0.0, ''),
               (3, False, 0, 1.0, ''), (0, False, 0, 0.0, '')], got
types = call(SIM, 'get_parameter_types', 'GetParameterTypes', ['mode', 'noise', 'unknown'])
assert list(types.types) == [4, 1, 0], types

results = call(SIM, 'set_parameters', 'SetParameters', [
    parameter('use_sim_time', value(1, True)),
    parameter('seed', value(2, integer=3)),
    parameter('use_sim_time', value(1, False)),
    parameter('use_sim_time', value(4, text='true')),
    parameter('max_speed', value(3, double=0.1)),
]).results
said = [(r.successful, r.reason) for r in results]
assert said[0] == (True, ''), said
assert not said[1][0] and 'read-only' in said[1][1] and '--seed' in said[1][1], said
assert not said[2][0] and 'expected use_sim_time to be true' in said[2][1], said
assert not said[3][0] and 'to be a bool; found a string' in said[3][1], said
assert not said[4][0] and "'max_speed' is not one of the bridge's" in said[4][1], said
atomically = call(SIM, 'set_parameters_atomically', 'SetParametersAtomically', [
    parameter('use_sim_time', value(1, True)), parameter('mode', value(4, text='free'))]).result
assert not atomically.successful and '--mode' in atomically.reason, atomically

(described,) = call(SIM, 'describe_parameters', 'DescribeParameters', ['seed']).descriptors
assert (described.name, described.type, described.read_only) == ('seed', 2, True), described
assert '--seed' in described.description, described
print('parameters served')
"""


@needs_ros2
@needs_namespace
def test_ros2_param_lists_gets_sets_and_describes_the_bridges_parameters() -> None:
    bridge = [*MAZESIM, "ros2", "bridge", "--seed", "7", "--ros-args",
              "-r", "__node:=sim", "-r", "__ns:=/robot"]  # fmt: skip
    # A lockstep bridge that no driver has matched yet answers them.
    result = run_in_namespace([bridge], [sys.executable, "-c", CLIENT], grace=1.0)
    assert result.returncode == 0, result.stderr
    assert "parameters served" in result.stdout, result.stdout
    assert "does not offer" not in result.stderr, result.stderr


def test_a_parameter_is_refused_for_what_it_is() -> None:
    parameters = BridgeParameters(
        [Parameter("use_sim_time", True, "the clock", read_only=False), Parameter("seed", 0, "x")]
    )
    assert parameters.refusal("use_sim_time", 1, True) == ""
    assert "read-only" in parameters.refusal("seed", 2, 0)
    assert "expected use_sim_time to be a bool; found a double" in parameters.refusal(
        "use_sim_time", 3, 1.0
    )
    assert "found a value of type 42" in parameters.refusal("use_sim_time", 42, None)
    assert parameters.names(["seed"]) == ["seed"]
    assert parameters.names([]) == ["seed", "use_sim_time"]
