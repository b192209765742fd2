"""The bridge's ROS 2 parameters, served as every rclcpp and rclpy node serves its own.

A ROS 2 node offers six services under its own name, which ``ros2 param list``, ``get``, ``set``,
``describe`` and ``dump`` (and rqt's parameter editor, and a launch file's tools) call:
``~/list_parameters``, ``~/get_parameters``, ``~/set_parameters``,
``~/set_parameters_atomically``, ``~/describe_parameters`` and ``~/get_parameter_types``, of
the ``rcl_interfaces/srv`` types of the same names, laid out on the wire as
:mod:`mazesim.ros2.services` says. The bridge's parameters are ``use_sim_time`` (every ROS 2
node has it; the bridge is the clock, so it is ``true`` and stays so: setting it ``true`` succeeds,
``false`` is refused) and its settings (``world``, ``seed``, ``mode``...), each named after its
command-line option and read-only, as a node's ``read_only`` parameters are: setting one is
refused with the option to restart the bridge with. Names and types follow
``rcl_interfaces/msg/ParameterType``; a name the bridge does not have reads as not set, as rclpy
answers for an undeclared parameter.
"""

from __future__ import annotations

import dataclasses
import functools
import struct
from collections.abc import Callable, Sequence
from typing import Any

from mazesim.errors import InvalidActionError, _shown
from mazesim.ros2 import cdr, messages

__all__ = [
    "PARAMETER_SERVICES",
    "BridgeParameters",
    "Parameter",
    "ParameterServers",
    "bridge_parameters",
]

#: ``rcl_interfaces/msg/ParameterType``.
NOT_SET, BOOL, INTEGER, DOUBLE, STRING = 0, 1, 2, 3, 4
_TYPE_NAMES = ("not set", "bool", "integer", "double", "string", "byte array", "bool array",
               "integer array", "double array", "string array")  # fmt: skip

#: A node's parameter services (after its full name) and their ``rcl_interfaces`` types.
PARAMETER_SERVICES = {
    "list_parameters": "rcl_interfaces/srv/ListParameters",
    "get_parameters": "rcl_interfaces/srv/GetParameters",
    "set_parameters": "rcl_interfaces/srv/SetParameters",
    "set_parameters_atomically": "rcl_interfaces/srv/SetParametersAtomically",
    "describe_parameters": "rcl_interfaces/srv/DescribeParameters",
    "get_parameter_types": "rcl_interfaces/srv/GetParameterTypes",
}

_VALUE = "rcl_interfaces/msg/ParameterValue"
_PARAMETER = "rcl_interfaces/msg/Parameter"
_RESULT = "rcl_interfaces/msg/SetParametersResult"
_LIST_RESULT = "rcl_interfaces/msg/ListParametersResult"
_DESCRIPTOR = "rcl_interfaces/msg/ParameterDescriptor"
#: Each service's request and response fields: ``(name, message type)``, a message type ending
#: in ``[]`` for a sequence, or a base type (``string[]``, ``uint64``, ``uint8[]``).
_FIELDS = {
    "ListParameters": ([("prefixes", "string[]"), ("depth", "uint64")],
                       [("result", _LIST_RESULT)]),
    "GetParameters": ([("names", "string[]")], [("values", _VALUE + "[]")]),
    "SetParameters": ([("parameters", _PARAMETER + "[]")], [("results", _RESULT + "[]")]),
    "SetParametersAtomically": ([("parameters", _PARAMETER + "[]")], [("result", _RESULT)]),
    "DescribeParameters": ([("names", "string[]")], [("descriptors", _DESCRIPTOR + "[]")]),
    "GetParameterTypes": ([("names", "string[]")], [("types", "uint8[]")]),
}  # fmt: skip


