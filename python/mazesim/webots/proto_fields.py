"""The fields the PROTOs mazesim builds in (and the base appearance nodes) declare, with their
default values: what a Webots supervisor reads from an instance's field that the world file
leaves out.

Webots gives every field a PROTO declares to its instances; a world file writes only those it
changes. mazesim builds these PROTOs in rather than expanding their files (which it may not
have: their ``EXTERNPROTO`` URLs need a download), so their declared fields are written here.

Sources (cyberbotics/webots): ``projects/objects/floors/protos/RectangleArena.proto`` (the
same fields and defaults from R2019b on), ``projects/robots/gctronic/e-puck/protos/
E-puck.proto`` (R2022b on: the default controller is ``e-puck_avoid_obstacles``, the radio
channels 1, the camera 52 x 39 pixels with a 0.84 rad field of view; the E-puck.proto of Webots
V8.5 declares the same default controller and radio channels, so worlds of every version share
them), ``projects/objects/factory/containers/protos/WoodenBox.proto`` (size 0.6 m, mass 0,
unlocked, from R2021b on); the light nodes' and WorldInfo's fields are those of Webots'
reference manual (Light, PointLight, SpotLight, DirectionalLight, WorldInfo).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any

from mazesim._core import EPUCK_DEFAULT_CONTROLLER
from mazesim.errors import MazesimError
from mazesim.webots.camera import DEFAULT_FOV, DEFAULT_HEIGHT, DEFAULT_WIDTH
from mazesim.webots.expansions import interface_of
from mazesim.webots.proto.definition import FieldDeclaration
from mazesim.webots.proto.values import field_value
from mazesim.webots.radio_devices import E_PUCK_CHANNEL
from mazesim.webots.scene import BASE_NAMES

__all__ = ["DeclaredFields", "declared_fields", "default_controller", "robot_label"]


@dataclass(frozen=True)
class DeclaredFields:
    """A PROTO's declared fields with their defaults, by kind: numbers (an ``SFFloat``,
    ``SFInt32``, ``SFVec2f``...), strings and flags (``SFBool``)."""

    numbers: dict[str, list[float]] = field(default_factory=dict)
    strings: dict[str, str] = field(default_factory=dict)
    flags: dict[str, bool] = field(default_factory=dict)
    #: Those of ``numbers`` that are ``SFFloat`` fields (a whole value is no ``SFInt32``).
    floats: frozenset[str] = frozenset()
    #: Its ``SFNode`` fields (empty, ``NULL``, where the file leaves them out).
    nodes: frozenset[str] = frozenset()
    #: Its list fields of values: kind (``"MFString"``...) and default values, in order.
    lists: dict[str, tuple[str, tuple[Any, ...]]] = field(default_factory=dict)


_RECTANGLE_ARENA = DeclaredFields(
    numbers={
        "floorSize": [1.0, 1.0],
        "floorTileSize": [0.5, 0.5],
        "wallThickness": [0.01],
        "wallHeight": [0.1],
    },
    strings={"name": "rectangle arena", "contactMaterial": "default"},
)

_E_PUCK = DeclaredFields(
    numbers={
        "emitter_channel": [float(E_PUCK_CHANNEL)],
        "receiver_channel": [float(E_PUCK_CHANNEL)],
        "camera_width": [float(DEFAULT_WIDTH)],
        "camera_height": [float(DEFAULT_HEIGHT)],
        "camera_fieldOfView": [DEFAULT_FOV],
        "camera_rotation": [0.0, 0.0, 1.0, 0.0],
        "camera_noise": [0.0],
        "camera_motionBlur": [0.0],
        "distance_sensor_numberOfRays": [1.0],
    },
    strings={
        "name": "e-puck",
        "controller": EPUCK_DEFAULT_CONTROLLER,
        "window": "e-puck",
        "customData": "",
        "version": "1",
    },
    flags={
        "supervisor": False,
        "synchronization": True,
        "kinematic": False,
        "camera_antiAliasing": False,
    },
    floats=frozenset({"camera_fieldOfView", "camera_noise", "camera_motionBlur"}),
)

# Webots' reference manual, WorldInfo (R2022a on: gravity a number, coordinateSystem).
_WORLD_INFO = DeclaredFields(
    numbers={
        "gravity": [9.81],
        "CFM": [0.00001],
        "ERP": [0.2],
        "basicTimeStep": [32.0],
        "FPS": [60.0],
        "optimalThreadCount": [1.0],
        "physicsDisableTime": [1.0],
        "physicsDisableLinearThreshold": [0.01],
        "physicsDisableAngularThreshold": [0.01],
        "inkEvaporation": [0.0],
        "gpsReference": [0.0, 0.0, 0.0],
        "lineScale": [0.1],
        "dragForceScale": [30.0],
        "dragTorqueScale": [5.0],
        "randomSeed": [0.0],
    },
    strings={
        "title": "",
        "window": "",
        "physics": "",
        "coordinateSystem": "ENU",
        "gpsCoordinateSystem": "local",
    },
    floats=frozenset(
        {
            "gravity",
            "CFM",
            "ERP",
            "basicTimeStep",
            "FPS",
            "physicsDisableTime",
            "physicsDisableLinearThreshold",
            "physicsDisableAngularThreshold",
            "inkEvaporation",
            "lineScale",
            "dragForceScale",
            "dragTorqueScale",
        }
    ),
    nodes=frozenset({"defaultDamping"}),
)

# Base nodes' fields (Webots' reference manual, PBRAppearance and Material): a supervisor
# reads an appearance's transparency the world file leaves out, and sets it.
_PBR_APPEARANCE = DeclaredFields(
    numbers={
        "baseColor": [1.0, 1.0, 1.0],
        "transparency": [0.0],
        "roughness": [0.0],
        "metalness": [1.0],
        "IBLStrength": [1.0],
        "normalMapFactor": [1.0],
        "occlusionMapStrength": [1.0],
        "emissiveColor": [0.0, 0.0, 0.0],
        "emissiveIntensity": [1.0],
    },
    strings={"name": "PBRAppearance"},
    floats=frozenset(
        {
            "transparency",
            "roughness",
            "metalness",
            "IBLStrength",
            "normalMapFactor",
            "occlusionMapStrength",
            "emissiveIntensity",
        }
    ),
)
_MATERIAL = DeclaredFields(
    numbers={
        "ambientIntensity": [0.2],
        "diffuseColor": [0.8, 0.8, 0.8],
        "emissiveColor": [0.0, 0.0, 0.0],
        "shininess": [0.2],
        "specularColor": [0.0, 0.0, 0.0],
        "transparency": [0.0],
    },
    floats=frozenset({"ambientIntensity", "shininess", "transparency"}),
)

# projects/objects/factory/containers/protos/WoodenBox.proto: its size, its mass (0 or less: a
# box without physics) and its locked flag, which a supervisor reads though the file leaves
# them out.
_WOODEN_BOX = DeclaredFields(
    numbers={"size": [0.6, 0.6, 0.6], "mass": [0.0]},
    strings={"name": "wooden box"},
    flags={"locked": False},
    floats=frozenset({"mass"}),
)
# The light nodes' fields (Webots' reference manual, Light, PointLight, SpotLight and
# DirectionalLight): a supervisor moves, dims or switches off a light whose file leaves the
# field out (mazesim.webots.lights reads the same defaults).
_LIGHT_NUMBERS = {"ambientIntensity": [0.0], "color": [1.0, 1.0, 1.0], "intensity": [1.0]}
_LIGHT_FLAGS = {"on": True, "castShadows": False}
_LIGHT_FLOATS = frozenset({"ambientIntensity", "intensity", "radius", "beamWidth", "cutOffAngle"})
_POINT_LIGHT = DeclaredFields(
    numbers={
        **_LIGHT_NUMBERS,
        "attenuation": [1.0, 0.0, 0.0],
        "location": [0.0, 0.0, 0.0],
        "radius": [100.0],
    },
    flags=dict(_LIGHT_FLAGS),
    floats=_LIGHT_FLOATS,
)
_SPOT_LIGHT = DeclaredFields(
    numbers={
        **_POINT_LIGHT.numbers,
        "beamWidth": [1.570796],
        "cutOffAngle": [0.785398],
        "direction": [0.0, 0.0, -1.0],
    },
    flags=dict(_LIGHT_FLAGS),
    floats=_LIGHT_FLOATS,
)
_DIRECTIONAL_LIGHT = DeclaredFields(
    numbers={**_LIGHT_NUMBERS, "direction": [0.0, 0.0, -1.0]},
    flags=dict(_LIGHT_FLAGS),
    floats=_LIGHT_FLOATS,
)
# The single fields of the base nodes a supervisor reads most, with their defaults (Webots'
# reference manual, R2023b: Pose, Transform, Solid, Robot, JointParameters,
# HingeJointParameters, Physics): a field the file leaves out is found at its default, and a
# float field written as a whole number (`position 1`) stays an SFFloat. `translation` and
# `rotation` are a node's pose, kept apart (`Node.from_scene`).
_POSE = DeclaredFields(
    numbers={"translationStep": [0.01], "rotationStep": [0.261799]},
    floats=frozenset({"translationStep", "rotationStep"}),
)
_TRANSFORM = DeclaredFields(
    numbers={**_POSE.numbers, "scale": [1.0, 1.0, 1.0]}, floats=_POSE.floats
)
_SOLID = DeclaredFields(
    numbers={
        **_POSE.numbers,
        "radarCrossSection": [0.0],
        "linearVelocity": [0.0, 0.0, 0.0],
        "angularVelocity": [0.0, 0.0, 0.0],
    },
    strings={"name": "solid", "model": "", "description": "", "contactMaterial": "default"},
    flags={"locked": False},
    floats=_POSE.floats | {"radarCrossSection"},
    nodes=frozenset({"boundingObject", "physics"}),
)
_ROBOT = DeclaredFields(
    numbers={**_SOLID.numbers, "cpuConsumption": [10.0]},
    strings={
        **_SOLID.strings,
        "name": "robot",
        "customData": "",
        "window": "<generic>",
        "remoteControl": "<none>",
    },
    flags={**_SOLID.flags, "supervisor": False, "synchronization": True, "selfCollision": False},
    floats=_SOLID.floats | {"cpuConsumption"},
    nodes=_SOLID.nodes,
)
_JOINT_PARAMETERS = DeclaredFields(
    numbers={
        "position": [0.0],
        "axis": [0.0, 0.0, 1.0],
        "minStop": [0.0],
        "maxStop": [0.0],
        "springConstant": [0.0],
        "dampingConstant": [0.0],
        "staticFriction": [0.0],
    },
    floats=frozenset(
        {"position", "minStop", "maxStop", "springConstant", "dampingConstant", "staticFriction"}
    ),
)
_HINGE_JOINT_PARAMETERS = DeclaredFields(
    numbers={
        **_JOINT_PARAMETERS.numbers,
        "axis": [1.0, 0.0, 0.0],
        "anchor": [0.0, 0.0, 0.0],
        "suspensionSpringConstant": [0.0],
        "suspensionDampingConstant": [0.0],
        "suspensionAxis": [1.0, 0.0, 0.0],
        "stopCFM": [-1.0],
        "stopERP": [-1.0],
    },
    floats=_JOINT_PARAMETERS.floats
    | {"suspensionSpringConstant", "suspensionDampingConstant", "stopCFM", "stopERP"},
)
_PHYSICS = DeclaredFields(
    numbers={"density": [1000.0], "mass": [-1.0]},
    floats=frozenset({"density", "mass"}),
    nodes=frozenset({"damping"}),
)
_DECLARED = {
    "Pose": _POSE,
    "Transform": _TRANSFORM,
    "Solid": _SOLID,
    "Robot": _ROBOT,
    "JointParameters": _JOINT_PARAMETERS,
    "HingeJointParameters": _HINGE_JOINT_PARAMETERS,
    "Physics": _PHYSICS,
    "PointLight": _POINT_LIGHT,
    "SpotLight": _SPOT_LIGHT,
    "DirectionalLight": _DIRECTIONAL_LIGHT,
    "RectangleArena": _RECTANGLE_ARENA,
    "WoodenBox": _WOODEN_BOX,
    "E-puck": _E_PUCK,
    "WorldInfo": _WORLD_INFO,
    "PBRAppearance": _PBR_APPEARANCE,
    "Material": _MATERIAL,
}


def declared_fields(type_name: str) -> DeclaredFields:
    """The declared fields of a PROTO mazesim builds in, else those of a PROTO the world
    imported last read from its file (a project's own, :func:`interface_of`), else none."""
    if type_name in _DECLARED:
        return _DECLARED[type_name]
    interface = interface_of(type_name)
    return DeclaredFields() if interface is None else _read_interface(interface)


#: The vector types of a PROTO's interface, read as numbers.
_VECTORS = ("SFVec2f", "SFVec3f", "SFColor", "SFRotation")


#: The interfaces read, by identity (a supervisor asks for a node's fields at each getField):
#: each with the interface it was read from, which keeps its identity its own.
_READ: dict[int, tuple[Mapping[str, FieldDeclaration], DeclaredFields]] = {}


def _read_interface(interface: Mapping[str, FieldDeclaration]) -> DeclaredFields:
    """A PROTO file's declared fields of values at their defaults (its ``translation`` and
    ``rotation`` aside: an instance's pose is the scene's; a default that cannot be read aside
    too), read once."""
    kept = _READ.get(id(interface))
    if kept is not None and kept[0] is interface:
        return kept[1]
    if len(_READ) >= 256:
        _READ.clear()
    read = _parse_interface(interface)
    _READ[id(interface)] = (interface, read)
    return read


def _parse_interface(interface: Mapping[str, FieldDeclaration]) -> DeclaredFields:
    """What :func:`_read_interface` gives, read anew."""
    read = DeclaredFields()
    floats: set[str] = set()
    nodes: set[str] = set()
    for name, declared in interface.items():
        if name in ("translation", "rotation"):
            continue
        if declared.kind == "SFNode":
            nodes.add(name)
            continue
        if declared.kind.startswith("MF"):
            if declared.kind != "MFNode":
                items = _list_default(declared)
                if items is not None:
                    read.lists[name] = (declared.kind, items)
            continue
        try:
            value = field_value(declared.kind, declared.default)
        except (MazesimError, ValueError):
            continue
        if declared.kind == "SFString":
            read.strings[name] = str(value)
        elif declared.kind == "SFBool":
            read.flags[name] = bool(value)
        elif declared.kind in ("SFFloat", "SFInt32"):
            read.numbers[name] = [float(value)]
            if declared.kind == "SFFloat":
                floats.add(name)
        elif declared.kind in _VECTORS and isinstance(value, dict):
            read.numbers[name] = [float(v) for v in value.values()]
    return replace(read, floats=frozenset(floats), nodes=frozenset(nodes))


def _list_default(declared: FieldDeclaration) -> tuple[Any, ...] | None:
    """The values of a list field's default, in order (a vector's numbers one after another),
    or None when the default cannot be read."""
    try:
        items = field_value(declared.kind, declared.default)
    except (MazesimError, ValueError):
        return None
    flat: list[Any] = []
    for item in items:
        flat.extend(item.values() if isinstance(item, dict) else [item])
    return tuple(flat)


#: The models the import gives an instance of Webots' E-puck PROTO (``version "2"``: e-puck2).
_E_PUCK_MODELS = ("E-puck", "e-puck2")


def robot_label(robot: Mapping[str, Any]) -> str:
    """What a robot of the import's ``robots`` is called, as Webots calls it: its ``name``
    field, else its base node type's default (a Robot's "robot"), else the default its PROTO
    declares (an E-puck's, of either version, is "e-puck"), else its DEF name, else its
    model."""
    if robot.get("name"):
        return str(robot["name"])
    if robot.get("node_type") in BASE_NAMES:
        return BASE_NAMES[str(robot["node_type"])]
    model = robot.get("model")
    declared = declared_fields("E-puck" if model in _E_PUCK_MODELS else str(model))
    return str(declared.strings.get("name") or robot.get("def_name") or model)


def default_controller(robot: Mapping[str, Any]) -> str:
    """The controller a robot of the import's ``robots`` runs where its node leaves the
    ``controller`` field out, as Webots reads the field: the default its PROTO declares (the
    E-puck's ``e-puck_avoid_obstacles``, a project PROTO's own), or for a plain ``Robot`` node
    (an e-puck saved expanded too, whose model is the E-puck's) Webots' ``<generic>``, which
    runs nothing; "" where nothing is declared."""
    model = str(robot.get("model") or "")
    if robot.get("node_type") in BASE_NAMES and model in _E_PUCK_MODELS:
        return "<generic>"
    return declared_fields(model).strings.get("controller", "")
