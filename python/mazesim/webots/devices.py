"""The e-puck's devices as Webots' Python ``controller`` module presents them.

Semantics follow Webots: a sensor reads NaN until it is enabled and one sampling period has
passed, then refreshes every sampling period (every getter of the reading, those derived from it
too: see :func:`derived_reading`); a motor starts in position control at 0 and turns
to velocity control with ``setPosition(float('inf'))``; a velocity beyond ``getMaxVelocity()`` is
clamped with Webots' warning. Messages printed on stderr are Webots' own.
"""

from __future__ import annotations

import functools
import math
import re
import sys
import zlib
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from mazesim._toml import load_toml
from mazesim.errors import MOST_MESSAGE, InvalidArgumentError, _a_type, _shortened
from mazesim.webots.distance_rays import sensor_type
from mazesim.webots.last_commands import PositionControl, WheelCommand, motor_speed
from mazesim.webots.node_types import node_type
from mazesim.webots.webots_api import NotSimulated, webots_property

if TYPE_CHECKING:
    from mazesim._core import RobotProfile
    from mazesim.webots.simulation import RobotSimulation

__all__ = ["LED", "Device", "DistanceSensor", "Motor", "PositionSensor"]

#: The proximity sensors' lookup table of Webots' E-puck PROTO: distance (m), value, noise.
PROXIMITY_TABLE = (
    (0.0, 4095.0, 0.002),
    (0.005, 2133.33, 0.003),
    (0.01, 1465.73, 0.007),
    (0.015, 601.46, 0.0406),
    (0.02, 383.84, 0.01472),
    (0.03, 234.93, 0.0241),
    (0.04, 158.03, 0.0287),
    (0.05, 120.0, 0.04225),
    (0.06, 104.09, 0.03065),
    (0.07, 67.19, 0.04897),
)


def _print_error(message: str) -> None:
    """Prints Webots' error ``message`` as its library does, on stderr; at most
    :data:`~mazesim.errors.MOST_MESSAGE` characters of it, as mazesim's raised messages, so that a
    name of a million characters a controller passed shows as a line."""
    print(_shortened(message, MOST_MESSAGE), file=sys.stderr)


#: The longest sampling period Webots takes: its ``enable`` functions take a C ``int`` of ms.
MAX_SAMPLING_PERIOD_MS = 2**31 - 1
#: The most pixels of a side of a camera's, range finder's or display's image, and the most
#: points or layers of a lidar, that mazesim simulates; a world's larger field is cut to it with
#: a warning (a ``width 2147483648`` would ask for gigabytes at the first image).
MAX_DEVICE_SIDE = 4096


def device_side(value: Any, default: int, what: str, smallest: int = 1) -> int:
    """A device's size field as a whole number of pixels, points or layers: ``value`` (a number
    of the world file, None where the node has none: ``default``), at least ``smallest`` and at
    most :data:`MAX_DEVICE_SIDE`; ``what`` names it in the warning a larger one (or one that is
    no finite number) prints, e.g. ``Camera "camera" width``."""
    number = float(default if value is None else value)
    if not math.isfinite(number) or number > MAX_DEVICE_SIDE:
        shown = f"{number:.12g}"
        number = MAX_DEVICE_SIDE if number > 0 else default
        print(
            f"mazesim: warning: {what} {shown}: more than the {MAX_DEVICE_SIDE} mazesim "
            f"simulates, or no number; taken as {int(number)}",
            file=sys.stderr,
        )
    return max(smallest, int(number))


#: A motor's ``maxTorque`` (N m) where its node does not set it: Webots' RotationalMotor
#: default, which the E-puck PROTO keeps.
MAX_TORQUE = 10.0
#: The ``aperture`` (rad) of the E-puck's proximity sensors (its ``E-puckDistanceSensor`` PROTO).
EPUCK_PROXIMITY_APERTURE = 0.1