@functools.cache
def idl_types(distro: str, srvtype: str) -> tuple[Any, Any]:
    """The Cyclone DDS request and response types of a parameter service, named as ROS 2 names
    them (``rcl_interfaces::srv::dds_::GetParameters_Request_``), each led by the header
    ``rmw_cyclonedds_cpp`` puts first (the client's id, the sequence number): Cyclone checks a
    sample it receives or writes against its type, and would drop a request whose header it
    read as the first field's length."""
    import cyclonedds.idl.types as idl_types_module
    from cyclonedds.idl import make_idl_struct

    idl: Any = idl_types_module

    bases: dict[str, Any] = {"string": str, "uint64": idl.uint64, "uint8": idl.uint8}
    name = srvtype.rsplit("/", 1)[1]
    made = []
    for part, fields in zip(("Request", "Response"), _FIELDS[name]):
        annotations: dict[str, Any] = {"client_id": idl.uint64, "sequence_number": idl.int64}
        for field, kind in fields:
            element = kind.removesuffix("[]")
            inner = bases.get(element) or messages.idl_type(distro, element)
            annotations[field] = idl.sequence[inner] if kind.endswith("[]") else inner
        class_name = f"{name}_{part}_"
        made.append(
            make_idl_struct(class_name, messages.dds_type_name(srvtype + "_" + part), annotations)
        )
    return made[0], made[1]


@dataclasses.dataclass(frozen=True)
class Parameter:
    """One parameter of the bridge: its name, value (``bool``, ``int``, ``float`` or ``str``),
    what it is, and whether it can be set."""

    name: str
    value: bool | int | float | str
    description: str
    read_only: bool = True

    @property
    def type(self) -> int:
        """Its ``rcl_interfaces/msg/ParameterType``."""
        for kind, code in ((bool, BOOL), (int, INTEGER), (float, DOUBLE)):
            if isinstance(self.value, kind):
                return code
        return STRING


#: ``use_sim_time``: the bridge is the clock.
USE_SIM_TIME = Parameter(
    "use_sim_time",
    True,
    "the bridge publishes /clock and stamps every message with simulation time: always true",
    read_only=False,
)


def bridge_parameters(settings: Any) -> list[Parameter]:
    """``use_sim_time`` and the bridge's settings (a
    :class:`~mazesim.ros2.bridge.BridgeSettings`), each named after its option, read-only."""
    options = [
        ("world", settings.world, "--world", "the world simulated"),
        ("robot", settings.robot, "--robot", "the robot's profile"),
        ("seed", settings.seed, "--seed", "the seed of the sensor noise"),
        ("noise", settings.noise, "--no-noise", "the sensors are noisy"),
        ("ros_distro", settings.distro, "--ros-distro", "the ROS 2 distribution's layouts"),
        ("mode", settings.mode, "--mode", "lockstep (a step per command) or free-running"),
        ("speed", float(settings.speed), "--speed", "free-running: simulated s per wall s"),
        ("paused", settings.paused, "--paused", "free-running: started paused"),
        ("stop_after", settings.stop_after, "--stop-after", "steps before stopping (0: never)"),
        ("stop_at_goal", settings.stop_at_goal, "--stop-at-goal", "stops at the world's goal"),
        ("bag", settings.bag or "", "--bag", "the rosbag2 folder recorded ('' for none)"),
        ("network", settings.network, "--network", "discovery open to the subnet"),
        ("frame_prefix", settings.frame_prefix, "--frame-prefix", "frames prefixed by robot"),
        ("namespace", settings.namespace, "--namespace", "the one robot's namespace"),
        ("command_period", float(settings.command_period), "--command-period",
         "lockstep: the period of the driving node's timer, s (0: a step per command)"),
        ("command_deadline", float(settings.command_deadline), "--command-deadline",
         "lockstep: wall s before stepping without a command (0: waits)"),
        ("idle_timeout", float(settings.idle_timeout), "--idle-timeout",
         "wall s with no command writer before giving up (0: never)"),
    ]  # fmt: skip
    return [USE_SIM_TIME] + [
        Parameter(name, value, f"{what} ({option}; restart the bridge to change it)")
        for name, value, option, what in options
    ]


