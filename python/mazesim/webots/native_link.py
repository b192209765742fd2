"""The lockstep link between mazesim and a compiled Webots controller running as a child process.

A C controller is linked to mazesim's controller library (``mazesim/webots/capi``), which
implements Webots' C API over this link; mazesim serves the link with the Python ``controller``
module's :class:`~mazesim.webots.robot.Robot`, so a C controller's devices behave as a Python
controller's do, reading for reading.

Transport: one end of a ``socketpair`` (a stream), whose file descriptor the child finds in the
environment variable ``MAZESIM_CONTROLLER_FD``. Numbers are in the machine's own byte order
(both ends run on one machine): ``i32`` a 32-bit signed integer, ``f64`` a double, ``str`` an
``i32`` length then that many UTF-8 bytes.

Messages from the controller, each starting with an ``i32`` kind:

``HELLO`` (1), ``i32`` version
    Sent once, by ``wb_robot_init`` (or the first API call). mazesim answers with the robot's
    description: ``i32`` version, ``f64`` basic time step (ms), ``str`` name, model, custom data,
    controller name, project path, world path, ``i32`` supervisor (0/1), ``i32`` device count,
    then per device (tag 1, 2... in this order) ``str`` name, ``str`` model, ``i32`` node type
    (Webots' ``WbNodeType`` numbers, :mod:`mazesim.webots.node_types`), ``i32`` count and that
    many ``f64`` facts: for a DistanceSensor its min value, max value, aperture, type, then its
    lookup table's rows (3 numbers each); for a RotationalMotor its max velocity, min position,
    max position, acceleration and its position sensor's tag (0 for none); for a
    PositionSensor its motor's tag; for a Camera its width, height and field of view.

``STEP`` (2), ``i32`` duration (ms), ``i32`` command count, commands
    Sent by ``wb_robot_step`` with the commands queued since the last step, each ``i32`` op,
    ``i32`` tag, ``f64`` a, ``f64`` b: ENABLE (1, sampling period a), DISABLE (2),
    SET_POSITION (3, a), SET_VELOCITY (4, a), SET_ACCELERATION (5, a), LED_SET (6, a). Tag 0
    in ENABLE and DISABLE is the keyboard. mazesim applies them in order, steps the simulation
    as ``Robot.step(duration)`` does and answers ``i32`` result (0, or -1 when the run's time is
    up), ``f64`` time (s), ``i32`` reading count, and per enabled device ``i32`` tag, ``i32``
    value count, ``i32`` byte count, the values as ``f64`` (a receiver's: the length of its
    queue) and the bytes (none so far). The keyboard's reading (tag 0) holds the keys of this
    step. A camera has no reading: ``wb_camera_get_image`` asks for its image (B G R A per
    pixel) with a ``CALL`` the first time it is called after a step, so that a camera enabled
    and never read draws no image.

``CLEANUP`` (3)
    Sent by ``wb_robot_cleanup``; no answer. The controller then exits.

``CALL`` (4), ``i32`` command count, commands, ``str`` function, ``i32`` value count, values
    Sent by the functions a controller waits for (the radio's and the supervisor's, see
    :mod:`mazesim.webots.native_calls`), after the commands queued so far, which mazesim
    applies first (as a step would) so that they keep their order. Each value is an ``i32``
    type then: nothing (0, no value or ``NULL``), an ``i32`` (1), an ``f64`` (2), ``i32``
    size and bytes (3), ``i32`` count and that many ``f64`` (4). mazesim answers ``i32``
    value count and the values.

Once a step has answered -1, the controller has
:data:`~mazesim.webots.termination.GRACE_SECONDS` of real time to exit, as in Webots; then it is
killed. Closing the link (mazesim ending) makes the controller exit.
"""

from __future__ import annotations

import socket
import struct
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

from mazesim.errors import MazesimIOError
from mazesim.webots.native_calls import NativeCalls
from mazesim.webots.node_types import node_type

__all__ = [
    "CALL",
    "CLEANUP",
    "HELLO",
    "STEP",
    "VERSION",
    "Command",
    "LinkClosed",
    "RobotLink",
]

