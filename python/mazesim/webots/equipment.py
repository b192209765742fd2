"""The devices a robot carries in a run: the profile's, the e-puck's built-in ones, and those
the world mounts in its extension slots.

Names are Webots': ``left wheel motor`` / ``right wheel motor``, ``left wheel sensor`` /
``right wheel sensor``, the profile's distance sensors (``ps0``..``ps7``, and ``tof`` on the
e-puck2) and ground sensors (``gs0``..``gs2``), ``ls0``..``ls7``, ``led0``..``led9``,
``camera``, ``accelerometer``, ``gyro``, ``emitter``, ``receiver``, ``speaker``; then every
device of the import report's ``extension_devices``. A robot saved expanded that names its
wheels' motors or position sensors otherwise has them by its world's names; a robot's other
motors and their position sensors turn joints that move nothing (:mod:`mazesim.webots.joints`).
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Mapping, Sequence
from dataclasses import replace
from typing import Any

from mazesim.errors import _shown
from mazesim.webots.camera import Camera, CameraView, node_view
from mazesim.webots.devices import (
    EPUCK_PROXIMITY_APERTURE,
    LED,
    PROXIMITY_TABLE,
    Device,
    DistanceSensor,
    Motor,
    PositionSensor,
    _Sensor,
    device_side,
)
from mazesim.webots.differential_drive import EPUCK_WHEELS, DifferentialDrive
from mazesim.webots.distance_rays import MOST_RAYS
from mazesim.webots.frames import axes_or_none, camera_heading
from mazesim.webots.inert import Display, Pen, Speaker
from mazesim.webots.joints import JointMotor, JointPositionSensor, LinearJointMotor, pair_joints
from mazesim.webots.keyboard import Joystick, Keyboard, Mouse
from mazesim.webots.own_drive import wheel_names
from mazesim.webots.radio_devices import (
    E_PUCK_CHANNEL,
    Emitter,
    Receiver,
    emitter_from_fields,
    receiver_from_fields,
)
from mazesim.webots.robot_frames import Footprint, Mount, bounding_footprints, robot_mount
from mazesim.webots.scanners import RayLidar, RayRangeFinder
from mazesim.webots.scene import read_world_text
from mazesim.webots.sensors import (
    DISTANCE_SENSOR_APERTURE,
    GPS,
    Accelerometer,
    Compass,
    DeviceMount,
    Gyro,
    InertialUnit,
    LightSensor,
    RayDistanceSensor,
    TouchSensor,
)
from mazesim.webots.simulation import RobotSimulation

__all__ = ["Equipment", "extension_device"]

#: Number of LEDs of the e-puck (led0..led9; led8 is the body LED, led9 the front LED).
LED_COUNT = 10
#: Number of light sensors of the e-puck (ls0..ls7, beside ps0..ps7).
LIGHT_SENSOR_COUNT = 8
#: Height of the e-puck's light sensors above the floor (m).
LIGHT_SENSOR_HEIGHT = 0.033


def _names(profile: Any, attribute: str) -> list[str]:
    """A profile's sensor names, whether the binding gives them as a property or a method."""
    names = getattr(profile, attribute)
    return list(names() if callable(names) else names)


def _table(fields: Mapping[str, Any]) -> list[list[float]] | None:
    """A lookupTable field as rows of numbers (rows, or Webots' flat list), or None where the
    node has none; an empty one (``lookupTable []``) is kept: Webots reads through no table."""
    raw = fields.get("lookupTable")
    if not isinstance(raw, Sequence) or isinstance(raw, str):
        return None
    if all(isinstance(row, Sequence) for row in raw):
        return [[float(v) for v in row] for row in raw]
    flat = [float(v) for v in raw]
    return [flat[i : i + 3] for i in range(0, len(flat) - 2, 3)]


