"""The PROTO census: which PROTO types the corpus's worlds use, how often, and how many of their
instances import.

A node type that is not one of Webots' built-in nodes is a PROTO. An instance is *dropped* when
the import says so of its line (a warning ``line N: Type ...`` that it is not imported, ignored or
not simulated, or a ``dropped`` entry of the run's summary), *stood in* when the import says a
stand-in replaced it, and *imported* otherwise; an instance inside a dropped one is dropped too.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

#: Webots' built-in node types (its reference manual's node chart, R2019 to R2025, with the
#: older DifferentialWheels, Servo and Supervisor): every other type is a PROTO.
BUILTIN_NODES = frozenset(
    """Accelerometer Altimeter Appearance Background BallJoint BallJointParameters Billboard Box
    Brake CadShape Camera Capsule Charger Color Compass Cone Connector ContactProperties Coordinate
    Cylinder Damping DifferentialWheels DirectionalLight Display DistanceSensor ElevationGrid
    Emitter Fluid Focus Fog GPS Group Gyro Hinge2Joint Hinge2JointParameters HingeJoint
    HingeJointParameters ImageTexture ImmersionProperties IndexedFaceSet IndexedLineSet
    InertialUnit JointParameters LED Lens LensFlare Lidar LightSensor LinearMotor Material Mesh
    Microphone Muscle Normal PBRAppearance Pen Physics Plane PointLight PointSet Pose
    PositionSensor Propeller Radar Radio RangeFinder Receiver Recognition Robot RotationalMotor
    Servo Shape Skin SliderJoint Slot Solid SolidReference Speaker Sphere SpotLight Supervisor
    TextureCoordinate TextureTransform TouchSensor Track TrackWheel Transform VacuumGripper
    Viewpoint WorldInfo Zoom""".split()
)
DROPPED_WORDS = ("not imported", "dropped", "ignored", "not simulated", "not expanded")
STAND_IN_WORDS = ("stand-in", "stood in", "stands in", "in its place")
_TOKEN = re.compile(r'"(?:\\.|[^"\\])*"|#[^\n]*|\{|\}|[^\s{}\[\]"#]+', re.S)
_LINE = re.compile(r"^line (\d+): ")


@dataclass(frozen=True)
class Instance:
    """A node of a world file whose type is a PROTO."""

    type_name: str
    line: int
    parent_line: int | None


def proto_instances(text: str) -> list[Instance]:
    """The PROTO instances of a world file's text, each with its line and the line of the
    PROTO instance it is inside (None at the top)."""
    instances: list[Instance] = []
    stack: list[int | None] = []  # per open brace: the PROTO line it opens, or None
    previous = ""
    name_start = 0
    for match in _TOKEN.finditer(text):
        token = match.group()
        if token.startswith(("#", '"')):
            previous = ""
            continue
        if token == "{":
            line = None
            name = previous
            if name[:1].isupper() and name not in BUILTIN_NODES and name != "PROTO":
                line = text.count("\n", 0, name_start) + 1
                enclosing = next((s for s in reversed(stack) if s is not None), None)
                instances.append(Instance(name, line, enclosing))
            stack.append(line)
        elif token == "}":
            if stack:
                stack.pop()
        else:
            name_start = match.start()
        previous = token if token not in ("{", "}") else ""
    return instances


def _lines(entries: Any) -> set[int]:
    found: set[int] = set()
    for entry in entries if isinstance(entries, list) else []:
        if isinstance(entry, Mapping) and isinstance(entry.get("line"), int):
            found.add(entry["line"])
        elif isinstance(entry, str) and (m := re.search(r"line (\d+)", entry)):
            found.add(int(m.group(1)))
    return found


def losses(
    warnings: Iterable[str], summary: Mapping[str, Any] | None = None
) -> tuple[set[int], set[int]]:
    """The lines the import dropped and the lines it stood in for, from its warnings and, when
    the run's summary lists them (``dropped``, ``stand_ins``), from there too."""
    dropped: set[int] = set()
    stood_in: set[int] = set()
    for warning in warnings:
        match = _LINE.match(warning)
        if not match:
            continue
        lowered = warning.lower()
        if any(word in lowered for word in STAND_IN_WORDS):
            stood_in.add(int(match.group(1)))
        elif any(word in lowered for word in DROPPED_WORDS):
            dropped.add(int(match.group(1)))
    if summary:
        dropped |= _lines(summary.get("dropped"))
        stood_in |= _lines(summary.get("stand_ins"))
    return dropped - stood_in, stood_in


@dataclass
class TypeCount:
    """A PROTO type's instances across the corpus, by what the import made of them."""

    worlds: set[str] = field(default_factory=set)
    imported: int = 0
    stood_in: int = 0
    dropped: int = 0

    @property
    def instances(self) -> int:
        return self.imported + self.stood_in + self.dropped


@dataclass
class Census:
    """PROTO types by name; each world is counted once, however many projects use it."""

    types: dict[str, TypeCount] = field(default_factory=dict)
    counted: set[str] = field(default_factory=set)

    def add(self, world: str, text: str, dropped: set[int], stood_in: set[int]) -> None:
        """Counts a world's PROTO instances (once per world key)."""
        if world in self.counted:
            return
        self.counted.add(world)
        status: dict[int, str] = {}
        for instance in proto_instances(text):
            parent = status.get(instance.parent_line) if instance.parent_line else None
            if parent == "dropped" or instance.line in dropped:
                state = "dropped"
            elif instance.line in stood_in:
                state = "stood_in"
            else:
                state = "imported"
            status[instance.line] = state
            count = self.types.setdefault(instance.type_name, TypeCount())
            count.worlds.add(world)
            setattr(count, state, getattr(count, state) + 1)

    def totals(self) -> TypeCount:
        """All types together."""
        total = TypeCount()
        for count in self.types.values():
            total.imported += count.imported
            total.stood_in += count.stood_in
            total.dropped += count.dropped
        return total

    def coverage(self) -> float:
        """The share of instances imported or stood in (1 for no instances)."""
        total = self.totals()
        return 1.0 if not total.instances else (total.imported + total.stood_in) / total.instances