def _write_value(writer: cdr.CdrWriter, kind: int, value: Any) -> None:
    """Appends an ``rcl_interfaces/msg/ParameterValue`` of a scalar (or none)."""
    writer.pack(_U8, 1, kind)
    writer.pack(_U8, 1, bool(value) if kind == BOOL else 0)
    writer.pack(_I64, 8, int(value) if kind == INTEGER else 0)
    writer.pack(_F64, 8, float(value) if kind == DOUBLE else 0.0)
    writer.string(str(value) if kind == STRING else "")
    for _ in range(5):  # the byte, bool, integer, double and string arrays: empty
        writer.pack(_U32, 4, 0)


def _read_value(reader: cdr.CdrReader) -> tuple[int, Any]:
    """The type and value of an ``rcl_interfaces/msg/ParameterValue`` (arrays as lists)."""
    kind, flag = reader.unpack("BB", 1)
    (integer,) = reader.unpack("q", 8)
    (double,) = reader.unpack("d", 8)
    text = reader.string()
    arrays: list[list[Any]] = []
    for code, size in (("B", 1), ("B", 1), ("q", 8), ("d", 8)):
        (count,) = reader.unpack("I", 4)
        arrays.append(list(reader.unpack(f"{count}{code}", size)) if count else [])
    (count,) = reader.unpack("I", 4)
    arrays.append([reader.string() for _ in range(int(count))])
    scalars = {BOOL: bool(flag), INTEGER: int(integer), DOUBLE: float(double), STRING: text}
    kind = int(kind)
    return kind, scalars.get(kind, arrays[kind - 5] if 5 <= kind <= 9 else None)


def _read_strings(reader: cdr.CdrReader) -> list[str]:
    (count,) = reader.unpack("I", 4)
    return [reader.string() for _ in range(int(count))]


def _read_parameters(reader: cdr.CdrReader) -> list[tuple[str, int, Any]]:
    (count,) = reader.unpack("I", 4)
    return [(reader.string(), *_read_value(reader)) for _ in range(int(count))]


_U8 = struct.Struct("<B")
_U32 = struct.Struct("<I")
_I64 = struct.Struct("<q")
_F64 = struct.Struct("<d")