def light_sensor_mount(profile: Any, index: int) -> DeviceMount:
    """Where light sensor ``ls<index>`` sits: beside proximity sensor ``ps<index>`` (the
    e-puck's TCRT1000 packages hold both), at the sensors' height."""
    poses = profile.distance_sensor_poses()
    if index < len(poses):
        x, y, heading = (float(v) for v in poses[index][:3])
    else:
        x, y, heading = 0.0, 0.0, index * math.tau / LIGHT_SENSOR_COUNT
    return DeviceMount((x, y, LIGHT_SENSOR_HEIGHT), heading)


#: The ``model`` of Webots' ``E-puckDistanceSensor`` PROTO: a distance sensor of that model in an
#: extension slot reads through the e-puck's proximity table, as the PROTO's DistanceSensor does.
EPUCK_DISTANCE_SENSOR_MODEL = "e-puck distance sensor"

#: Devices reading a vector in their own frame (``_TableVector._device_frame``).
_DEVICE_FRAME_KINDS = frozenset({"Compass", "Accelerometer", "Gyro"})
#: The devices whose values Webots rounds to their node's ``resolution`` field (each value
#: read: ``WbDistanceSensor``, ``WbGps``, ``WbCompass``, ``WbAccelerometer``, ``WbGyro``,
#: ``WbLightSensor``, ``WbTouchSensor``, ``WbPositionSensor``); the InertialUnit rounds its
#: quaternion instead, which mazesim does not.
_RESOLVED_KINDS = frozenset(
    {
        "DistanceSensor",
        "GPS",
        "Compass",
        "Accelerometer",
        "Gyro",
        "LightSensor",
        "TouchSensor",
        "PositionSensor",
    }
)
#: The devices whose reading depends on their axes on the robot when a mount tilts them.
_TILTED_KINDS = _DEVICE_FRAME_KINDS | {"InertialUnit", "DistanceSensor"}
#: A LightSensor node's default ``lookupTable`` (Webots' reference manual, LightSensor): 1 W/m^2
#: reads 1000, without noise. The node's Accelerometer and Gyro have an empty one (the raw
#: value); the E-puck PROTO's own ls0-ls7, accelerometer and gyro carry tables of their own.
LIGHT_NODE_TABLE = ((0.0, 0.0, 0.0), (1.0, 1000.0, 0.0))
#: The devices that look along their -z axis in a file before R2022a, as a Camera does there
#: (Webots' Y-up device frame: x right, y up, z back), and along their x axis since.
_LOOKING_KINDS = frozenset({"Lidar", "RangeFinder"})


#: The E-puck PROTO's names of its wheels' motors and position sensors, left first.
_WHEEL_MOTORS = ("left wheel motor", "right wheel motor")
_WHEEL_SENSORS = ("left wheel sensor", "right wheel sensor")
#: The ``resolution`` of the E-puck PROTO's wheel PositionSensors (rad; "(2 * pi) / 1000" in the
#: PROTO's comment, written 0.00628), to which Webots rounds their readings.
EPUCK_WHEEL_SENSOR_RESOLUTION = 0.00628


def _own(entries: Sequence[Mapping[str, Any]], kind: str) -> list[Mapping[str, Any]]:
    """The import's entries of the devices of ``kind`` among the robot's own children."""
    return [
        entry
        for entry in entries
        if entry.get("type") == kind and entry.get("slot") == "children" and entry.get("name")
    ]


def _wheel_names(
    entries: Sequence[Mapping[str, Any]], kind: str, stock: tuple[str, str]
) -> tuple[list[str], list[Mapping[str, Any]]]:
    """The names of the e-puck's two wheel devices of ``kind`` (``RotationalMotor`` or
    ``PositionSensor``), left first, and the import's entries that give them.

    A robot saved expanded (a plain Robot node, the E-puck PROTO's tree written out) may name
    its wheels' devices otherwise (``left_motor``): the import lists those among the robot's own
    devices (``slot`` ``children``), and they are its wheels', as Webots finds them by the
    names the world gives. A name saying ``left`` or ``right`` is that wheel's; another takes
    the first wheel not yet named, the left before the right (the PROTO's order). A robot with
    more than two such devices of its own (an arm's motors besides) keeps the PROTO's names, and
    so do the position sensors of a robot with more than two motors of its own (not the e-puck's
    two wheels: see :mod:`mazesim.webots.joints`). A lone device naming neither wheel (a
    gripper's lift ``motor`` beside wheels that keep the PROTO's names, which the import does not
    list as the robot's own) is not a wheel's: renamed wheels come as a pair or say their side.
    """
    own = _own(entries, kind)
    if not own or len(own) > 2 or len(_own(entries, "RotationalMotor")) > 2:
        return list(stock), []
    if len(own) == 1 and not _names_a_side(str(own[0]["name"])):
        return list(stock), []
    names = list(stock)
    free = [0, 1]
    for entry in own:
        name = str(entry["name"])
        lower = name.lower()
        side = 0 if "left" in lower else 1 if "right" in lower else free[0]
        side = side if side in free else free[0]
        names[side] = name
        free.remove(side)
    return names, own