def sampling_period(samplingPeriod: Any, function: str) -> int | None:
    """The sampling period an ``enable`` call (``function``, Webots' C name) asks for, in ms:
    the one check of every device's period. A whole number of ms that fits Webots' C ``int``
    (a float is truncated, as before); anything else (NaN, inf, a text, 2**40) is refused with
    an ``InvalidArgumentError``, since Webots' Python API would pass its low 32 bits on, a
    period the call never named. A negative period prints Webots' error and is ignored
    (None), as Webots does."""
    number = samplingPeriod
    is_number = isinstance(number, (int, float, np.integer, np.floating))
    if isinstance(number, (bool, np.bool_)) or not is_number or not math.isfinite(number):
        found = repr(number) if is_number else _a_type(number)
        raise InvalidArgumentError(
            f"{function}(): sampling period refused: expected a whole number of ms in "
            f"[0, {MAX_SAMPLING_PERIOD_MS}] (Webots' C int; 0 disables), found {found}"
        )
    period = int(number)
    if period > MAX_SAMPLING_PERIOD_MS:
        raise InvalidArgumentError(
            f"{function}(): sampling period refused: expected a whole number of ms in "
            f"[0, {MAX_SAMPLING_PERIOD_MS}] (Webots' C int; 0 disables), found {period}"
        )
    if period < 0:
        _print_error(f"Error: {function}() called with negative sampling period.")
        return None
    return period


def noise_stream(simulation: RobotSimulation, name: str) -> np.random.Generator | None:
    """The noise stream of the device ``name``: its own, from the run's seed (None without
    noise)."""
    if not simulation.noise:
        return None
    key = zlib.crc32(name.encode("utf-8"))
    return np.random.default_rng(np.random.SeedSequence(simulation.seed, spawn_key=(key,)))


def derived_reading(width: int = 0) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """Marks a sensor's getter that answers from the sensor's reading, or from what was measured
    with it, rather than from the reading itself (a GPS's speed beside its position, an inertial
    unit's quaternion beside its angles, a touch sensor's force vector beside its value): until
    the sensor's first reading it answers NaN, one (``width`` 0) or a list of ``width``, every
    component of it, as Webots' controller library creates each reading it keeps
    (``values[i] = NAN`` in src/controller/c: gps.c, touch_sensor.c...)."""

    def wrap(getter: Callable[..., Any]) -> Callable[..., Any]:
        # A derived getter takes no argument: one given is refused whether or not the sensor
        # has read yet (the NaN answer checked none).
        @functools.wraps(getter)
        def answer(self: _Sensor) -> Any:
            if not self._has_reading:
                return [math.nan] * width if width else math.nan
            return getter(self)

        return answer

    return wrap


Row = tuple[float, float, float]


class LookupTable:
    """A Webots lookup table: input, output, relative noise, row after row."""

    def __init__(self, rows: Sequence[Sequence[float]]) -> None:
        cleaned = [tuple(float(v) for v in row[:3]) for row in rows if len(row) >= 2]
        self.rows: list[Row] = [
            (row[0], row[1], row[2] if len(row) > 2 else 0.0) for row in cleaned
        ]
        self.rows.sort(key=lambda row: row[0])

    def __call__(self, x: float, rng: np.random.Generator | None) -> float:
        """The output for ``x``, with noise when ``rng`` is given; ``x`` itself without rows."""
        if not self.rows:
            return x
        inputs = [row[0] for row in self.rows]
        value = float(np.interp(x, inputs, [row[1] for row in self.rows]))
        noise = float(np.interp(x, inputs, [row[2] for row in self.rows]))
        if rng is not None and noise > 0.0:
            value += abs(value) * noise * float(rng.standard_normal())
        return value

    def flat(self) -> list[float]:
        """The table as Webots' ``getLookupTable`` returns it."""
        return [number for row in self.rows for number in row]


#: A sensor model of a robot profile: its kind (``infrared``, ``range``, ``ground``) and table.
SensorModel = tuple[str, tuple[Row, ...]]


@functools.lru_cache(maxsize=64)
def profile_sensor_models(
    profile: RobotProfile,
) -> tuple[tuple[SensorModel, ...], tuple[SensorModel, ...]]:
    """The models of ``profile``'s distance sensors and of its ground sensors, each in the
    profile's order (the order of the simulator's readings): the kind of the model a sensor
    reads through and that model's table, the one the simulator reads the sensor with (a copy
    of a built-in profile with a world's own tables holds them)."""
    layout = load_toml(profile.to_toml(), f"the {profile.name} profile")
    models = layout.get("models", {})

    def model_of(sensor: dict[str, Any]) -> SensorModel:
        model = models[sensor["model"]]
        rows = tuple(
            (float(row[0]), float(row[1]), float(row[2]) if len(row) > 2 else 0.0)
            for row in model["table"]
        )
        return str(model["kind"]), rows

    distance = tuple(model_of(sensor) for sensor in layout.get("distance_sensors", []))
    ground = tuple(model_of(sensor) for sensor in layout.get("ground_sensors", []))
    return distance, ground


