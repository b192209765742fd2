"""What a controller sees of a Webots world file beyond the import report.

The import report gives walls, the robot's pose and its extension devices; the controller module
also wants the DEF names (for ``Supervisor.getFromDef``), whether the robot is a supervisor,
the E-puck's camera fields and the world's north. They are read from the file's text here.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

from mazesim.webots.lights import Light, read_lights

__all__ = ["Scene", "read_scene"]

_DEF = re.compile(r"\bDEF\s+([^\s{}\[\]]+)\s+([A-Za-z_][\w-]*)\s*\{")
_NAME = re.compile(r'\bname\s+"((?:[^"\\]|\\.)*)"')
_CUSTOM_DATA = re.compile(r'\bcustomData\s+"((?:[^"\\]|\\.)*)"')
_CONTROLLER_ARGS = re.compile(r'\bcontrollerArgs\s+(?:\[([^\]]*)\]|"((?:[^"\\]|\\.)*)")')
_STRING = re.compile(r'"((?:[^"\\]|\\.)*)"')
_SUPERVISOR = re.compile(r"\bsupervisor\s+TRUE\b")
_NUMBER = r"([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)"
_CAMERA_WIDTH = re.compile(r"\bcamera_width\s+" + _NUMBER)
_CAMERA_HEIGHT = re.compile(r"\bcamera_height\s+" + _NUMBER)
_CAMERA_FOV = re.compile(r"\bcamera_fieldOfView\s+" + _NUMBER)
_CAMERA_ROTATION = re.compile(r"\bcamera_rotation" + r"\s+".join([""] + [_NUMBER] * 4))
_HEADER = re.compile(r"#VRML_SIM\s+(?:R(\d{4})([a-z])?|V?(\d+)\.)")
_NUE = re.compile(r'\bcoordinateSystem\s+"NUE"')
_TRANSLATION = re.compile(r"\btranslation\s+" + _NUMBER + r"\s+" + _NUMBER + r"\s+" + _NUMBER)
_NORTH = re.compile(r"\bnorthDirection\s+" + _NUMBER + r"\s+" + _NUMBER + r"\s+" + _NUMBER)
#: Node types that are robots.
ROBOT_TYPES = {"E-puck", "Robot", "e-puck2", "Epuck", "E-puck2"}


@dataclass
class Scene:
    """DEF names, supervisor flag, camera fields and north of a world file.

    Attributes:
        defs: DEF name -> node type, in file order.
        translations: DEF name -> the ``translation`` of a top-level DEF node, in the world
            frame (ENU, converted from NUE), when the node gives one.
        robot_def: The robot node's DEF name, or None.
        supervisor: Whether the file says ``supervisor TRUE``.
        robot_name: The robot's ``name`` field (Webots' default for the E-puck, ``"e-puck"``).
        robot_custom_data: The robot's ``customData`` field.
        controller_args: The robot's ``controllerArgs`` (a list of strings since R2021a, one
            string split at spaces before), given to the controller as ``sys.argv[1:]``.
        camera_width: The E-puck's ``camera_width`` field, if set.
        camera_height: The E-puck's ``camera_height`` field, if set.
        camera_fov: The E-puck's ``camera_fieldOfView`` field, if set.
        camera_pitch: How far down (rad) the E-puck's ``camera_rotation`` tilts the camera
            (its part about the camera's y axis).
        north: ``WorldInfo.northDirection`` as x, y (world frame), if set.
        lights: The world's lights that are on (empty: the light sensors' default ambient).
        nue: Whether the file uses Webots' old NUE frame (y up): before R2022a, or
            ``coordinateSystem "NUE"``; a GPS then reads in that frame.
    """

    defs: dict[str, str] = field(default_factory=dict)
    translations: dict[str, tuple[float, float, float]] = field(default_factory=dict)
    robot_def: str | None = None
    supervisor: bool = False
    robot_name: str = "e-puck"
    robot_custom_data: str = ""
    controller_args: list[str] = field(default_factory=list)
    camera_width: int | None = None
    camera_height: int | None = None
    camera_fov: float | None = None
    camera_pitch: float = 0.0
    north: tuple[float, float] | None = None
    nue: bool = False
    lights: list[Light] = field(default_factory=list)


def read_scene(text: str, robot_model: str | None = None) -> Scene:
    """Reads the scene facts of a world file's text (comments skipped).

    Args:
        text: The ``.wbt`` text.
        robot_model: The robot's node type from the import report, if any.
    """
    header = _HEADER.match(text.lstrip())
    scene = Scene()
    if header is not None:
        year = header.group(1)
        scene.nue = int(year) < 2022 if year else header.group(3) is not None
    text = "\n".join(line.split("#", 1)[0] for line in text.splitlines())
    scene.nue = scene.nue or bool(_NUE.search(text))
    robot_types = ROBOT_TYPES | ({robot_model} if robot_model else set())
    depth, scanned = 0, 0
    for match in _DEF.finditer(text):
        name, node_type = match.group(1), match.group(2)
        depth += _nesting(text[scanned : match.start()])
        scanned = match.start()
        scene.defs.setdefault(name, node_type)
        if scene.robot_def is None and node_type in robot_types:
            scene.robot_def = name
        if depth == 0 and (translation := _own_translation(text, match.end())) is not None:
            x, y, z = translation
            scene.translations.setdefault(name, (x, -z, y) if scene.nue else (x, y, z))
    scene.supervisor = bool(_SUPERVISOR.search(text))
    robot = re.search(
        r"\b(?:" + "|".join(re.escape(t) for t in sorted(robot_types)) + r")\s*\{", text
    )
    if robot is not None:
        fields = _own_text(text, robot.end())
        if found := _NAME.search(fields):
            scene.robot_name = found.group(1)
        if found := _CUSTOM_DATA.search(fields):
            scene.robot_custom_data = found.group(1)
    scene.lights = read_lights(text, scene.nue)
    if found := _CONTROLLER_ARGS.search(text):
        listed, single = found.groups()
        scene.controller_args = (
            _STRING.findall(listed) if listed is not None else (single or "").split()
        )
    if found := _CAMERA_WIDTH.search(text):
        scene.camera_width = max(1, int(float(found.group(1))))
    if found := _CAMERA_HEIGHT.search(text):
        scene.camera_height = max(1, int(float(found.group(1))))
    if found := _CAMERA_FOV.search(text):
        scene.camera_fov = float(found.group(1))
    if found := _CAMERA_ROTATION.search(text):
        ax, ay, az, angle = (float(v) for v in found.groups())
        norm = math.sqrt(ax * ax + ay * ay + az * az) or 1.0
        scene.camera_pitch = angle * ay / norm
    if (found := _NORTH.search(text)) and not scene.nue:
        scene.north = (float(found.group(1)), float(found.group(2)))
    return scene


def _nesting(text: str) -> int:
    """How much deeper (in braces and brackets) the end of ``text`` is than its start."""
    return text.count("{") + text.count("[") - text.count("}") - text.count("]")


def _own_text(text: str, body: int) -> str:
    """The fields of the node whose body starts at ``body`` (after its ``{``), without its
    children's."""
    depth, own = 0, []
    for index in range(body, len(text)):
        char = text[index]
        if char in "{[":
            depth += 1
        elif char in "}]":
            depth -= 1
            if depth < 0:
                break
        elif depth == 0:
            own.append(char)
    return "".join(own)


def _own_translation(text: str, body: int) -> tuple[float, float, float] | None:
    """The ``translation`` field of the node whose body starts at ``body``."""
    found = _TRANSLATION.search(_own_text(text, body))
    if found is None:
        return None
    return float(found.group(1)), float(found.group(2)), float(found.group(3))