def _wheel_sensor_fields(name: str, renamed: Sequence[Mapping[str, Any]]) -> tuple[float, float]:
    """The ``resolution`` and ``noise`` of the wheel sensor ``name``: those of the world's own
    PositionSensor node of that name (a robot saved expanded; Webots' defaults -1 and 0 where it
    writes none), else the E-puck PROTO's (0.00628, no noise)."""
    for entry in renamed:
        if str(entry.get("name")) == name:
            fields = entry.get("fields")
            fields = fields if isinstance(fields, Mapping) else {}
            return _number_field(fields, "resolution", -1.0), _number_field(fields, "noise", 0.0)
    return EPUCK_WHEEL_SENSOR_RESOLUTION, 0.0


def _number_field(fields: Mapping[str, Any], name: str, default: float) -> float:
    """A node's number field as the import gives it, or Webots' ``default``."""
    value = fields.get(name)
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return float(value)
    return default


def _ray_count(fields: Mapping[str, Any]) -> int:
    """A DistanceSensor's ``numberOfRays`` (1 where it is left out or no number), at most
    :data:`~mazesim.webots.distance_rays.MOST_RAYS`."""
    count = _number_field(fields, "numberOfRays", 1.0)
    return int(min(count, MOST_RAYS)) if math.isfinite(count) else 1


def _names_a_side(name: str) -> bool:
    """Whether a device's name says which wheel it is (``left_motor``, ``encoder R``...)."""
    lower = name.lower()
    return "left" in lower or "right" in lower