class _Tabled:
    """Mixin of a sensor with a lookup table: ``getLookupTable`` and ``lookup_table``."""

    _table: LookupTable

    def getLookupTable(self) -> list[float]:
        """The lookup table as Webots returns it."""
        return self._table.flat()

    lookup_table = webots_property("getLookupTable")


class Sampled:
    """Mixin of what is read every sampling period: ``getSamplingPeriod`` and the
    ``sampling_period`` property (assigning it enables or disables)."""

    _period_ms: int
    #: The C function names Webots' messages quote.
    _api: ClassVar[str] = "wb_sensor"
    _warned_disabled = False

    def enable(self, samplingPeriod: int) -> None:
        raise NotImplementedError

    def disable(self) -> None:
        raise NotImplementedError

    def getSamplingPeriod(self) -> int:
        """The sampling period in ms, 0 when disabled."""
        return self._period_ms

    @property
    def sampling_period(self) -> int:
        """The sampling period in ms (property style); assigning it enables or disables."""
        return self._period_ms

    @sampling_period.setter
    def sampling_period(self, period: int | None) -> None:
        if period:
            self.enable(period)
        else:
            self.disable()

    def _checked_period(self, samplingPeriod: int) -> int | None:
        """The sampling period as an integer; None, with Webots' message, when negative."""
        return sampling_period(samplingPeriod, f"{self._api}_enable")

    def _warn_disabled(self, function: str) -> None:
        """Prints Webots' message for a read of a disabled device, once."""
        if self._period_ms == 0 and not self._warned_disabled:
            self._warned_disabled = True
            _print_error(
                f"Error: {self._api}_{function}() called for a disabled device! "
                f"Please use: {self._api}_enable()."
            )


def _internal(cls: type) -> bool:
    """Whether a class is one of mazesim's own device classes (not a controller's subclass)."""
    return cls.__module__.startswith("mazesim.")


def _already_built(init: Callable[..., None]) -> Callable[..., None]:
    """Wraps a mazesim device class's ``__init__`` so that a controller's subclass may call
    ``super().__init__(name)`` as in Webots: on a device the robot already built, it does
    nothing."""

    @functools.wraps(init)
    def initialise(self: Any, *args: Any, **kwargs: Any) -> None:
        if len(args) <= 1 and not kwargs and "_simulation" in vars(self):
            return
        if _names_its_device(self, args, kwargs):
            # A controller's subclass called without its device's name, whose own __init__
            # names it here: the robot's device becomes an instance of the subclass and this
            # instance shares its state while that __init__ goes on; the class call then
            # gives the robot's device itself.
            device = _robot_device(type(self), args[0])
            if device is not None:
                device.__class__ = type(self)
                device.__dict__.update(vars(self))  # what it set before naming its device
                self.__dict__ = device.__dict__
                _ADOPTED[id(self)] = device
            return
        init(self, *args, **kwargs)

    return initialise


#: The robot's devices that a controller's subclass instance named in its ``super().__init__``
#: call, by the instance's id, while the subclass's ``__init__`` runs (see ``_DeviceType``).
_ADOPTED: dict[int, Any] = {}


def _names_its_device(device: Any, args: tuple[Any, ...], kwargs: dict[str, Any]) -> bool:
    """Whether ``super().__init__(name)`` is called on a controller's subclass instance that is
    not yet a device of the robot."""
    return (
        len(args) == 1
        and not kwargs
        and isinstance(args[0], (str, int))
        and not _internal(type(device))
        and "_simulation" not in vars(device)
    )


def _robot_device(cls: type, key: str | int) -> Any:
    """The robot's device of that name (or index) for ``cls``, or None with Webots' message:
    no Robot yet, or a device of another type than ``cls``'s."""
    from mazesim.webots.robot import Robot

    robot = Robot.created
    if robot is None:
        _print_error(f'Error: {cls.__name__}("{key}") needs the Robot: create it first.')
        return None
    device = robot.getDeviceByIndex(key) if isinstance(key, int) else robot.getDevice(key)
    if device is None or _internal(cls) or isinstance(device, cls):
        return device
    if not issubclass(cls, type(device)):
        _print_error(
            f'Error: {cls.__name__}("{key}"): the device "{key}" is a '
            f"{type(device).__name__}, not a {cls.__mro__[1].__name__}."
        )
        return None
    return device


