"""Webots' ``Robot``: the e-puck a controller drives, its devices and its clock."""

from __future__ import annotations

import difflib
import math
import os
import sys
import time
import warnings
from typing import Any, ClassVar

from mazesim.errors import InvalidArgumentError, _shortened, _shown
from mazesim.webots import simulation as _simulations
from mazesim.webots.devices import (
    MAX_SAMPLING_PERIOD_MS,
    battery_energy,
    sampling_period,
)
from mazesim.webots.equipment import Equipment
from mazesim.webots.keyboard import Joystick, Keyboard, Mouse
from mazesim.webots.node_types import node_type
from mazesim.webots.scene import EPUCK_TYPES
from mazesim.webots.termination import GRACE_SECONDS, unwind_controller
from mazesim.webots.webots_api import NotSimulated

__all__ = ["ControllerStopped", "Robot"]


class ControllerStopped(BaseException):
    """Raised in a controller that calls ``Robot.step`` after it returned -1: the run is over.

    It derives from ``BaseException`` so that a controller's ``except Exception`` does not
    swallow it; ``mazesim webots run`` treats it as the controller's normal end.
    """


#: Why a controller that went on after its run's end was stopped.
STOPPED_MESSAGE = (
    f"the controller went on for more than {GRACE_SECONDS:g} s of real time after Robot.step "
    "returned -1: stopped, as Webots ends such a controller"
)

#: The E-puck PROTOs (Webots 7's ``EPuck``, the ENU variants): their ``model`` is the PROTO's.
EPUCK_PROTO_TYPES = ("E-puck", "E-puck_enu", "E-Puck_enu", "EPuck")
#: The e-puck's ground sensors, which Webots' E-puck has only with its ground sensors module.
GROUND_SENSOR_NAMES = ("gs0", "gs1", "gs2")

#: The deprecated per-type getters of Webots' Robot (all are ``getDevice`` now).
DEPRECATED_GETTERS = (
    "getAccelerometer",
    "getAltimeter",
    "getBrake",
    "getCamera",
    "getCompass",
    "getConnector",
    "getDisplay",
    "getDistanceSensor",
    "getEmitter",
    "getGPS",
    "getGyro",
    "getInertialUnit",
    "getLED",
    "getLidar",
    "getLightSensor",
    "getMotor",
    "getPen",
    "getPositionSensor",
    "getRadar",
    "getRangeFinder",
    "getReceiver",
    "getSkin",
    "getSpeaker",
    "getTouchSensor",
    "getVacuumGripper",
)


def _deprecated_getter(getter: str) -> Any:
    # Webots' own message spells getLED as getLed.
    spelled = "getLed" if getter == "getLED" else getter

    def get(self: Robot, name: str) -> Any:
        warnings.warn(
            f"DEPRECATION: Robot.{spelled} is deprecated, please use Robot.getDevice instead.",
            DeprecationWarning,
            stacklevel=2,
        )
        return self.getDevice(name)

    get.__name__ = getter
    get.__doc__ = "Deprecated in Webots: use :meth:`getDevice`."
    return get


def _answer_the_end(simulation: Any) -> int:
    """Notes that the run's end was answered to ``Robot.step`` (-1), and when: the controller
    then has :data:`GRACE_SECONDS` of wall-clock time to end."""
    simulation.ended = True
    simulation.ended_at = time.monotonic()
    return -1


def _equipment_property(device: str) -> Any:
    """The robot's ``keyboard``, ``mouse`` or ``joystick`` as a property that a controller's
    ``Robot`` subclass may set to its own object, as in Webots."""
    key = f"_{device}_set"
    return property(
        lambda self: (
            self.__dict__[key] if key in self.__dict__ else getattr(self._equipment, device)
        ),
        lambda self, value: self.__dict__.__setitem__(key, value),
        doc=f"The {device}; a controller's ``Robot`` subclass may keep its own ``self.{device}``.",
    )