#: The protocol's version (``LINK_VERSION`` in ``capi/src/link.h``).
VERSION = 4
HELLO, STEP, CLEANUP, CALL = 1, 2, 3, 4
ENABLE, DISABLE, SET_POSITION, SET_VELOCITY, SET_ACCELERATION, LED_SET = 1, 2, 3, 4, 5, 6
#: The tag of the keyboard in ENABLE, DISABLE and readings.
KEYBOARD_TAG = 0
#: Value types of a CALL and its answer.
VALUE_NONE, VALUE_INT, VALUE_DOUBLE, VALUE_BYTES, VALUE_DOUBLES = 0, 1, 2, 3, 4
#: Most values a CALL carries, and most bytes a value holds.
MAX_VALUES, MAX_VALUE_BYTES = 64, 1 << 26
#: Devices that give no reading at a step (their functions are calls).
_UNREAD_TYPES = {
    node_type(name) for name in ("EMITTER", "DISPLAY", "CAMERA", "LIDAR", "RANGE_FINDER")
}
#: Most commands one step may carry (a controller queues a few per device).
MAX_COMMANDS = 1 << 20

#: The device method each command calls, and the C function it stands for.
_METHODS = {
    ENABLE: ("enable", "wb_device_enable"),
    DISABLE: ("disable", "wb_device_disable"),
    SET_POSITION: ("setPosition", "wb_motor_set_position"),
    SET_VELOCITY: ("setVelocity", "wb_motor_set_velocity"),
    SET_ACCELERATION: ("setAcceleration", "wb_motor_set_acceleration"),
    LED_SET: ("set", "wb_led_set"),
}

_INT = struct.Struct("=i")
_DOUBLE = struct.Struct("=d")
_COMMAND = struct.Struct("=iidd")
_READING = struct.Struct("=iii")


class LinkClosed(Exception):
    """The controller closed the link (it exited, crashed, or called ``wb_robot_cleanup``)."""


@dataclass(frozen=True)
class Command:
    """One command of a step: ``op`` on the device ``tag`` with the arguments ``a``, ``b``."""

    op: int
    tag: int
    a: float
    b: float


def _encoded(value: Any) -> bytes:
    """A value of a CALL's answer: None, an int, a float, bytes or a list of numbers."""
    if value is None:
        return _INT.pack(VALUE_NONE)
    if isinstance(value, int):
        return _INT.pack(VALUE_INT) + _INT.pack(max(-(2**31), min(2**31 - 1, value)))
    if isinstance(value, float):
        return _INT.pack(VALUE_DOUBLE) + _DOUBLE.pack(value)
    if isinstance(value, (bytes, bytearray)):
        return _INT.pack(VALUE_BYTES) + _INT.pack(len(value)) + bytes(value)
    numbers = [float(v) for v in value]
    packed = struct.pack(f"={len(numbers)}d", *numbers)
    return _INT.pack(VALUE_DOUBLES) + _INT.pack(len(numbers)) + packed


def _text(value: str) -> bytes:
    data = value.encode("utf-8")
    return _INT.pack(len(data)) + data