def extension_device(simulation: RobotSimulation, entry: Mapping[str, Any]) -> Device | None:
    """The device for one entry of the import report's ``extension_devices``, or None when
    mazesim has no such device type (a warning is printed)."""
    kind = str(entry.get("type", ""))
    name = str(entry.get("name") or kind.lower())
    fields: Mapping[str, Any] = entry.get("fields") or {}
    yaw = float(entry.get("yaw", 0.0))
    if simulation.scene.y_up_devices and kind in _DEVICE_FRAME_KINDS:
        # The import gives the direction of the device's x axis; a Y-up PROTO's device reads
        # in a frame whose x is the robot's right when unturned (forward is its -z), which the
        # reading converts from the robot's frame: its forward is a quarter turn left of x.
        yaw += math.pi / 2
    axes = axes_or_none(entry.get("axes"))
    if simulation.scene.y_up_devices and kind in _LOOKING_KINDS and axes is not None:
        forward = (-axes[2][0], -axes[2][1], -axes[2][2])
        yaw, pitch = camera_heading(forward)
        entry = {**entry, "pitch": pitch}
    mount = _device_mount(simulation, entry, yaw, kind in _TILTED_KINDS)
    table = _table(fields)
    e_puck_sensor = fields.get("model") == EPUCK_DISTANCE_SENSOR_MODEL
    default = EPUCK_PROXIMITY_APERTURE if e_puck_sensor else DISTANCE_SENSOR_APERTURE
    aperture = float(fields.get("aperture", default))
    if table is None and e_puck_sensor:
        table = [list(row) for row in PROXIMITY_TABLE]
    north = simulation.scene.north or (0.0, 1.0)
    builders: dict[str, Callable[[], Device]] = {
        "GPS": lambda: GPS(name, simulation, mount, table),
        "Compass": lambda: Compass(name, simulation, mount, table, north),
        "Accelerometer": lambda: Accelerometer(name, simulation, mount, table or ()),
        "Gyro": lambda: Gyro(name, simulation, mount, table or ()),
        "InertialUnit": lambda: InertialUnit(name, simulation, mount, None),
        "TouchSensor": lambda: TouchSensor(name, simulation, mount, _bumper(simulation, name)),
        "DistanceSensor": lambda: RayDistanceSensor(
            name,
            simulation,
            mount,
            table,
            str(fields.get("type", "generic")),
            aperture,
            _number_field(fields, "redColorSensitivity", 1.0),
            _ray_count(fields),
            _number_field(fields, "gaussianWidth", 1.0),
        ),
        "LightSensor": lambda: LightSensor(
            name, simulation, LIGHT_NODE_TABLE if table is None else table, mount
        ),
        "LED": lambda: LED(name, simulation),
        "Camera": lambda: Camera(name, simulation, _camera_view(simulation, entry)),
        "Emitter": lambda: emitter_from_fields(name, simulation, fields, entry.get("axes")),
        "Receiver": lambda: receiver_from_fields(name, simulation, fields, entry.get("axes")),
        "Speaker": lambda: Speaker(name, simulation),
        "Display": lambda: Display(
            name,
            simulation,
            device_side(fields.get("width"), 64, f"Display {_shown(name)} width", 0),
            device_side(fields.get("height"), 64, f"Display {_shown(name)} height", 0),
        ),
        "Pen": lambda: Pen(name, simulation),
        "Lidar": lambda: RayLidar(name, simulation, mount, fields),
        "RangeFinder": lambda: RayRangeFinder(name, simulation, mount, fields),
        "RotationalMotor": lambda: JointMotor(name, simulation, fields),
        "LinearMotor": lambda: LinearJointMotor(name, simulation, fields),
        "PositionSensor": lambda: JointPositionSensor(name, simulation),
    }
    build = builders.get(kind)
    if build is None:
        print(
            f"mazesim: warning: the {kind or 'unnamed'} device {_shown(name)} in the world is not "
            "simulated",
            file=sys.stderr,
        )
        return None
    device = build()
    resolution = fields.get("resolution")
    if kind in _RESOLVED_KINDS and isinstance(resolution, (int, float)):
        device._resolution = float(resolution)  # type: ignore[attr-defined]
    if isinstance(device, PositionSensor):
        device._set_noise(_number_field(fields, "noise", 0.0))
    return device


def _bumper(simulation: RobotSimulation, name: str) -> list[Footprint]:
    """The boundingObject of the robot's TouchSensor ``name`` as the world file writes it, seen
    from above in the sensor's frame (:func:`~mazesim.webots.robot_frames.bounding_footprints`);
    empty without the file's text or such a node."""
    report = simulation.report
    fleet_text = getattr(simulation.fleet, "text", None) if simulation.fleet else None
    text = fleet_text
    if text is None and report.get("path"):
        try:
            text = read_world_text(str(report["path"]))
        except OSError:
            return []
    if text is None:
        return []
    return bounding_footprints(
        text,
        report.get("robot_line"),
        "TouchSensor",
        name,
        simulation.scene.body_y_up,
        "touch sensor",
    )


def _camera_view(simulation: RobotSimulation, entry: Mapping[str, Any]) -> CameraView:
    """Where a camera of the run's robot sits and looks: on a robot node mazesim does not move,
    from its full pose; on one it simulates, as high above the floor as the robot's origin
    rests (``Scene.origin_height``: a plain Robot's on its wheels) plus the camera's place."""
    mount = _still_mount(simulation)
    view = node_view(entry, simulation.scene.y_up_devices, mount)
    if mount is None and simulation.scene.origin_height > 0.0:
        view = replace(view, z=view.z + simulation.scene.origin_height)
    return view


