"""The Webots functions a compiled controller waits for, run on the robot's Python objects.

A C or C++ controller's radio, camera image, recognition and lens, inertial unit quaternion, lidar,
motor torque, GPS speed, lookup table, robot battery, DifferentialWheels, pen, speaker, range
finder, mouse, joystick and supervisor functions are calls over the link
(:mod:`mazesim.webots.native_link`, message ``CALL``): a Webots C function's name and typed
values. :class:`NativeCalls` runs each on the object that implements it for Python controllers
(a device of the robot, such as an
:class:`~mazesim.webots.radio_devices.Emitter`, a :class:`~mazesim.webots.camera.Camera` or an
:class:`~mazesim.webots.inert.Lidar`, the :class:`~mazesim.webots.robot.Robot` itself, its
:class:`~mazesim.webots.differential_drive.DifferentialDrive`, or its
:class:`~mazesim.webots.supervisor.Supervisor` and the nodes and fields it hands out), so
channels, ranges, queues, nodes and fields behave for a compiled controller as they do for a
Python one, and answers typed values. The functions follow Webots' reference manual
(https://cyberbotics.com/doc/reference/emitter, /receiver, /recognition, /inertialunit, /lidar,
/camera, /motor, /gps, /robot and /supervisor).

A camera's recognised objects cross the link as two values: one list of numbers (per object:
id, position, orientation, size, position and size on the image, number of colours, then the
colours' red, green and blue) and their models, each ending with a NUL. A lidar's point cloud
is one list of numbers (per point: x, y, z, layer, time), a node's contact points another (per
point: x, y, z, node id).

Nodes and fields cross the link as handles (1, 2... in the order they are first handed out; 0
is ``NULL``); a field's handle comes with its type (``WB_SF_VEC3F``...).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from mazesim.errors import InvalidArgumentError, MazesimIOError, _shown
from mazesim.webots.camera import CameraRecognitionObject
from mazesim.webots.devices import _print_error
from mazesim.webots.field import Field
from mazesim.webots.inert import ContactPoint, LidarPoint, Speaker
from mazesim.webots.supervisor import Node, Supervisor
from mazesim.webots.supervisor_refusal import _refusal_of

__all__ = ["FUNCTIONS", "Function", "NativeCalls"]


@dataclass(frozen=True)
class Function:
    """How a Webots C function maps onto the Python API.

    Attributes:
        target: What its first argument is: ``"device"`` (a device tag), ``"node"`` or
            ``"field"`` (a handle), ``"robot"`` (no argument: the robot), ``"supervisor"``
            (no argument: the robot's supervisor), ``"differential_wheels"`` (no argument:
            the robot's :class:`~mazesim.webots.differential_drive.DifferentialDrive`) or
            ``"speakers"`` (no argument: the :class:`~mazesim.webots.inert.Speaker` class,
            whose ``playSound`` takes both speakers), ``"mouse"`` or ``"joystick"`` (no
            argument: the robot's).
        method: The Python method that implements it.
        arguments: The kinds of its other arguments, one letter each: ``i`` an integer, ``f``
            a number, ``s`` a text, ``b`` bytes, ``v`` numbers, ``n`` a node handle, ``t`` a
            device tag.
    """

    target: str
    method: str
    arguments: str = ""


def _table(target: str, prefix: str, rows: dict[str, tuple[str, str]]) -> dict[str, Function]:
    return {f"{prefix}{name}": Function(target, *row) for name, row in rows.items()}


#: The functions served, by C name.
FUNCTIONS: dict[str, Function] = {
    **_table(
        "device",
        "wb_emitter_",
        {
            "send": ("send", "b"),
            "get_buffer_size": ("getBufferSize", ""),
            "get_channel": ("getChannel", ""),
            "set_channel": ("setChannel", "i"),
            "get_range": ("getRange", ""),
            "set_range": ("setRange", "f"),
        },
    ),
    **_table(
        "device",
        "wb_receiver_",
        {
            "get_channel": ("getChannel", ""),
            "set_channel": ("setChannel", "i"),
            "get_queue_length": ("getQueueLength", ""),
            "next_packet": ("nextPacket", ""),
            "get_data_size": ("getDataSize", ""),
            "get_data": ("getBytes", ""),
            "get_signal_strength": ("getSignalStrength", ""),
            "get_emitter_direction": ("getEmitterDirection", ""),
        },
    ),
    **_table(
        "device",
        "wb_camera_",
        {
            "get_image": ("getImage", ""),
            "has_recognition": ("hasRecognition", ""),
            "recognition_enable": ("recognitionEnable", "i"),
            "recognition_disable": ("recognitionDisable", ""),
            "recognition_get_sampling_period": ("getRecognitionSamplingPeriod", ""),
            "recognition_get_number_of_objects": ("getRecognitionNumberOfObjects", ""),
            "recognition_get_objects": ("getRecognitionObjects", ""),
            "recognition_has_segmentation": ("hasRecognitionSegmentation", ""),
            "recognition_enable_segmentation": ("enableRecognitionSegmentation", ""),
            "recognition_disable_segmentation": ("disableRecognitionSegmentation", ""),
            "recognition_is_segmentation_enabled": ("isRecognitionSegmentationEnabled", ""),
            "recognition_get_segmentation_image": ("getRecognitionSegmentationImage", ""),
        },
    ),
    **_table(
        "device",
        "wb_camera_",
        {
            "get_fov": ("getFov", ""),
            "set_fov": ("setFov", "f"),
            "get_min_fov": ("getMinFov", ""),
            "get_max_fov": ("getMaxFov", ""),
            "get_exposure": ("getExposure", ""),
            "set_exposure": ("setExposure", "f"),
            "get_focal_length": ("getFocalLength", ""),
            "get_focal_distance": ("getFocalDistance", ""),
            "get_min_focal_distance": ("getMinFocalDistance", ""),
            "get_max_focal_distance": ("getMaxFocalDistance", ""),
            "set_focal_distance": ("setFocalDistance", "f"),
            "get_near": ("getNear", ""),
            "save_image": ("saveImage", "si"),
            "recognition_save_segmentation_image": ("saveRecognitionSegmentationImage", "si"),
        },
    ),
    **_table(
        "device",
        "wb_motor_",
        {
            "set_control_pid": ("setControlPID", "fff"),
            "set_available_torque": ("setAvailableTorque", "f"),
            "set_available_force": ("setAvailableForce", "f"),
            "set_torque": ("setTorque", "f"),
            "set_force": ("setForce", "f"),
            "get_available_torque": ("getAvailableTorque", ""),
            "get_available_force": ("getAvailableForce", ""),
            "get_max_torque": ("getMaxTorque", ""),
            "get_max_force": ("getMaxForce", ""),
            "enable_torque_feedback": ("enableTorqueFeedback", "i"),
            "enable_force_feedback": ("enableForceFeedback", "i"),
            "disable_torque_feedback": ("disableTorqueFeedback", ""),
            "disable_force_feedback": ("disableForceFeedback", ""),
            "get_torque_feedback": ("getTorqueFeedback", ""),
            "get_force_feedback": ("getForceFeedback", ""),
            "get_torque_feedback_sampling_period": ("getTorqueFeedbackSamplingPeriod", ""),
            "get_force_feedback_sampling_period": ("getForceFeedbackSamplingPeriod", ""),
            "get_multiplier": ("getMultiplier", ""),
            "get_brake": ("getBrake", ""),
        },
    ),
    **_table(
        "device",
        "wb_gps_",
        {
            "get_speed": ("getSpeed", ""),
            "get_speed_vector": ("getSpeedVector", ""),
            "get_coordinate_system": ("getCoordinateSystem", ""),
        },
    ),
    **{
        f"wb_{device}_get_lookup_table": Function("device", "getLookupTable")
        for device in ("accelerometer", "compass", "gyro", "light_sensor", "touch_sensor")
    },
    **_table(
        "device",
        "wb_touch_sensor_",
        {"get_values": ("getValues", ""), "get_type": ("getType", "")},
    ),
    **_table(
        "device",
        "wb_position_sensor_",
        {"get_type": ("getType", ""), "get_brake": ("getBrake", "")},
    ),
    **_table(
        "robot",
        "wb_robot_",
        {
            "battery_sensor_enable": ("batterySensorEnable", "i"),
            "battery_sensor_disable": ("batterySensorDisable", ""),
            "battery_sensor_get_sampling_period": ("batterySensorGetSamplingPeriod", ""),
            "battery_sensor_get_value": ("batterySensorGetValue", ""),
            "get_type": ("getType", ""),
            "get_urdf": ("getUrdf", "s"),
            "wait_for_user_input_event": ("waitForUserInputEvent", "ii"),
            "wwi_send_text": ("wwiSendText", "s"),
            "wwi_receive_text": ("wwiReceiveText", ""),
        },
    ),
    **_table(
        "device", "wb_pen_", {"write": ("write", "i"), "set_ink_color": ("setInkColor", "if")}
    ),
    "wb_speaker_play_sound": Function("speakers", "playSound", "ttsfffi"),
    **_table(
        "device",
        "wb_speaker_",
        {
            "stop": ("stop", "s"),
            "is_sound_playing": ("isSoundPlaying", "s"),
            "set_engine": ("setEngine", "s"),
            "set_language": ("setLanguage", "s"),
            "get_engine": ("getEngine", ""),
            "get_language": ("getLanguage", ""),
            "speak": ("speak", "sf"),
            "is_speaking": ("isSpeaking", ""),
        },
    ),
    **_table(
        "mouse",
        "wb_mouse_",
        {
            "enable": ("enable", "i"),
            "disable": ("disable", ""),
            "get_sampling_period": ("getSamplingPeriod", ""),
            "enable_3d_position": ("enable3dPosition", ""),
            "disable_3d_position": ("disable3dPosition", ""),
            "is_3d_position_enabled": ("is3dPositionEnabled", ""),
            "get_state": ("getState", ""),
        },
    ),
    **_table(
        "joystick",
        "wb_joystick_",
        {
            "enable": ("enable", "i"),
            "disable": ("disable", ""),
            "get_sampling_period": ("getSamplingPeriod", ""),
            "is_connected": ("isConnected", ""),
            "get_model": ("getModel", ""),
            "get_number_of_axes": ("getNumberOfAxes", ""),
            "get_axis_value": ("getAxisValue", "i"),
            "get_number_of_povs": ("getNumberOfPovs", ""),
            "get_pov_value": ("getPovValue", "i"),
            "get_pressed_button": ("getPressedButton", ""),
            "set_constant_force": ("setConstantForce", "i"),
            "set_constant_force_duration": ("setConstantForceDuration", "f"),
            "set_auto_centering_gain": ("setAutoCenteringGain", "f"),
            "set_resistance_gain": ("setResistanceGain", "f"),
            "set_force_axis": ("setForceAxis", "i"),
        },
    ),
    **_table(
        "differential_wheels",
        "wb_differential_wheels_",
        {
            "set_speed": ("setSpeed", "ff"),
            "get_left_speed": ("getLeftSpeed", ""),
            "get_right_speed": ("getRightSpeed", ""),
            "get_max_speed": ("getMaxSpeed", ""),
            "get_speed_unit": ("getSpeedUnit", ""),
            "enable_encoders": ("enableEncoders", "i"),
            "disable_encoders": ("disableEncoders", ""),
            "get_encoders_sampling_period": ("getEncodersSamplingPeriod", ""),
            "get_left_encoder": ("getLeftEncoder", ""),
            "get_right_encoder": ("getRightEncoder", ""),
            "set_encoders": ("setEncoders", "ff"),
        },
    ),
    **_table(
        "device",
        "wb_inertial_unit_",
        {"get_quaternion": ("getQuaternion", ""), "get_noise": ("getNoise", "")},
    ),
    **_table(
        "device",
        "wb_lidar_",
        {
            "get_range_image": ("getRangeImage", ""),
            "get_layer_range_image": ("getLayerRangeImage", "i"),
            "enable_point_cloud": ("enablePointCloud", ""),
            "disable_point_cloud": ("disablePointCloud", ""),
            "is_point_cloud_enabled": ("isPointCloudEnabled", ""),
            "get_point_cloud": ("getPointCloud", ""),
            "get_layer_point_cloud": ("getLayerPointCloud", "i"),
            "get_number_of_points": ("getNumberOfPoints", ""),
            "get_horizontal_resolution": ("getHorizontalResolution", ""),
            "get_number_of_layers": ("getNumberOfLayers", ""),
            "get_min_frequency": ("getMinFrequency", ""),
            "get_max_frequency": ("getMaxFrequency", ""),
            "get_frequency": ("getFrequency", ""),
            "set_frequency": ("setFrequency", "f"),
            "get_fov": ("getFov", ""),
            "get_vertical_fov": ("getVerticalFov", ""),
            "get_min_range": ("getMinRange", ""),
            "get_max_range": ("getMaxRange", ""),
        },
    ),
    **_table(
        "device",
        "wb_range_finder_",
        {
            "get_range_image": ("getRangeImage", ""),
            "get_width": ("getWidth", ""),
            "get_height": ("getHeight", ""),
            "get_fov": ("getFov", ""),
            "get_min_range": ("getMinRange", ""),
            "get_max_range": ("getMaxRange", ""),
        },
    ),
    **_table(
        "supervisor",
        "wb_supervisor_",
        {
            "simulation_quit": ("simulationQuit", "i"),
            "simulation_reset": ("simulationReset", ""),
            "simulation_reset_physics": ("simulationResetPhysics", ""),
            "simulation_get_mode": ("simulationGetMode", ""),
            "simulation_set_mode": ("simulationSetMode", "i"),
            "world_load": ("worldLoad", "s"),
            "world_save": ("worldSave", "s"),
            "world_reload": ("worldReload", ""),
            "set_label": ("setLabel", "isfffifs"),
            "export_image": ("exportImage", "si"),
            "movie_start_recording": ("movieStartRecording", "siiiiii"),
            "movie_stop_recording": ("movieStopRecording", ""),
            "movie_is_ready": ("movieIsReady", ""),
            "movie_failed": ("movieFailed", ""),
            "node_get_root": ("getRoot", ""),
            "node_get_self": ("getSelf", ""),
            "node_get_from_def": ("getFromDef", "s"),
            "node_get_from_id": ("getFromId", "i"),
            "node_get_from_device": ("getFromDevice", "t"),
            "node_get_selected": ("getSelected", ""),
            "virtual_reality_headset_is_used": ("virtualRealityHeadsetIsUsed", ""),
        },
    ),
    **_table(
        "node",
        "wb_supervisor_node_",
        {
            "get_parent_node": ("getParentNode", ""),
            "get_id": ("getId", ""),
            "get_def": ("getDef", ""),
            "get_type": ("getType", ""),
            "get_type_name": ("getTypeName", ""),
            "get_base_type_name": ("getBaseTypeName", ""),
            "is_proto": ("isProto", ""),
            "get_field": ("getField", "s"),
            "get_proto_field": ("getProtoField", "s"),
            "get_number_of_fields": ("getNumberOfFields", ""),
            "get_field_by_index": ("_field_name_at", "i"),
            "get_position": ("getPosition", ""),
            "get_orientation": ("getOrientation", ""),
            "get_pose": ("getPose", "n"),
            "get_center_of_mass": ("getCenterOfMass", ""),
            "get_velocity": ("getVelocity", ""),
            "set_velocity": ("setVelocity", "v"),
            "reset_physics": ("resetPhysics", ""),
            "restart_controller": ("restartController", ""),
            "get_static_balance": ("getStaticBalance", ""),
            "remove": ("remove", ""),
            "get_contact_points": ("getContactPoints", "i"),
        },
    ),
    **_table(
        "field",
        "wb_supervisor_field_",
        {
            "get_type_name": ("getTypeName", ""),
            "get_count": ("getCount", ""),
            "get_sf_bool": ("c_sf_bool", ""),
            "get_sf_int32": ("c_sf_int32", ""),
            "get_sf_float": ("c_sf_float", ""),
            "get_sf_vec2f": ("c_sf_vec2f", ""),
            "get_sf_vec3f": ("c_sf_vec3f", ""),
            "get_sf_rotation": ("c_sf_rotation", ""),
            "get_sf_color": ("c_sf_color", ""),
            "get_sf_string": ("c_sf_string", ""),
            "get_sf_node": ("getSFNode", ""),
            "get_mf_node": ("getMFNode", "i"),
            "get_mf_bool": ("getMFBool", "i"),
            "get_mf_int32": ("getMFInt32", "i"),
            "get_mf_float": ("getMFFloat", "i"),
            "get_mf_vec2f": ("getMFVec2f", "i"),
            "get_mf_vec3f": ("getMFVec3f", "i"),
            "get_mf_rotation": ("getMFRotation", "i"),
            "get_mf_color": ("getMFColor", "i"),
            "get_mf_string": ("getMFString", "i"),
            "set_mf_bool": ("setMFBool", "ii"),
            "set_mf_int32": ("setMFInt32", "ii"),
            "set_mf_float": ("setMFFloat", "if"),
            "set_mf_vec2f": ("setMFVec2f", "iv"),
            "set_mf_vec3f": ("setMFVec3f", "iv"),
            "set_mf_rotation": ("setMFRotation", "iv"),
            "set_mf_color": ("setMFColor", "iv"),
            "set_mf_string": ("setMFString", "is"),
            "insert_mf_bool": ("insertMFBool", "ii"),
            "insert_mf_int32": ("insertMFInt32", "ii"),
            "insert_mf_float": ("insertMFFloat", "if"),
            "insert_mf_vec2f": ("insertMFVec2f", "iv"),
            "insert_mf_vec3f": ("insertMFVec3f", "iv"),
            "insert_mf_rotation": ("insertMFRotation", "iv"),
            "insert_mf_color": ("insertMFColor", "iv"),
            "insert_mf_string": ("insertMFString", "is"),
            "set_sf_bool": ("setSFBool", "i"),
            "set_sf_int32": ("setSFInt32", "i"),
            "set_sf_float": ("setSFFloat", "f"),
            "set_sf_vec2f": ("setSFVec2f", "v"),
            "set_sf_vec3f": ("setSFVec3f", "v"),
            "set_sf_rotation": ("setSFRotation", "v"),
            "set_sf_color": ("setSFColor", "v"),
            "set_sf_string": ("setSFString", "s"),
            "import_mf_node_from_string": ("importMFNodeFromString", "is"),
            "import_sf_node_from_string": ("importSFNodeFromString", "s"),
            "import_mf_node": ("importMFNode", "is"),
            "import_sf_node": ("importSFNode", "s"),
            "remove_mf": ("removeMF", "i"),
            "remove_sf": ("removeSF", ""),
        },
    ),
}


class NativeCalls:
    """Runs a compiled controller's calls on its robot.

    Args:
        robot: The robot (a :class:`~mazesim.webots.supervisor.Supervisor` serves the
            supervisor's functions).
        devices: The robot's devices, by tag - 1.
    """

    def __init__(self, robot: Any, devices: list[Any]) -> None:
        self.robot = robot
        self.devices = devices
        self._nodes: list[Node] = []
        self._node_handles: dict[int, int] = {}
        self._fields: list[Field] = []
        self._field_handles: dict[tuple[int, str], int] = {}

    def call(self, name: str, values: list[Any]) -> list[Any]:
        """Runs the function ``name`` with the call's values; returns the answer's values.

        Raises:
            MazesimIOError: ``name`` is not a function mazesim serves (a library of another
                version).
        """
        function = FUNCTIONS.get(name)
        if function is None:
            raise MazesimIOError(
                f"expected a call of a Webots function mazesim serves, found {_shown(name)}"
            )
        values = list(values)
        first = values.pop(0) if function.target in ("device", "node", "field") and values else 0
        target = self._target(function, name, first)
        if target is None:
            return [None]
        method: Callable[..., Any] = getattr(target, function.method)
        arguments = [self._argument(kind, value) for kind, value in zip(function.arguments, values)]
        try:
            result = method(*arguments)
        except InvalidArgumentError as error:
            # Webots' C library refuses an argument with a message and the function's default
            # answer (no value here), and the controller goes on: it never ends it.
            _print_error(f"Error: {name}(): {error}")
            return [None]
        return self._answer(result)

    # --- the first argument ----------------------------------------------------------------

    def _target(self, function: Function, name: str, first: Any) -> Any:
        if function.target == "robot":
            return self.robot
        if function.target == "differential_wheels":
            return self.robot._equipment.differential_drive
        if function.target == "speakers":
            return Speaker
        if function.target == "mouse":
            return self.robot.getMouse()
        if function.target == "joystick":
            return self.robot.getJoystick()
        if function.target == "supervisor":
            if not isinstance(self.robot, Supervisor):
                _print_error(f"Error: {name}() can only be called by a supervisor.")
                return None
            if self.robot._simulation.scene.supervisor_refused:
                _refusal_of(name)
                return None
            # As a Python controller that makes a Supervisor, the robot becomes one.
            self.robot._simulation.supervisor = True
            return self.robot
        if function.target == "device":
            device = self._device(first)
            # A tag of a device of another kind: Webots' message for a wrong tag.
            if device is None or getattr(type(device), function.method, None) is None:
                _print_error(f"Error: {name}(): invalid device tag.")
                return None
            return device
        handles: list[Any] = self._nodes if function.target == "node" else self._fields
        index = int(first) if isinstance(first, (int, float)) else 0
        if not 1 <= index <= len(handles):
            _print_error(f"Error: {name}() called with a NULL '{function.target}' argument.")
            return None
        return handles[index - 1]

    def _device(self, tag: Any) -> Any:
        index = int(tag) if isinstance(tag, (int, float)) else 0
        return self.devices[index - 1] if 1 <= index <= len(self.devices) else None

    def _argument(self, kind: str, value: Any) -> Any:
        if kind == "s":
            return None if value is None else bytes(value).decode("utf-8", errors="replace")
        if kind == "n":
            index = int(value or 0)
            return self._nodes[index - 1] if 1 <= index <= len(self._nodes) else None
        if kind == "t":
            return self._device(value)
        if kind == "i":
            return int(value or 0)
        if kind == "f":
            return float(value)
        return value

    # --- the answer ------------------------------------------------------------------------

    def _answer(self, result: Any) -> list[Any]:
        if isinstance(result, Node):
            return [self._node_handle(result)]
        if isinstance(result, Field):
            key = (id(result._node), result.getName())
            if key not in self._field_handles:
                self._node_handle(result._node)  # keeps the node, and so its id
                self._fields.append(result)
                self._field_handles[key] = len(self._fields)
            return [self._field_handles[key], result.getType()]
        if isinstance(result, bool):
            return [int(result)]
        if isinstance(result, str):
            return [result.encode("utf-8")]
        if isinstance(result, list) and result and isinstance(result[0], CameraRecognitionObject):
            return _recognised(result)
        if isinstance(result, list) and result and isinstance(result[0], ContactPoint):
            return [[v for p in result for v in (*p.getPoint(), p.getNodeId())]]
        if isinstance(result, list) and result and isinstance(result[0], LidarPoint):
            return [[v for p in result for v in (p.x, p.y, p.z, p.layer_id, p.time)]]
        if isinstance(result, (list, tuple)):
            return [[float(v) for v in result]]
        return [result]

    def _node_handle(self, node: Node) -> int:
        if id(node) not in self._node_handles:
            self._nodes.append(node)
            self._node_handles[id(node)] = len(self._nodes)
        return self._node_handles[id(node)]


def _recognised(objects: list[CameraRecognitionObject]) -> list[Any]:
    """A camera's recognised objects as the link carries them (see the module's docstring)."""
    numbers: list[float] = []
    for thing in objects:
        numbers.append(float(thing.getId()))
        for values in (
            thing.getPosition(),
            thing.getOrientation(),
            thing.getSize(),
            thing.getPositionOnImage(),
            thing.getSizeOnImage(),
        ):
            numbers.extend(float(v) for v in values)
        colors = [float(v) for v in thing.getColors()]
        numbers.append(float(len(colors) // 3))
        numbers.extend(colors[: 3 * (len(colors) // 3)])
    models = b"".join(thing.getModel().encode("utf-8") + b"\0" for thing in objects)
    return [numbers, models]