class _DeviceType(type):
    """Lets a controller write ``DistanceSensor("ps0")``, as older Webots controllers do: a
    device class called with only a name gives the robot's device of that name. A controller's
    own subclass (``class EpuckMotor(Motor)``) called with a name and any other arguments gives
    that device too, made an instance of the subclass, whose ``__init__`` runs on it; one called
    without a name (``class EpuckCamera(Camera)`` whose ``__init__`` calls
    ``super().__init__("camera")``) gives the device its ``__init__`` names there."""

    def __init__(cls, name: str, bases: tuple[type, ...], namespace: dict[str, Any]) -> None:
        super().__init__(name, bases, namespace)
        if "__init__" in namespace and _internal(cls):
            cls.__init__ = _already_built(namespace["__init__"])  # type: ignore[misc]

    def __call__(cls, *args: Any, **kwargs: Any) -> Any:
        subclass = not _internal(cls)
        named = bool(args) and isinstance(args[0], (str, int))
        if (named and len(args) == 1 and not kwargs) or (subclass and named):
            device = _robot_device(cls, args[0])
            if device is None or not subclass or isinstance(device, cls):
                return device
            device.__class__ = cls
            cls.__init__(device, *args, **kwargs)  # type: ignore[misc]
            return device
        if subclass:
            # A subclass whose own __init__ takes no name and gives one to super().__init__.
            made: Any = object.__new__(cls)  # type: ignore[arg-type]
            cls.__init__(made, *args, **kwargs)  # type: ignore[misc]
            # None when it named no device of the robot (Webots' message is printed).
            return _ADOPTED.pop(id(made), None)
        return super().__call__(*args, **kwargs)


class Device(NotSimulated, metaclass=_DeviceType):
    """A device of the robot, found by its name."""

    #: Webots' node type of the device (``Node.DISTANCE_SENSOR``...), set by each class.
    _node_type: ClassVar[int] = 0

    def __init__(self, name: str, simulation: RobotSimulation) -> None:
        self._name = name
        self._simulation = simulation

    def getName(self) -> str:
        """The device's name, e.g. ``"ps0"``."""
        return self._name

    def _restart(self) -> None:
        """What Webots' reset (a supervisor's ``simulationReset``) restarts in the device: its
        noise stream, when it has one of its own."""
        if getattr(self, "_rng", None) is not None:
            self._rng = noise_stream(self._simulation, self._name)

    def getModel(self) -> str:
        """The device's model string (empty, as for the e-puck's devices in Webots)."""
        return ""

    def getNodeType(self) -> int:
        """Webots' node type of the device (a ``Node`` constant)."""
        return self._node_type

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self._name!r})"


def battery_energy(simulation: RobotSimulation, steps: int | None = None) -> float:
    """The energy (J) left in the robot's battery after ``steps`` basic steps (by default, the
    steps taken), as Webots drains it (``WbRobot::postPhysicsStep``): the ``battery`` field's
    first value less the robot's ``cpuConsumption`` (W) for each basic step, down to 0; its
    motors consume nothing here (mazesim has no torques) and nothing recharges it (no
    Charger). -1 for a robot without a battery, as Webots gives it."""
    scene = simulation.scene
    battery = getattr(scene, "robot_battery", ())
    if not battery:
        return -1.0
    taken = simulation.steps if steps is None else steps
    used = scene.robot_cpu_consumption * simulation.basic_time_step_ms / 1000.0 * taken
    return max(0.0, battery[0] - used) if battery[0] > 0.0 else battery[0]


def battery_ran_out(simulation: RobotSimulation) -> bool:
    """Whether the robot's battery started with energy and has none left: Webots drains a
    battery and powers its robot off only while its energy is above 0
    (``WbRobot::postPhysicsStep``, ``setCurrentEnergy``), so a battery that starts at 0 (a
    world saved after its robot ran out) leaves the robot powered on."""
    battery: tuple[float, ...] = tuple(getattr(simulation.scene, "robot_battery", ()))
    if not battery:
        return False
    return battery[0] > 0.0 and battery_energy(simulation) == 0.0


def discretize(value: float, resolution: float) -> float:
    """``value`` to a sensor's ``resolution`` as Webots rounds it
    (``WbMathsUtilities::discretize``: ``int(value / resolution + 0.5) * resolution``, the cast
    truncating towards 0, so that -0.7 of a step reads 0); NaN and infinities as they are, and
    a value too far out for a whole number of steps to hold (1e308 to a resolution of 0.01)."""
    steps = value / resolution + 0.5
    if not math.isfinite(steps):
        return value
    return math.trunc(steps) * resolution