def _device_mount(
    simulation: RobotSimulation, entry: Mapping[str, Any], yaw: float, tilted: bool
) -> DeviceMount:
    """Where a device of the import report's ``entry`` sits on the run's robot, turned ``yaw``
    (with its ``axes`` when ``tilted``: its reading depends on them). On a robot node mazesim
    does not move, in the floor's frame below the node, raised, tilted and scaled as the node
    is (a Webots robot without physics stays where its node stands), as the camera's view is."""
    translation = entry.get("translation") or (0.0, 0.0, 0.0)
    pitch = float(entry.get("pitch", 0.0))
    axes = entry.get("axes") if tilted else None
    still = _still_mount(simulation)
    if still is None:
        return DeviceMount(translation, yaw, pitch, axes)
    ahead = still.direction(
        (math.cos(pitch) * math.cos(yaw), math.cos(pitch) * math.sin(yaw), -math.sin(pitch))
    )
    return DeviceMount(
        still.point(translation),
        math.atan2(ahead[1], ahead[0]),
        math.asin(max(-1.0, min(1.0, -ahead[2]))),
        None if axes is None else [still.direction(axis) for axis in axes],
        placed=True,
    )


def _still_mount(simulation: RobotSimulation) -> Mount | None:
    """The height, tilt and scale of the run's robot node when it is not an e-puck (mazesim
    does not move it: it stays where its node stands, as a Webots robot without physics);
    None for an e-puck (Webots' physics lays its body on the floor) or an upright node."""
    report = simulation.report
    line = report.get("robot_line")
    own = next((r for r in report.get("robots") or [] if r.get("line") == line), None)
    if own is None or own.get("profile") is not None:
        return None
    mount = robot_mount(simulation.scene)
    return None if mount is None or mount.upright else mount


def _proto_channel(scene: Any, name: str) -> int:
    """The E-puck PROTO's ``emitter_channel`` or ``receiver_channel`` field of the robot's own
    node (the PROTO's default, 1, when the file does not set it)."""
    own = next((node for node in scene.nodes if node.robot), None)
    values = own.numbers.get(name) if own is not None else None
    return int(values[0]) if values else E_PUCK_CHANNEL


#: Devices a robot's own node of the same name replaces (the e-puck's emitter and receiver).
RADIO_DEVICES = (Emitter, Receiver)


def _replaces(known: Device, device: Device, own_node: bool) -> bool:
    """Whether ``device`` of the world replaces the e-puck's ``known`` of the same name: a
    robot's own Emitter or Receiver node does, and its own Camera node (among its children:
    a robot saved expanded, or one that is no e-puck), with the fields the world gives it;
    a camera in an E-puck PROTO's slot comes after the PROTO's own, which Webots finds first."""
    if type(known) is not type(device):
        return False
    return type(known) in RADIO_DEVICES or (own_node and isinstance(known, Camera))