class RobotLink:
    """mazesim's end of the link: a :class:`~mazesim.webots.robot.Robot` served to a child.

    Args:
        channel: mazesim's end of the socket pair.
        robot: The robot the controller drives.
        facts: The controller name, project path and world path the description reports.
    """

    def __init__(self, channel: socket.socket, robot: Any, facts: tuple[str, str, str]) -> None:
        self.channel = channel
        self.robot = robot
        self.facts = facts
        count = int(robot.getNumberOfDevices())
        self.devices = [robot.getDeviceByIndex(i) for i in range(count)]
        self.tags = {id(device): i + 1 for i, device in enumerate(self.devices)}
        self.enabled: dict[int, Any] = {}
        self.keyboard_enabled = False
        self.calls = NativeCalls(robot, self.devices)

    # --- reading and writing ---------------------------------------------------------------

    def _receive(self, size: int) -> bytes:
        chunks, left = [], size
        while left:
            chunk = self.channel.recv(min(left, 1 << 16))
            if not chunk:
                raise LinkClosed
            chunks.append(chunk)
            left -= len(chunk)
        return b"".join(chunks)

    def _int(self) -> int:
        return int(_INT.unpack(self._receive(_INT.size))[0])

    def receive_kind(self) -> int:
        """The kind of the controller's next message (:data:`HELLO`, :data:`STEP`...).

        Raises:
            LinkClosed: The controller closed the link.
        """
        return self._int()

    def receive_hello(self) -> None:
        """Reads a HELLO's version and sends the robot's description.

        Raises:
            MazesimIOError: The controller's library speaks another version.
        """
        version = self._int()
        if version != VERSION:
            raise MazesimIOError(
                f"expected a controller built with mazesim's controller library, link version "
                f"{VERSION}, found version {version}"
            )
        self.channel.sendall(self.description())

    def receive_step(self) -> tuple[int, list[Command]]:
        """A STEP's duration (ms) and commands.

        Raises:
            MazesimIOError: The message is malformed.
        """
        duration = self._int()
        return duration, self._commands()

    def receive_call(self) -> None:
        """Reads a CALL, applies the commands before it, runs it and sends its answer.

        Raises:
            MazesimIOError: The message is malformed or names a function mazesim does not
                serve.
        """
        self.apply(self._commands())
        name = self._bytes(256).decode("utf-8", errors="replace")
        count = self._int()
        if not 0 <= count <= MAX_VALUES:
            raise MazesimIOError(
                f"expected at most {MAX_VALUES} values in a call from the controller, found {count}"
            )
        values = [self._value() for _ in range(count)]
        answer = self.calls.call(name, values)
        self.channel.sendall(_INT.pack(len(answer)) + b"".join(map(_encoded, answer)))

    def _bytes(self, limit: int) -> bytes:
        size = self._int()
        if not 0 <= size <= limit:
            raise MazesimIOError(
                f"expected at most {limit} bytes in a value from the controller, found {size}"
            )
        return self._receive(size)

    def _value(self) -> Any:
        kind = self._int()
        if kind == VALUE_INT:
            return self._int()
        if kind == VALUE_DOUBLE:
            return float(_DOUBLE.unpack(self._receive(_DOUBLE.size))[0])
        if kind == VALUE_BYTES:
            return self._bytes(MAX_VALUE_BYTES)
        if kind == VALUE_DOUBLES:
            count = self._int()
            if not 0 <= count <= MAX_VALUE_BYTES // _DOUBLE.size:
                raise MazesimIOError(
                    f"expected at most {MAX_VALUE_BYTES // _DOUBLE.size} numbers in a value "
                    f"from the controller, found {count}"
                )
            data = self._receive(count * _DOUBLE.size)
            return [float(v) for (v,) in _DOUBLE.iter_unpack(data)]
        if kind != VALUE_NONE:
            raise MazesimIOError(f"expected a value type 0 to 4 from the controller, found {kind}")
        return None

    def _commands(self) -> list[Command]:
        count = self._int()
        if not 0 <= count <= MAX_COMMANDS:
            raise MazesimIOError(
                f"expected at most {MAX_COMMANDS} commands in a step from the controller, "
                f"found {count}"
            )
        data = self._receive(count * _COMMAND.size)
        return [Command(*fields) for fields in _COMMAND.iter_unpack(data)]

    # --- the robot's side ------------------------------------------------------------------

    def description(self) -> bytes:
        """The HELLO's answer: the robot and its devices."""
        robot = self.robot
        name, project, world = self.facts
        parts = [
            _INT.pack(VERSION),
            _DOUBLE.pack(float(robot.getBasicTimeStep())),
            # The clock as the controller starts: 0 at the world's start, the running time for
            # a controller a supervisor restarted or imported (``wb_robot_get_time`` reads it
            # before the first step, as Webots' does after ``wb_robot_init``).
            _DOUBLE.pack(float(robot.getTime())),
            *(_text(str(v)) for v in (robot.getName(), robot.getModel(), robot.getCustomData())),
            *(_text(v) for v in (name, project, world)),
            _INT.pack(1 if robot.getSupervisor() else 0),
            _INT.pack(1 if robot.getSynchronization() else 0),
            _INT.pack(len(self.devices)),
        ]
        for device in self.devices:
            facts = self._facts(device)
            parts += [
                _text(str(device.getName())),
                _text(str(device.getModel())),
                _INT.pack(int(device.getNodeType())),
                _INT.pack(len(facts)),
                *(_DOUBLE.pack(float(f)) for f in facts),
            ]
        return b"".join(parts)

    def _tag(self, device: Any) -> int:
        return self.tags.get(id(device), 0) if device is not None else 0

    def _facts(self, device: Any) -> list[float]:
        kind = int(device.getNodeType())
        if kind == node_type("DISTANCE_SENSOR"):
            table = list(device.getLookupTable())
            head = [device.getMinValue(), device.getMaxValue(), device.getAperture()]
            return [*head, device.getType(), *table]
        if kind == node_type("ROTATIONAL_MOTOR"):
            return [
                device.getMaxVelocity(),
                device.getMinPosition(),
                device.getMaxPosition(),
                device.getAcceleration(),
                self._tag(device.getPositionSensor()),
            ]
        if kind == node_type("POSITION_SENSOR"):
            return [self._tag(device.getMotor())]
        if kind == node_type("CAMERA"):
            return [device.getWidth(), device.getHeight(), device.getFov()]
        if kind == node_type("DISPLAY"):
            return [device.getWidth(), device.getHeight()]
        return []

    def apply(self, commands: list[Command]) -> None:
        """Applies a step's commands in order, as the Python API calls would."""
        for command in commands:
            if command.tag == KEYBOARD_TAG and command.op in (ENABLE, DISABLE):
                keyboard = self.robot.getKeyboard()
                if command.op == ENABLE:
                    keyboard.enable(int(command.a))
                else:
                    keyboard.disable()
                self.keyboard_enabled = command.op == ENABLE and int(command.a) > 0
                continue
            if not 1 <= command.tag <= len(self.devices):
                continue
            device = self.devices[command.tag - 1]
            self._apply(command, device)

    def _apply(self, command: Command, device: Any) -> None:
        op, value = command.op, command.a
        method = _METHODS.get(op)
        call = getattr(device, method[0], None) if method else None
        if call is None:
            # A tag of another kind of device (wb_led_set on a motor...): Webots' message.
            function = method[1] if method else "wb_robot_step"
            print(f"Error: {function}(): invalid device tag.", file=sys.stderr)
            return
        if op == ENABLE:
            call(int(value))
            if int(value) > 0:
                self.enabled[command.tag] = device
            else:
                self.enabled.pop(command.tag, None)
        elif op == DISABLE:
            call()
            self.enabled.pop(command.tag, None)
        elif op == LED_SET:
            call(int(value))
        else:
            call(value)

    def answer_step(self, result: int) -> None:
        """Sends a step's result, the time and the enabled devices' readings."""
        readings = list(self._readings())
        parts = [_INT.pack(result), _DOUBLE.pack(float(self.robot.getTime()))]
        parts.append(_INT.pack(len(readings)))
        for tag, values, data in readings:
            parts.append(_READING.pack(tag, len(values), len(data)))
            parts += [_DOUBLE.pack(v) for v in values]
            parts.append(data)
        self.channel.sendall(b"".join(parts))

    def _readings(self) -> Iterator[tuple[int, list[float], bytes]]:
        if self.keyboard_enabled:
            keyboard = self.robot.getKeyboard()
            keys: list[float] = []
            while len(keys) < 64:
                key = int(keyboard.getKey())
                if key < 0:
                    break
                keys.append(float(key))
            yield KEYBOARD_TAG, keys, b""
        for tag, device in self.enabled.items():
            kind = int(device.getNodeType())
            if kind in _UNREAD_TYPES:
                continue
            if kind == node_type("RECEIVER"):
                # Its queue's length, which only a step and wb_receiver_next_packet change.
                yield tag, [float(device.getQueueLength())], b""
            elif hasattr(type(device), "getValues") and kind != node_type("TOUCH_SENSOR"):
                yield tag, [float(v) for v in device.getValues()], b""
            else:
                yield tag, [float(device.getValue())], b""