class _Sensor(Sampled, Device):
    """A sampled sensor: enable, disable, getSamplingPeriod, getValue (Webots' ``Sensor``)."""

    _webots_name: ClassVar[str] = "Sensor"

    def __init__(self, name: str, simulation: RobotSimulation) -> None:
        super().__init__(name, simulation)
        self._period_ms = 0
        self._period_steps = 0
        self._enabled_at = 0
        self._value: Any = math.nan
        #: Whether a reading has been taken (the getters of :func:`derived_reading` answer NaN
        #: until then).
        self._has_reading = False
        #: The node's ``resolution``: each value read is rounded to it (-1, Webots' default:
        #: not at all).
        self._resolution = -1.0

    def enable(self, samplingPeriod: int) -> None:
        """Reads the sensor every ``samplingPeriod`` ms (rounded up to whole basic steps)."""
        period = self._checked_period(samplingPeriod)
        if period is None:
            return
        if period == 0:
            self.disable()
            return
        basic = self._simulation.basic_time_step_ms
        self._period_ms = period
        self._period_steps = max(1, math.ceil(period / basic - 1e-9))
        self._enabled_at = self._simulation.steps

    def disable(self) -> None:
        """Stops reading; ``getValue`` keeps the last reading."""
        self._period_ms = 0
        self._period_steps = 0

    def _reading(self, function: str) -> Any:
        self._warn_disabled(function)
        return self._value

    def _after_step(self) -> None:
        """Takes a reading when a sampling period ends at this step."""
        if (
            self._period_steps
            and (self._simulation.steps - self._enabled_at) % self._period_steps == 0
        ):
            self._value = self._resolved(self._read())
            self._has_reading = True

    def _resolved(self, value: Any) -> Any:
        """A reading (a number or a list of them) to the sensor's resolution."""
        if self._resolution <= 0.0:
            return value
        if isinstance(value, list):
            return [discretize(float(v), self._resolution) for v in value]
        return discretize(float(value), self._resolution)

    def _read(self) -> Any:
        raise NotImplementedError


class _ScalarSensor(_Sensor):
    """A sensor with one value: ``getValue`` and the ``value`` property."""

    def getValue(self) -> float:
        """The last reading; NaN before the first sampling period has passed."""
        return float(self._reading("get_value"))

    value = webots_property("getValue")


class _VectorSensor(_Sensor):
    """A sensor with three values: ``getValues`` and the ``value`` property."""

    _width: ClassVar[int] = 3

    def __init__(self, name: str, simulation: RobotSimulation) -> None:
        super().__init__(name, simulation)
        self._value = [math.nan] * self._width

    def getValues(self) -> list[float]:
        """The last reading; NaNs before the first sampling period has passed."""
        return list(self._reading("get_values"))

    value = webots_property("getValues")


class DistanceSensor(_Tabled, _ScalarSensor):
    """An infra-red sensor: a proximity sensor ``ps0``..``ps7`` or a ground sensor ``gs0``..``gs2``.

    Readings are the raw values of Webots' e-puck model (about 4095 touching, 67 at 7 cm and
    beyond; ground: about 856 on white, 300 on black), or of the world's own ``lookupTable``
    of the sensor (:attr:`RobotSimulation.sensor_tables`; 0 through an empty one, as Webots
    reads then); the e-puck2's ``tof`` reads its distance in millimetres. ``getLookupTable``,
    ``getMinValue``, ``getMaxValue`` and the ranges come from the table the simulator reads
    the sensor with (:func:`profile_sensor_models`).
    """

    _node_type = node_type("DISTANCE_SENSOR")

    GENERIC = 0
    INFRA_RED = 1
    SONAR = 2
    LASER = 3
    _api = "wb_distance_sensor"

    def __init__(self, name: str, simulation: RobotSimulation, index: int, ground: bool) -> None:
        super().__init__(name, simulation)
        self._index = index
        self._ground = ground
        # The table the simulator reads this sensor with: the world's own lookupTable of it
        # when the simulation reads through that, else its model's in the robot's profile (a
        # world of several robots gives each robot's process the built-in profile alone).
        kind, table = profile_sensor_models(simulation.simulator.robot)[ground][index]
        own = simulation.sensor_tables.get(name)
        self._table = LookupTable(table if own is None else own)
        self._kind = kind

    def _read(self) -> float:
        if not self._table.rows:
            # ``lookupTable []``: Webots' DistanceSensor reads 0 through no table.
            return 0.0
        readings = (
            self._simulation.ground_readings()
            if self._ground
            else self._simulation.distance_readings()
        )
        return float(readings[self._index])

    def getMinValue(self) -> float:
        """The smallest value the table gives."""
        return min((row[1] for row in self._table.rows), default=0.0)

    def getMaxValue(self) -> float:
        """The largest value the table gives."""
        return max((row[1] for row in self._table.rows), default=0.0)

    def getType(self) -> int:
        """The world's ``type`` of the sensor (:attr:`RobotSimulation.sensor_types`), else
        :data:`GENERIC` for a sensor its profile reads by distance alone (a ``range`` model: the
        e-puck2's time-of-flight ``tof``), :data:`INFRA_RED` for the others."""
        given = self._simulation.sensor_types.get(self._name)
        if given is None:
            return self.GENERIC if self._kind == "range" else self.INFRA_RED
        return sensor_type(given)

    def getMaxRange(self) -> float:
        """The table's last distance (m)."""
        return self._table.rows[-1][0] if self._table.rows else 0.0

    def getMinRange(self) -> float:
        """The table's first distance (m)."""
        return self._table.rows[0][0] if self._table.rows else 0.0

    def getAperture(self) -> float:
        """The sensor's ``aperture`` (rad): an E-puck proximity sensor's, 0.1, as its
        ``E-puckDistanceSensor`` PROTO sets it (R2022a-R2025a); another's 0 (one ray)."""
        if not self._ground and self._kind != "range" and re.fullmatch(r"ps[0-7]", self._name):
            return EPUCK_PROXIMITY_APERTURE
        return 0.0