class Robot(NotSimulated):
    """The e-puck the controller drives (only one per controller process, as in Webots)."""

    EVENT_QUIT = -1
    EVENT_NO_EVENT = 0
    EVENT_MOUSE_CLICK = 1
    EVENT_MOUSE_MOVE = 2
    EVENT_KEYBOARD = 4
    EVENT_JOYSTICK_BUTTON = 8
    EVENT_JOYSTICK_AXIS = 16
    EVENT_JOYSTICK_POV = 32
    MODE_SIMULATION = 0
    MODE_CROSS_COMPILATION = 1
    MODE_REMOTE_CONTROL = 2
    created: ClassVar[Robot | None] = None
    _simulation: _simulations.RobotSimulation
    _equipment: Equipment
    _custom_data: str
    #: The number of the last supervisor's write of ``customData`` read (0: none).
    _custom_data_written = 0
    #: The names ``getDevice`` found no device of, in the order asked.
    _missing_devices: tuple[str, ...] = ()
    #: The battery sensor's sampling period (ms), in basic steps, and the step it was enabled.
    _battery_sampling: tuple[int, int, int] = (0, 0, 0)
    #: The battery's last reading when its sensor was disabled.
    _battery_kept = math.nan

    def __init__(self) -> None:
        """Attaches to the prepared simulation and finds the robot's devices.

        Raises:
            InvalidArgumentError: No simulation was prepared (see :func:`mazesim.webots.prepare`).
        """
        simulation = _simulations.current()
        #: The e-puck device names the node lacks that a hint was printed for.
        self._warned_lacked: set[str] = set()
        earlier = Robot.created
        if earlier is not None and earlier._simulation is simulation:
            print(
                "Error: only one Robot instance can be created per controller process.",
                file=sys.stderr,
            )
            self._simulation = simulation
            self._equipment = earlier._equipment
            self._custom_data = earlier._custom_data
            return
        self._simulation = simulation
        self._equipment = Equipment(simulation)
        self._custom_data = simulation.scene.robot_custom_data
        # Only a whole robot is the process's one: a construction that raised leaves none.
        Robot.created = self

    # --- the robot -------------------------------------------------------------------------

    def getBasicTimeStep(self) -> float:
        """The world's basic time step in milliseconds (``WorldInfo.basicTimeStep``)."""
        return self._simulation.basic_time_step_ms

    def getTime(self) -> float:
        """Simulated seconds since the start, or since a supervisor last reset the world."""
        return self._simulation.clock

    def getName(self) -> str:
        """The robot's name: the world's ``name`` field of the robot (a project robot PROTO's
        declared default when the instance writes none), else its node type's default (the
        E-puck's ``"e-puck"``, a plain Robot's ``"robot"``)."""
        return self._simulation.robot_name

    def getModel(self) -> str:
        """The robot's model as Webots reports it: the E-puck PROTO's ``model`` field,
        "GCtronic e-puck" (``version "2"``: "GCtronic e-puck2"); any other robot node's own
        ``model`` field (a project PROTO's once expanded), empty by default."""
        own = self._simulation.own_robot
        node_type = own.get("node_type")
        if node_type is not None and node_type not in EPUCK_PROTO_TYPES:
            return str(own.get("model_field") or "")
        profile = str(self._simulation.simulator.robot.name)
        if profile.startswith("e-puck"):
            return "GCtronic e-puck2" if profile == "e-puck2" else "GCtronic e-puck"
        return profile

    def getCustomData(self) -> str:
        """The robot's ``customData`` string: the world file's, or the last one set, by
        :meth:`setCustomData` or by a supervisor's write of the field (in a world of several
        robots, read after the world's next step)."""
        written = getattr(self._simulation.simulator, "custom_data", None)
        if written is not None and written[0] != self._custom_data_written:
            self._custom_data_written, self._custom_data = written
        return self._custom_data

    def setCustomData(self, data: str) -> None:
        """Sets the robot's ``customData`` string; in a world of several robots a supervisor
        reads it in the robot's node's field after the world's next step, as in Webots."""
        self._custom_data = str(data)
        if hasattr(self._simulation.simulator, "own_custom_data"):
            self._simulation.simulator.own_custom_data = self._custom_data

    getData = getCustomData
    setData = setCustomData

    def getSupervisor(self) -> bool:
        """Whether the robot is a supervisor: the world says so, or its controller made one and
        the world does not refuse it (:mod:`~mazesim.webots.supervisor_refusal`)."""
        return self._simulation.supervisor

    def getSynchronization(self) -> bool:
        """The robot's ``synchronization`` field (TRUE unless the world says FALSE), as Webots
        gives it. mazesim waits for every controller at every step whatever it says: a run
        without waiting would depend on how fast the controllers run."""
        return self._simulation.scene.synchronization

    def getMode(self) -> int:
        """:data:`MODE_SIMULATION`."""
        return self.MODE_SIMULATION

    def setMode(self, mode: int, arg: Any = None) -> None:
        """Only simulation is possible: any other mode prints Webots' error."""
        if mode != self.MODE_SIMULATION:
            print("Error: wb_robot_set_mode(): no remote control plugin.", file=sys.stderr)

    def getProjectPath(self) -> str:
        """The controller's project folder (the folder above ``controllers/``, else its own)."""
        folder = os.path.dirname(os.path.abspath(sys.argv[0] if sys.argv else "."))
        parent = os.path.dirname(folder)
        if os.path.basename(parent) == "controllers":
            return os.path.dirname(parent)
        return folder

    def getWorldPath(self) -> str:
        """The world file's path, or the world's name for a built-in world."""
        return str(self._simulation.report.get("path") or self._simulation.world.name)

    def getControllerName(self) -> str:
        """The controller's name, as the robot's ``controller`` field gives it in Webots: the
        name of the file that runs (without ``.py``)."""
        return os.path.splitext(os.path.basename(sys.argv[0] if sys.argv else ""))[0]

    def getControllerArguments(self) -> str:
        """The robot's ``controllerArgs`` as one string (``sys.argv[1:]`` joined by spaces)."""
        return " ".join(self._simulation.scene.controller_args)

    def getType(self) -> int:
        """Webots' node type of the robot: ``Node.ROBOT``."""
        return node_type("ROBOT")

    def getUrdf(self, prefix: str = "") -> str:
        """A minimal URDF of the robot (its name only: mazesim has no link tree)."""
        return f'<?xml version="1.0"?>\n<robot name="{prefix}{self.getName()}">\n</robot>\n'

    def waitForUserInputEvent(self, eventType: int, timeout: int) -> int:
        """:data:`EVENT_NO_EVENT`: a headless run has no user."""
        return self.EVENT_NO_EVENT

    def wwiSendText(self, text: str) -> None:
        """Accepted; there is no robot window."""

    def wwiReceiveText(self) -> None:
        """None: there is no robot window."""
        return None

    def batterySensorEnable(self, samplingPeriod: int) -> None:
        """Reads the battery every ``samplingPeriod`` ms (whole basic steps, rounded up)."""
        period = sampling_period(samplingPeriod, "wb_robot_battery_sensor_enable")
        if period is None:
            return
        basic = self._simulation.basic_time_step_ms
        self._battery_sampling = (
            period,
            max(1, math.ceil(period / basic - 1e-9)) if period else 0,
            self._simulation.steps,
        )

    def batterySensorDisable(self) -> None:
        """Stops reading the battery; the last reading stays."""
        period, steps, since = self._battery_sampling
        if steps:
            taken = (self._simulation.steps - since) // steps * steps
            self._battery_kept = (
                battery_energy(self._simulation, since + taken) if taken else math.nan
            )
        self._battery_sampling = (0, 0, 0)

    def batterySensorGetValue(self) -> float:
        """The energy (J) left in the robot's ``battery`` at the end of the last sampling
        period (see :func:`~mazesim.webots.devices.battery_energy`; -1 without a battery);
        NaN before the first period has passed."""
        _, steps, since = self._battery_sampling
        if not steps:
            return self._battery_kept
        taken = (self._simulation.steps - since) // steps * steps
        return battery_energy(self._simulation, since + taken) if taken else math.nan

    def batterySensorGetSamplingPeriod(self) -> int:
        """The sampling period set (ms); 0 while disabled."""
        return self._battery_sampling[0]

    def __del__(self) -> None:
        """Nothing, as in Webots' Python API made by SWIG (before R2023a), whose objects have
        a ``__del__`` that does nothing: a controller of that time calls ``robot.__del__()``
        and then ``exit()`` once :meth:`step` returns -1."""

    def step(self, time_step: float | None = None) -> int:
        """Runs the simulation for ``time_step`` ms (a whole number of basic steps, rounded up;
        the parameter has Webots' name since R2023a, ``robot.step(time_step=32)``).

        Args:
            time_step: Milliseconds to simulate; by default one basic time step.

        Returns:
            0, or -1 when the run's time is up, a supervisor (this robot's or, in a world run,
            another's) asked to quit, removed this robot or paused the simulation (it does
            not advance then; paused, ``step(0)`` returns 0 at once).

        Raises:
            InvalidArgumentError: ``time_step`` is negative, beyond Webots' C int or not a
                number.
            ControllerStopped: ``step`` was called again after it returned -1.
        """
        simulation = self._simulation
        basic = simulation.basic_time_step_ms
        duration = basic if time_step is None else float(time_step)
        if not (math.isfinite(duration) and 0.0 <= duration <= MAX_SAMPLING_PERIOD_MS):
            raise InvalidArgumentError(
                f"Robot.step expects a duration in ms from 0 to {MAX_SAMPLING_PERIOD_MS} "
                f"(Webots' C int), found {_shown(duration)}"
            )
        if simulation.ended:
            ended_at = simulation.ended_at if simulation.ended_at is not None else 0.0
            if time.monotonic() - ended_at > GRACE_SECONDS:
                # Webots kills such a controller; here its frames are unwound instead.
                simulation.stopped = True
                unwind_controller(ControllerStopped, STOPPED_MESSAGE)
            raise ControllerStopped("the run is over: Robot.step returned -1 before")
        if simulation.paused:
            if duration == 0.0:
                return 0
            if simulation.quit_status is None:
                print(
                    "mazesim: the supervisor paused the simulation (simulationSetMode(PAUSE)) "
                    "and nothing resumes it in a headless run: the run ends here",
                    file=sys.stderr,
                )
                simulation.quit_status = 0
        for _ in range(max(1, math.ceil(duration / basic - 1e-9))):
            if simulation.time_is_up or simulation.quit_status is not None:
                return _answer_the_end(simulation)
            self._equipment.advance()
            if simulation.world_over:
                # The world's run ended instead of taking this step (another robot's supervisor
                # quit it, or removed this robot): no time passed, and Webots answers the step
                # with the end, not with one step more.
                return _answer_the_end(simulation)
        return 0

    def stepBegin(self, time_step: float | None = None) -> int:
        """The first half of :meth:`step`: here the whole step (``stepEnd`` returns its
        result)."""
        self._pending = self.step(time_step)
        return 0 if self._pending == 0 else -1

    def stepEnd(self) -> int:
        """The result of the step :meth:`stepBegin` ran."""
        return int(getattr(self, "_pending", 0))

    # --- devices ---------------------------------------------------------------------------

    def getDevice(self, name: str) -> Any:
        """The device of that name, or None (with Webots' message) if the robot has none."""
        device = self._equipment.devices.get(str(name))
        if device is None:
            self._missing_devices = (*self._missing_devices, str(name))
            shown = _shortened(str(name))
            print(f'Device "{shown}" was not found on robot "{self.getName()}"', file=sys.stderr)
            similar = difflib.get_close_matches(str(name), list(self._equipment.devices), n=3)
            if similar:
                # Older worlds and other robots name devices otherwise ("left wheel", "ds0").
                print(
                    f"mazesim: the robot's devices with a name like {_shortened(repr(str(name)))}: "
                    + ", ".join(repr(found) for found in similar),
                    file=sys.stderr,
                )
            if hint := self._lacked_hint(str(name)):
                print(hint, file=sys.stderr)
        return device

    def _lacked_hint(self, name: str) -> str:
        """What mazesim says, once per name, when a controller asks for a device of the e-puck
        that the robot's node does not hold (the import's ``missing_devices``): Webots finds
        only the devices a node holds; empty for any other name, or said before (the ground
        sensors' module once for the three)."""
        lacked = self._simulation.report.get("missing_devices") or []
        module = name in GROUND_SENSOR_NAMES and self._simulation.scene.robot_type in EPUCK_TYPES
        said = "gs0..gs2" if module else name
        if name not in lacked or said in self._warned_lacked:
            return ""
        self._warned_lacked.add(said)
        if module:
            return (
                "mazesim: the world's E-puck has no ground sensors module: its node needs "
                "groundSensorsSlot [ E-puckGroundSensors { } ] for gs0..gs2, in Webots as here"
            )
        return (
            f"mazesim: the node of robot {_shown(self.getName())} holds no device "
            f"{_shortened(repr(name))} (an E-puck PROTO would have one): Webots finds only the "
            "devices a robot's node holds"
        )

    def _missing_devices_line(self) -> str:
        """The line that ends a controller's run stopped by a call on the None ``getDevice``
        gave (as Webots gives it) for a name the robot has no device of: the names asked for
        and the robot's devices; empty when every name asked for was found."""
        if not self._missing_devices:
            return ""
        asked = ", ".join(_shortened(repr(name)) for name in dict.fromkeys(self._missing_devices))
        have = ", ".join(repr(name) for name in self._equipment.devices)
        return (
            f"mazesim: getDevice returned None for {asked}: robot {_shown(self.getName())} has no "
            f"device of that name; its devices: {have}\n"
        )

    def getNumberOfDevices(self) -> int:
        """How many devices the robot has."""
        return len(self._equipment.devices)

    def getDeviceByIndex(self, index: int) -> Any:
        """The device at ``index``, or None (with Webots' message) out of range."""
        devices = list(self._equipment.devices.values())
        if not 0 <= int(index) < len(devices):
            print(
                f"Error: wb_robot_get_device_by_index(): index {index} is out of range "
                f"[0, {len(devices) - 1}].",
                file=sys.stderr,
            )
            return None
        return devices[int(index)]

    def getKeyboard(self) -> Keyboard:
        """The keyboard."""
        return self._equipment.keyboard

    keyboard = _equipment_property("keyboard")

    def keyboardEnable(self, samplingPeriod: int) -> None:
        """Webots' API before R2018a: ``getKeyboard().enable(samplingPeriod)``."""
        self._equipment.keyboard.enable(samplingPeriod)

    def keyboardDisable(self) -> None:
        """Webots' API before R2018a: ``getKeyboard().disable()``."""
        self._equipment.keyboard.disable()

    def keyboardGetKey(self) -> int:
        """Webots' API before R2018a: ``getKeyboard().getKey()``."""
        return self._equipment.keyboard.getKey()

    def getMouse(self) -> Mouse:
        """The mouse (no button is ever pressed)."""
        return self._equipment.mouse

    mouse = _equipment_property("mouse")

    def getJoystick(self) -> Joystick:
        """The joystick (never connected)."""
        return self._equipment.joystick

    joystick = _equipment_property("joystick")


for _getter in DEPRECATED_GETTERS:
    setattr(Robot, _getter, _deprecated_getter(_getter))