class BridgeParameters:
    """The answers to the parameter services over the bridge's parameters.

    Args:
        parameters: The parameters, ``use_sim_time`` among them.
    """

    def __init__(self, parameters: Sequence[Parameter]) -> None:
        self.parameters = {parameter.name: parameter for parameter in parameters}

    def names(self, prefixes: Sequence[str]) -> list[str]:
        """The names under ``prefixes`` (all when none), as ``ros2 param list`` shows them."""
        return sorted(
            name
            for name in self.parameters
            if not prefixes or any(name == p or name.startswith(p + ".") for p in prefixes)
        )

    def refusal(self, name: str, kind: int, value: Any) -> str:
        """Why setting ``name`` to ``value`` of ``kind`` is refused; ``""`` when it is taken."""
        parameter = self.parameters.get(name)
        if parameter is None:
            return (
                f"parameter {_shown(name)} is not one of the bridge's: {', '.join(self.names(()))}"
            )
        if parameter.read_only:
            return f"parameter {name} is read-only: {parameter.description}"
        if kind != parameter.type:
            found = _TYPE_NAMES[kind] if 0 <= kind < len(_TYPE_NAMES) else f"value of type {kind}"
            return f"expected {name} to be a {_TYPE_NAMES[parameter.type]}; found a {found}"
        if value != parameter.value:
            shown = str(parameter.value).lower() if kind == BOOL else _shown(parameter.value)
            return f"expected {name} to be {shown}: {parameter.description}"
        return ""

    def answer(self, service: str, request: bytes) -> bytes:
        """The response (CDR, with its encapsulation header) to ``request`` (CDR, without the
        service header) of the service ``service`` (``get_parameters``...).

        Raises:
            InvalidActionError, struct.error, UnicodeDecodeError, IndexError: The request does
                not decode.
        """
        reader = cdr.CdrReader(request, PARAMETER_SERVICES[service])
        writer = cdr.CdrWriter()
        handler: Callable[[cdr.CdrReader, cdr.CdrWriter], None] = getattr(self, "_" + service)
        handler(reader, writer)
        return writer.bytes()

    def _list_parameters(self, reader: cdr.CdrReader, writer: cdr.CdrWriter) -> None:
        names = self.names(_read_strings(reader))
        writer.pack(_U32, 4, len(names))
        for name in names:
            writer.string(name)
        writer.pack(_U32, 4, 0)  # no prefixes: no name holds a "."

    def _get_parameters(self, reader: cdr.CdrReader, writer: cdr.CdrWriter) -> None:
        names = _read_strings(reader)
        writer.pack(_U32, 4, len(names))
        for name in names:
            parameter = self.parameters.get(name)
            if parameter is None:
                _write_value(writer, NOT_SET, None)
            else:
                _write_value(writer, parameter.type, parameter.value)

    def _get_parameter_types(self, reader: cdr.CdrReader, writer: cdr.CdrWriter) -> None:
        names = _read_strings(reader)
        writer.pack(_U32, 4, len(names))
        for name in names:
            parameter = self.parameters.get(name)
            writer.pack(_U8, 1, NOT_SET if parameter is None else parameter.type)

    def _describe_parameters(self, reader: cdr.CdrReader, writer: cdr.CdrWriter) -> None:
        names = _read_strings(reader)
        writer.pack(_U32, 4, len(names))
        for name in names:
            parameter = self.parameters.get(name)
            writer.string(name)
            writer.pack(_U8, 1, NOT_SET if parameter is None else parameter.type)
            writer.string("" if parameter is None else parameter.description)
            writer.string("")  # additional_constraints
            writer.pack(_U8, 1, parameter is None or parameter.read_only)
            writer.pack(_U8, 1, 0)  # dynamic_typing
            writer.pack(_U32, 4, 0)  # floating_point_range
            writer.pack(_U32, 4, 0)  # integer_range

    def _set_parameters(self, reader: cdr.CdrReader, writer: cdr.CdrWriter) -> None:
        refusals = [self.refusal(*parameter) for parameter in _read_parameters(reader)]
        writer.pack(_U32, 4, len(refusals))
        for refusal in refusals:
            _write_result(writer, refusal)

    def _set_parameters_atomically(self, reader: cdr.CdrReader, writer: cdr.CdrWriter) -> None:
        refusals = [self.refusal(*parameter) for parameter in _read_parameters(reader)]
        _write_result(writer, next((refusal for refusal in refusals if refusal), ""))


def _write_result(writer: cdr.CdrWriter, refusal: str) -> None:
    """Appends an ``rcl_interfaces/msg/SetParametersResult``."""
    writer.pack(_U8, 1, not refusal)
    writer.string(refusal)


class ParameterServers:
    """The six parameter services of one node, answered from its parameters.

    Args:
        node: The node (:class:`~mazesim.ros2.node.Node`) whose services they are.
        parameters: Its parameters.
        report: Called with a line for a request that does not decode.
    """

    def __init__(
        self, node: Any, parameters: Sequence[Parameter], report: Callable[[str], None]
    ) -> None:
        full_name = f"{node.namespace.rstrip('/')}/{node.name}"
        self.parameters = BridgeParameters(parameters)
        self.report = report
        self.servers = [
            (node.service_server(f"{full_name}/{service}", srvtype), service)
            for service, srvtype in PARAMETER_SERVICES.items()
        ]

    def serve(self) -> int:
        """Answers the requests that came since the last call; returns how many."""
        served = 0
        for server, service in self.servers:
            server.flush()
            for request in server.take_requests():
                try:
                    response = self.parameters.answer(service, request.fields)
                except (InvalidActionError, struct.error, UnicodeDecodeError, IndexError):
                    self.report(
                        f"{server.service}: a request of {len(request.fields)} bytes that does "
                        f"not decode as {PARAMETER_SERVICES[service]}_Request; not answered"
                    )
                    continue
                server.reply(request, response)
                served += 1
        return served