class PositionSensor(_ScalarSensor):
    """A wheel encoder: the wheel's angle in radians."""

    _node_type = node_type("POSITION_SENSOR")

    ROTATIONAL = 0
    LINEAR = 1
    _api = "wb_position_sensor"

    def __init__(self, name: str, simulation: RobotSimulation, side: int) -> None:
        super().__init__(name, simulation)
        self._side = side
        self._motor: Motor | None = None
        #: The node's ``noise`` (rad): the standard deviation of the gaussian Webots adds to
        #: each reading before rounding it (``WbPositionSensor::position``); 0: none.
        self._noise = 0.0
        self._rng: np.random.Generator | None = None

    def _set_noise(self, noise: float) -> None:
        """Adds ``noise`` (rad, the node's ``noise`` field) times a gaussian draw of the run's
        seed to each reading, before its rounding, as Webots does (none in a run without
        noise)."""
        self._noise = noise
        self._rng = noise_stream(self._simulation, self._name) if noise > 0.0 else None

    def _angle(self) -> float:
        """The joint's position now (rad)."""
        return self._simulation.wheel_angles()[self._side]

    def _read(self) -> float:
        angle = self._angle()
        if self._rng is not None:
            angle += self._noise * float(self._rng.standard_normal())
        return angle

    def getType(self) -> int:
        """:data:`ROTATIONAL`."""
        return self.ROTATIONAL

    def getMotor(self) -> Motor | None:
        """The motor of the same wheel."""
        return self._motor

    def getBrake(self) -> None:
        """None: the e-puck's wheels have no brake device."""
        return None