class Equipment:
    """Every device of the robot in a run, by name, and the inputs (keyboard, mouse, joystick).

    Attributes:
        devices: The devices by name, in Webots' order.
        differential_drive: The wheels as a ``DifferentialWheels`` node drives them.
        keyboard: The keyboard.
        mouse: The mouse.
        joystick: The joystick.
    """

    def __init__(self, simulation: RobotSimulation) -> None:
        self._simulation = simulation
        profile = simulation.simulator.robot
        entries = [
            entry
            for entry in simulation.report.get("extension_devices") or []
            if isinstance(entry, Mapping)
        ]
        drive = simulation.scene.drive
        sensor_names, renamed_sensors = _wheel_names(entries, "PositionSensor", _WHEEL_SENSORS)
        motor_names, renamed_motors = _wheel_names(entries, "RotationalMotor", _WHEEL_MOTORS)
        # A two-wheeled robot of its own build: its left wheel is the one its node puts left.
        for side, name in wheel_names(drive, "PositionSensor").items():
            sensor_names[side] = name
        for side, name in wheel_names(drive, "RotationalMotor").items():
            motor_names[side] = name
        wheel_entries = {id(entry) for entry in [*renamed_sensors, *renamed_motors]}
        encoders = [
            PositionSensor(name, simulation, side) for side, name in enumerate(sensor_names)
        ]
        for encoder in encoders:
            encoder._resolution, noise = _wheel_sensor_fields(encoder.getName(), renamed_sensors)
            encoder._set_noise(noise)
        self._motors = [
            Motor(name, simulation, side, encoders[side]) for side, name in enumerate(motor_names)
        ]
        for motor, encoder in zip(self._motors, encoders):
            encoder._motor = motor
        simulation.wheel_motors = list(self._motors)
        # Each wheel's motor, then its sensor: the E-puck PROTO's tree order, which numbers a
        # C controller's device tags (left motor 1, left sensor 2, right motor 3...).
        devices: list[Device] = [self._motors[0], encoders[0], self._motors[1], encoders[1]]
        devices += [
            DistanceSensor(name, simulation, i, ground=False)
            for i, name in enumerate(_names(profile, "distance_sensor_names"))
        ]
        devices += [
            LightSensor(f"ls{i}", simulation, mount=light_sensor_mount(profile, i))
            for i in range(LIGHT_SENSOR_COUNT)
        ]
        devices += [
            DistanceSensor(name, simulation, i, ground=True)
            for i, name in enumerate(_names(profile, "ground_sensor_names"))
        ]
        devices += [LED(f"led{i}", simulation) for i in range(LED_COUNT)]
        scene = simulation.scene
        view = CameraView(
            width=scene.camera_width or CameraView.width,
            height=scene.camera_height or CameraView.height,
            fov=scene.camera_fov or CameraView.fov,
            pitch=scene.camera_pitch,
            yaw=scene.camera_yaw,
        )
        devices += [
            Camera("camera", simulation, view),
            Accelerometer("accelerometer", simulation),
            Gyro("gyro", simulation),
            Emitter("emitter", simulation, channel=_proto_channel(scene, "emitter_channel")),
            Receiver("receiver", simulation, channel=_proto_channel(scene, "receiver_channel")),
            Speaker("speaker", simulation),
        ]
        # Webots' getDevice finds only the devices the robot's node holds: a plain robot node
        # (a custom robot taken for an e-puck) lacks those of the e-puck it has no node of, an
        # E-puck without its ground sensors module its gs0..gs2.
        lacked = set(simulation.report.get("missing_devices") or ())
        devices = [device for device in devices if device.getName() not in lacked]
        own_nodes: set[int] = set()
        built: list[tuple[Mapping[str, Any], Device]] = []
        for entry in entries:
            if id(entry) in wheel_entries:
                continue
            if device := extension_device(simulation, entry):
                devices.append(device)
                built.append((entry, device))
                if entry.get("slot") == "children":
                    own_nodes.add(id(device))
        self._joints = pair_joints(built)
        self.devices: dict[str, Device] = {}
        for device in devices:
            known = self.devices.get(device.getName())
            if known is None or _replaces(known, device, id(device) in own_nodes):
                self.devices[device.getName()] = device
        devices = list(self.devices.values())
        self._sampled = [device for device in devices if isinstance(device, _Sensor)]
        #: The wheels as a ``DifferentialWheels`` node drives them (Webots 8's controllers).
        self.differential_drive = DifferentialDrive(
            simulation, self._motors, scene.wheels_node or EPUCK_WHEELS
        )
        self._sampled.append(self.differential_drive.encoders)
        self.keyboard = Keyboard(simulation=simulation)
        self.mouse = Mouse()
        self.joystick = Joystick()
        simulation.reset_listeners.append(self._restart)

    def _restart(self) -> None:
        """What the world's reset restarts in every device (motors, LEDs, noise streams)."""
        for device in self.devices.values():
            device._restart()

    def advance(self) -> None:
        """Runs one basic step with the motors' speeds, then lets each sensor take its reading."""
        simulation = self._simulation
        left, right = simulation.wheel_angles()
        simulation.advance(self._motors[0]._wheel_speed(left), self._motors[1]._wheel_speed(right))
        for joint in self._joints:
            joint._turn(simulation.basic_time_step_ms / 1000.0)
        for sensor in self._sampled:
            sensor._after_step()