class Motor(Device):
    """A wheel motor: position control by default, velocity control after ``setPosition(inf)``."""

    _node_type = node_type("ROTATIONAL_MOTOR")

    ROTATIONAL = 0
    LINEAR = 1

    def __init__(
        self, name: str, simulation: RobotSimulation, side: int, sensor: PositionSensor
    ) -> None:
        super().__init__(name, simulation)
        self._side = side
        self._sensor = sensor
        self._max_velocity = float(simulation.simulator.robot.max_wheel_speed)
        # As in Webots (WbMotor::preFinalize), position control starts at the joint's position:
        # 0, or where a world saved after a run left the wheel.
        self._target_position = float(simulation.scene.wheel_positions[side])
        # As in Webots, the velocity starts at maxVelocity (the speed of position control).
        self._velocity = self._max_velocity
        self._acceleration = -1.0
        #: The wheel's speed at the last step, which a set acceleration ramps from.
        self._current_speed = 0.0
        #: What the controller set last, as Webots' controller library keeps it (a reset of
        #: the world restarts the motor, not this): the getters' target position and velocity.
        self._set_points = (self._target_position, self._velocity)
        self._warned_clamp = False
        self._control = PositionControl()
        #: The torque the motor may use (N m): its ``maxTorque`` until the controller sets
        #: another; with none it does not drive (:meth:`setAvailableTorque`).
        self._available_torque = self._max_torque = MAX_TORQUE
        #: The torque feedback's sampling period (ms; 0: disabled).
        self._feedback_period = 0

    def _restart(self) -> None:
        """As Webots' reset does (WbMotor::reset): position control again, at the joint's
        position the reset restores, with ``maxVelocity``, until the controller sets the
        position or the velocity again; the getters still read what it set last, as Webots'
        controller library keeps it."""
        self._target_position = float(self._simulation.scene.wheel_positions[self._side])
        self._velocity = self._max_velocity
        self._current_speed = 0.0
        self._control.set_gains(self._control.gains)

    def setPosition(self, position: float) -> None:
        """Turns the wheel to ``position`` rad; ``float('inf')`` switches to velocity control."""
        position = float(position)
        if math.isnan(position):
            _print_error(
                "Error: wb_motor_set_position() called with an invalid 'position' argument (NaN)."
            )
            return
        self._target_position = position
        self._set_points = (position, self._set_points[1])

    def setVelocity(self, velocity: float) -> None:
        """Sets the wheel speed in rad/s (the speed limit of position control)."""
        velocity = float(velocity)
        if math.isnan(velocity):
            _print_error(
                "Error: wb_motor_set_velocity() called with an invalid 'velocity' argument.(NaN)"
            )
            return
        if velocity < 0.0 and not math.isinf(self._set_points[0]):
            _print_error(
                "Error: wb_motor_set_velocity() called with negative 'velocity' argument in "
                f"position control mode ({self._set_points[0]:g})."
            )
            return
        if abs(velocity) > self._max_velocity and not self._warned_clamp:
            self._warned_clamp = True
            _print_error(
                f'WARNING: RotationalMotor "{self._name}": The requested velocity {velocity:g} '
                f"exceeds 'maxVelocity' = {self._max_velocity:g}."
            )
        self._velocity = velocity
        self._set_points = (self._set_points[0], velocity)

    def setAcceleration(self, acceleration: float) -> None:
        """The most the wheel's speed changes per second (rad/s^2), as Webots' motor ramps its
        velocity towards the one asked (``WbMotor::computeCurrentDynamicVelocity``); -1 (the
        default): at once. Negative values but -1 are refused with Webots' error."""
        acceleration = float(acceleration)
        if math.isnan(acceleration):
            _print_error(
                "Error: wb_motor_set_acceleration() called with an invalid 'acceleration' "
                "argument (NaN)."
            )
            return
        if acceleration < 0.0 and acceleration != -1.0:
            _print_error(
                "Error: wb_motor_set_acceleration() called with negative 'acceleration' argument."
            )
            return
        self._acceleration = acceleration

    def getTargetPosition(self) -> float:
        """The position set last (``inf`` in velocity control)."""
        return self._set_points[0]

    def getVelocity(self) -> float:
        """The velocity set last."""
        return self._set_points[1]

    def getMaxVelocity(self) -> float:
        """The motor's speed limit in rad/s (6.28 for the e-puck)."""
        return self._max_velocity

    def getAcceleration(self) -> float:
        """The acceleration set last (-1: unlimited)."""
        return self._acceleration

    def getMinPosition(self) -> float:
        """0: the wheel has no position limit."""
        return 0.0

    def getMaxPosition(self) -> float:
        """0: the wheel has no position limit."""
        return 0.0

    def getType(self) -> int:
        """:data:`ROTATIONAL`."""
        return self.ROTATIONAL

    def getPositionSensor(self) -> PositionSensor:
        """The encoder of the same wheel."""
        return self._sensor

    def getBrake(self) -> None:
        """None: the e-puck's wheels have no brake device."""
        return None

    def getMultiplier(self) -> float:
        """1: the motor is not coupled."""
        return 1.0

    def setControlPID(self, p: float, i: float, d: float) -> None:
        """The gains of position control, as Webots' ``controlPID`` field: the wheel turns
        towards its target at ``p e + i sum(e dt) + d de/dt`` (at most the velocity set), e
        the target minus the position; the sum and the last error start again from 0."""
        gains = (float(p), float(i), float(d))
        if any(math.isnan(g) for g in gains):
            _print_error("Error: wb_motor_set_control_pid() called with an invalid argument (NaN).")
            return
        if gains[0] <= 0.0:
            _print_error(
                f"Error: wb_motor_set_control_pid(): 'controlP' (currently {gains[0]:g}) must "
                "be positive."
            )
            return
        if gains[1] < 0.0 or gains[2] < 0.0:
            _print_error(
                "Error: wb_motor_set_control_pid(): 'controlI' and 'controlD' must be non-negative."
            )
            return
        self._control.set_gains(gains)

    def setAvailableTorque(self, torque: float) -> None:
        """The torque the motor may use (N m), at most its ``maxTorque`` (Webots warns
        beyond). With 0 the motor has no control, as in Webots: its wheel does not drive,
        whatever velocity or position is asked, until a torque is given back; any other
        value drives the wheel at the commanded speed (mazesim's wheels are driven by
        speed, not torque)."""
        torque = float(torque)
        if math.isnan(torque) or torque < 0.0:
            _print_error(
                "Error: wb_motor_set_available_torque() called with negative 'torque' argument."
            )
            return
        if torque > self._max_torque:
            _print_error(
                f'WARNING: RotationalMotor "{self._name}": The requested available motor '
                f"torque {torque:g} exceeds 'maxTorque' = {self._max_torque:g}"
            )
        self._available_torque = torque

    def setTorque(self, torque: float) -> None:
        """Accepted; mazesim's wheels are driven by speed."""

    setAvailableForce = setAvailableTorque
    setForce = setTorque

    def getAvailableTorque(self) -> float:
        """The torque set last by :meth:`setAvailableTorque`; the ``maxTorque`` before."""
        return self._available_torque

    def getMaxTorque(self) -> float:
        """The motor's ``maxTorque`` (N m): 10, Motor's default, which the E-puck PROTO
        keeps."""
        return self._max_torque

    getAvailableForce = getAvailableTorque
    getMaxForce = getMaxTorque

    def enableTorqueFeedback(self, samplingPeriod: int) -> None:
        """Enables the torque feedback (0 disables it); it reads 0 N m, as no torque is
        simulated."""
        period = sampling_period(samplingPeriod, "wb_motor_enable_torque_feedback")
        if period is not None:
            self._feedback_period = period

    def disableTorqueFeedback(self) -> None:
        """Disables the torque feedback."""
        self._feedback_period = 0

    def getTorqueFeedback(self) -> float:
        """0 while enabled (no torque is simulated); NaN while disabled, Webots' value of a
        feedback never sampled."""
        return 0.0 if self._feedback_period else math.nan

    def getTorqueFeedbackSamplingPeriod(self) -> int:
        """The period given to :meth:`enableTorqueFeedback` (ms), 0 when disabled."""
        return self._feedback_period

    enableForceFeedback = enableTorqueFeedback
    disableForceFeedback = disableTorqueFeedback
    getForceFeedback = getTorqueFeedback
    getForceFeedbackSamplingPeriod = getTorqueFeedbackSamplingPeriod

    velocity = webots_property("getVelocity", "setVelocity")

    acceleration = webots_property("getAcceleration", "setAcceleration")

    def _wheel_speed(self, angle: float) -> float:
        """The wheel speed (rad/s) for the next step, the wheel being at ``angle``: the motor
        control's, reached at once or, with an acceleration set, ramped towards from the last
        step's by at most the acceleration times the step."""
        if self._available_torque == 0.0 or battery_ran_out(self._simulation):
            # Webots: "no control" (WbMotor::computeCurrentDynamicVelocity); a battery that ran
            # out powers the motors off (WbMotor::powerOn), leaving them none.
            self._current_speed = 0.0
            return 0.0
        control = None
        if not math.isinf(self._target_position):
            dt = self._simulation.basic_time_step_ms / 1000.0
            control = self._control.output(self._target_position - angle, dt)
        speed = motor_speed(
            self._target_position, self._velocity, self._max_velocity, angle, control
        )
        if self._acceleration >= 0.0:
            most = self._acceleration * self._simulation.basic_time_step_ms / 1000.0
            speed = max(self._current_speed - most, min(self._current_speed + most, speed))
        self._current_speed = speed
        return speed

    def _last_command(self, angle: float) -> WheelCommand:
        """The motor's commands as they stand, the wheel being at ``angle``: what drives the
        wheel once the controller has ended (:mod:`mazesim.webots.last_commands`)."""
        return WheelCommand(
            self._target_position,
            self._velocity,
            self._max_velocity,
            angle,
            self._control.gains[0],
            self._available_torque != 0.0,
        )


class LED(Device):
    """An LED; mazesim draws no light, it only remembers the value."""

    _node_type = node_type("LED")

    def __init__(self, name: str, simulation: RobotSimulation) -> None:
        super().__init__(name, simulation)
        self._value = 0

    def set(self, value: bool | int) -> None:
        """Switches the LED on (non-zero, True) or off (0, False): Webots' ``LED.set`` takes a
        bool too (``Union[bool, int]``), as ``led.set(ps0.getValue() > 80)`` writes it."""
        self._value = int(value)

    def get(self) -> int:
        """The value set last."""
        return self._value
