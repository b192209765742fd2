"""Expanding PROTO instances into the nodes they stand for, as Webots does before it simulates:
each instance's fields (given, else the PROTO's defaults) replace the body's ``IS`` references,
a procedural body is evaluated first, and PROTOs inside the body are expanded in their turn.
An expansion takes the place of the instance on the instance's own line, so the lines of the
rest of the world (and of every warning) stay those of the file."""

from __future__ import annotations

import os
import re
import sys
from dataclasses import dataclass, field
from typing import Any

from mazesim.errors import WorldFormatError

from .definition import FieldDeclaration, ProtoDefinition, externproto_urls, parse_definition
from .own_robot import OWN_ROBOT_TYPES, added_devices, outermost, with_devices
from .resolver import ProtoSource, ProtoUnavailableError, Resolver
from .stand_ins import STAND_INS
from .syntax import Node, line_of, located_error, parse_nodes, tokenize
from .templates import evaluate_template
from .values import field_value

__all__ = ["Expander", "ExpansionReport", "BASE_NODES", "CORE_TYPES"]

#: Webots' base node types: never PROTOs.
BASE_NODES = frozenset(
    "Accelerometer Altimeter Appearance Background Billboard BallJoint BallJointParameters Box "
    "Brake CadShape Camera Capsule Charger Color Compass Cone Connector ContactProperties "
    "Coordinate Cylinder Damping DifferentialWheels DirectionalLight Display DistanceSensor "
    "ElevationGrid Emitter Fluid Focus Fog GPS Group Gyro Hinge2Joint Hinge2JointParameters "
    "HingeJoint HingeJointParameters ImageTexture ImmersionProperties IndexedFaceSet "
    "IndexedLineSet InertialUnit JointParameters LED Lens LensFlare Lidar LightSensor "
    "LinearMotor Material Mesh Microphone Muscle Normal PBRAppearance Pen Physics Plane "
    "PointLight PointSet Pose PositionSensor Propeller Radar Radio RangeFinder Receiver "
    "Recognition "
    "Robot RotationalMotor Servo Shape SliderJoint Slot Skin Solid SolidReference Speaker "
    "Sphere SpotLight Supervisor TextureCoordinate TextureTransform TouchSensor Track TrackWheel "
    "Transform VacuumGripper Viewpoint WorldInfo Zoom".split()
)
#: PROTOs the core imports by name (the e-puck, its ground sensors, arenas and boxes, the
#: robots it stands the e-puck in for, backgrounds): left as they are.
CORE_TYPES = frozenset(
    "E-puck E-puck_enu E-Puck_enu EPuck E-puckGroundSensors EPuck_GroundSensorsModule "
    "RectangleArena Floor Wall WoodenBox "
    "CardboardBox SolidBox LegoTallWall LegoTallInterval TexturedBackground "
    "TexturedBackgroundLight Thymio2 Khepera1 Khepera3 Khepera4 Elisa3 Hemisson Pioneer2 "
    "Pioneer3dx Pioneer3at Create TurtleBot3Burger Rosbot Robotino3 Moose Mir100 Tiago BB-8 "
    "Nao".split()
)
#: Fields whose nodes only draw (their PROTOs, e.g. appearances, need no expansion).
VISUAL_FIELDS = frozenset({"appearance", "material", "texture", "textureTransform"})
#: A node type before its body (a word then ``{``), and comments to leave out before looking.
_NODE_TYPE = re.compile(r"(?<![\w-])([A-Za-z_][\w-]*)\s*\{")
_COMMENT = re.compile(r'"[^"\\\n]*(?:\\.[^"\\\n]*)*"|#[^\n]*')
_HIDDEN_LINE = re.compile(r"^[ \t]*hidden[ \t][^\n]*$", re.MULTILINE)
#: Deepest nesting of PROTOs in PROTOs (a PROTO that uses itself stops here).
MAX_NESTING = 24
#: Most instances expanded in one world.
MAX_INSTANCES = 20_000
#: Most characters of node text the expansions of one world make (300 instances of a PROTO of
#: 0.9 MB made 270 MB and ran for more than ten minutes; reading an expansion takes about a
#: second a megabyte), far beyond a real world's.
MAX_EXPANDED_TEXT = 32 * 1024 * 1024
#: Most templates run in one world: instances of a procedural PROTO with the same fields share
#: one run; each run is a process of its own (a few milliseconds), so a PROTO that instantiates
#: itself with fields that differ each time would otherwise take minutes.
MAX_TEMPLATE_RUNS = 4_000


@dataclass
class ExpansionReport:
    """What the expansion did, for the import report."""

    #: PROTO types expanded from a file or URL, with where each came from.
    expanded: dict[str, str] = field(default_factory=dict)
    #: PROTO types replaced by mazesim's stand-in, with the stand-in's description.
    stand_ins: dict[str, str] = field(default_factory=dict)
    #: Webots' own PROTO types that could not be read (offline, no cache, no WEBOTS_HOME) and
    #: have no stand-in, with why and where to put the file: left to the core, which may
    #: know the type itself (the Pi-puck board) or drop its instances.
    unreadable: dict[str, str] = field(default_factory=dict)
    #: Warnings, one sentence each, with their line in the world.
    warnings: list[str] = field(default_factory=list)
    #: URLs read from the download cache, and URLs downloaded.
    cache_hits: list[str] = field(default_factory=list)
    downloads: list[str] = field(default_factory=list)
    #: The interface of each PROTO read from a file, by its name: the fields (with their
    #: defaults) a supervisor finds on an instance that leaves them out.
    interfaces: dict[str, dict[str, FieldDeclaration]] = field(default_factory=dict)


@dataclass(frozen=True)
class _Scope:
    """The file whose text is being expanded: its location and its EXTERNPROTO declarations."""

    base: str
    externprotos: dict[str, str]
    #: The line in the world of the outermost instance (for messages).
    world_line: int | None = None


class Expander:
    """Expands the PROTO instances of one world.

    Args:
        world: The world file's path.
        text: Its text.
        version: Its Webots version tag (``R2023b``).
    """

    def __init__(self, world: str, text: str, version: str, y_up: bool) -> None:
        self.world = os.path.abspath(world)
        self.text = text
        self.y_up = y_up
        self.resolver = Resolver(world, version)
        self.report = ExpansionReport()
        self._definitions: dict[tuple[str, str], ProtoDefinition | None] = {}
        self._instances = 0
        #: The ``IS`` links of each PROTO body read so far, by (origin, body text).
        self._references: dict[tuple[str, str], list[_Reference]] = {}
        #: The characters of node text the expansions made so far (:data:`MAX_EXPANDED_TEXT`).
        self._expanded = 0
        self._said: set[str] = set()
        #: The text each template made, by PROTO and fields.
        self._made: dict[tuple[str, str, str], str] = {}

    def expand_world(self) -> str:
        """The world's text with every PROTO instance that can be read expanded."""
        types = {m.group(1) for m in _NODE_TYPE.finditer(_COMMENT.sub("", self.text))}
        if types & OWN_ROBOT_TYPES:
            self.text = self._own_robot_devices(self.text)
        if not any(self._expandable(t) for t in types):
            return self.text  # nothing to expand: a large mesh world is not tokenized for it
        scope = _Scope(self.world, externproto_urls(self.text))
        text = self._expand(self.text, scope, 0, keep_lines=True)
        self.report.cache_hits = list(self.resolver.cache_hits)
        self.report.downloads = list(self.resolver.downloads)
        return text

    def _own_robot_devices(self, text: str) -> str:
        """The world with the devices its project's own e-puck PROTO adds put into each
        instance's ``turretSlot`` (see :mod:`.own_robot`)."""
        try:
            nodes = parse_nodes(text, self.world)
        except WorldFormatError:
            return text  # the core says where the world is malformed
        inserts: list[tuple[int, str]] = []
        for node in outermost(nodes, OWN_ROBOT_TYPES):
            source = self.resolver.project_proto(node.type_name)
            devices = added_devices(source.text, source.origin) if source else []
            if source is None or not devices:
                continue
            inserts.append(with_devices(text, node, devices))
            names = ", ".join(f'{kind} "{name}"' for name, kind in _kinds(devices))
            self._say(
                f"the project's own {node.type_name} PROTO ({source.origin}) adds "
                f"{names} to Webots' e-puck: mounted in its turretSlot"
            )
        for at, insert in sorted(inserts, reverse=True):
            text = text[:at] + insert + text[at:]
        return text

    def _say(self, message: str) -> None:
        if message not in self._said:
            self._said.add(message)
            self.report.warnings.append(message)

    def _expand(self, text: str, scope: _Scope, depth: int, keep_lines: bool = False) -> str:
        if "{" not in text or not any(map(self._expandable, set(_NODE_TYPE.findall(text)))):
            return text  # no node of a PROTO type: nothing to parse (a mesh of 0.9 MB took 1 s)
        try:
            nodes = parse_nodes(text, scope.base)
        except WorldFormatError:
            if keep_lines:  # the world itself is malformed: the core says where
                return text
            raise
        replacements: list[tuple[int, int, str]] = []

        def walk(node: Node) -> None:
            expandable = node.use_name is None and self._expandable(node.type_name)
            if expandable and self._expanded <= MAX_EXPANDED_TEXT:
                expansion = self._instance(text, node, scope, depth, keep_lines)
                if expansion is not None and self._within_bound(expansion):
                    replacements.append((node.start, node.end, expansion))
                    return
            for item in node.fields:
                if item.name in VISUAL_FIELDS:
                    continue
                for child in item.nodes:
                    walk(child)

        for node in nodes:
            walk(node)
        # The text with each instance's node replaced by its expansion, joined once (rebuilding
        # the whole text at each replacement took time of the square of its length).
        pieces, done = [], 0
        for start, end, expansion in sorted(replacements):
            original = text[start:end]
            if keep_lines:
                breaks = line_of(original, len(original)) - 1
                expansion = expansion + "\n" * breaks
            pieces += [text[done:start], expansion]
            done = end
        return "".join([*pieces, text[done:]])

    def _within_bound(self, expansion: str) -> bool:
        """Counts ``expansion``'s characters; False, said once, past :data:`MAX_EXPANDED_TEXT`
        (the instance is then left as it is, as one past :data:`MAX_INSTANCES`)."""
        before = self._expanded
        self._expanded += len(expansion)
        if self._expanded <= MAX_EXPANDED_TEXT:
            return True
        if before <= MAX_EXPANDED_TEXT:
            self._say(
                f"the world's PROTO instances expand to more than {MAX_EXPANDED_TEXT} characters "
                "of nodes; the rest are not expanded"
            )
        return False

    @staticmethod
    def _expandable(type_name: str) -> bool:
        return type_name not in BASE_NODES and type_name not in CORE_TYPES

    def _where(self, text: str, node: Node, scope: _Scope, keep_lines: bool) -> str:
        if keep_lines:
            return f"line {line_of(text, node.start)}: {node.type_name}"
        if scope.world_line is not None:
            return f"line {scope.world_line}: {node.type_name} (in a PROTO)"
        return node.type_name

    def _definition(self, name: str, scope: _Scope, where: str) -> ProtoDefinition | None:
        url = scope.externprotos.get(name)
        key = (name, url or "")
        if key in self._definitions:
            return self._definitions[key]
        source: ProtoSource | None = None
        try:
            if url is not None:
                source = self.resolver.declared(url, scope.base)
                if source is None:
                    self._say(
                        f'{where}: EXTERNPROTO "{url}": no such file beside '
                        f"{scope.base}; looked in the project's protos/ folder instead"
                    )
            if source is None:
                source = self.resolver.undeclared(name)
        except ProtoUnavailableError as unavailable:
            official = url is not None and (
                url.startswith("webots://") or "cyberbotics/webots/" in url
            )
            if not official:
                raise
            source = None  # Webots' own PROTO while offline: a stand-in, if mazesim has one
            if name not in STAND_INS:
                self.report.unreadable[name] = str(unavailable)
        except (OSError, UnicodeError, ValueError) as error:
            # Not a MazesimError: a location the file system cannot even look up.
            self._say(f"{where}: its PROTO file cannot be read ({error}); not expanded")
            source = None
        definition = None
        if source is not None:
            definition = parse_definition(source.text, source.origin)
            definition.externprotos = externproto_urls(source.text)
            self.report.expanded.setdefault(name, source.origin)
            self.report.interfaces.setdefault(name, definition.fields)
        elif name in STAND_INS:
            stand_in = STAND_INS[name]
            definition = parse_definition(stand_in.text, f"mazesim's stand-in for {name}")
            self.report.stand_ins[name] = stand_in.description
        self._definitions[key] = definition
        return definition

    def _instance(
        self, text: str, node: Node, scope: _Scope, depth: int, keep_lines: bool
    ) -> str | None:
        where = self._where(text, node, scope, keep_lines)
        if depth >= MAX_NESTING:
            self._say(f"{where}: PROTOs nest deeper than {MAX_NESTING} levels; not expanded")
            return None
        self._instances += 1
        if self._instances > MAX_INSTANCES:
            self._say(
                f"the world expands to more than {MAX_INSTANCES} PROTO instances; "
                "the rest are not expanded"
            )
            return None
        definition = self._definition(node.type_name, scope, where)
        if definition is None:
            return None
        if definition.origin.startswith("mazesim's stand-in"):
            self._say(
                f"{where}: Webots' {node.type_name} PROTO cannot be read (no WEBOTS_HOME, not "
                "in the cache, no network): imported as mazesim's stand-in "
                f"({STAND_INS[node.type_name].description})"
            )
        world_line = scope.world_line if scope.world_line is not None else line_of(text, node.start)
        inner = _Scope(definition.origin, definition.externprotos, world_line)
        values: dict[str, str] = {}
        for name, declaration in definition.fields.items():
            given = node.field(name)
            if given is not None and given.is_reference is None:
                # `hidden` lines are engine state; the core's reader skips the rest of their line,
                # which on an expansion's single line would be the rest of the expansion.
                value = _HIDDEN_LINE.sub("", text[given.value_start : given.value_end])
                values[name] = self._expand(value, scope, depth + 1)
            else:
                values[name] = declaration.default
        # `hidden name value` lines (engine state) read as a field `hidden` and the next one.
        hidden = {
            later.name
            for earlier, later in zip(node.fields, node.fields[1:])
            if earlier.name == "hidden"
        }
        unknown = [
            f.name
            for f in node.fields
            if f.name not in definition.fields and f.name != "hidden" and f.name not in hidden
        ]
        for name in unknown:
            self._say(
                f"{where}: field `{name}` is not a field of the PROTO {definition.name}; ignored"
            )
        body = definition.body
        if definition.language is not None:
            try:
                template_fields = {
                    name: {
                        "value": field_value(d.kind, values[name]),
                        "defaultValue": field_value(d.kind, d.default),
                    }
                    for name, d in definition.fields.items()
                }
            except ValueError as error:
                raise located_error(f"{where}: {error}", self.world) from None
            made = self._template(definition, definition.language, template_fields)
            if made is None:
                return None
            body = made
        body = self._substitute(body, values, definition)
        body = self._expand(body, inner, depth + 1)
        flat = " ".join(token.text for token in tokenize(body, definition.origin))
        if node.def_name:
            flat = _with_def(flat, node.def_name)
        return flat

    def _template(
        self, definition: ProtoDefinition, language: str, fields: dict[str, Any]
    ) -> str | None:
        """The text a procedural PROTO's template makes for these fields (run once for each
        PROTO and fields), or None past :data:`MAX_TEMPLATE_RUNS`."""
        key = (definition.origin, definition.name, repr(fields))
        made = self._made.get(key)
        if made is not None:
            return made
        if len(self._made) >= MAX_TEMPLATE_RUNS:
            self._say(
                f"the world runs more than {MAX_TEMPLATE_RUNS} PROTO templates (instances whose"
                " fields differ); the rest are not expanded"
            )
            return None
        made = evaluate_template(
            language,
            definition.body,
            fields,
            self._context(definition),
            definition.origin,
        )
        self._made[key] = made
        return made

    def _context(self, definition: ProtoDefinition) -> dict[str, Any]:
        platform = {"win32": "windows", "darwin": "mac"}.get(sys.platform, "linux")
        proto = definition.origin
        return {
            "world": self.world,
            "proto": proto,
            "project_path": self.resolver.project,
            "webots_version": {"major": self.resolver.version, "revision": "0"},
            "webots_home": os.environ.get("WEBOTS_HOME", ""),
            "temporary_files_path": "",
            "os": platform,
            "id": 0,
            "coordinate_system": "NUE" if self.y_up else "ENU",
        }

    def _substitute(self, body: str, values: dict[str, str], definition: ProtoDefinition) -> str:
        """``body`` with each ``field IS name`` given the instance's value of ``name``. One
        naming a field the PROTO does not declare is left unlinked, as Webots leaves it
        (``WbNode::createProtoInstance`` finds no parameter to copy): the field is dropped and
        keeps its node's default, with a warning."""
        key = (definition.origin, body)
        references = self._references.get(key)
        if references is None:
            references = self._references[key] = _references(body, definition.origin)
        pieces, done = [], 0
        for (start, value_start, end), target, linked, node_type in references:
            if target not in values:
                self._say(
                    f"{definition.origin}: `{linked} IS {target}`: {definition.name} has no "
                    f"field `{target}`; left unlinked, as in Webots: {node_type}'s `{linked}` "
                    "keeps its default"
                )
                pieces += [body[done:start]]
            else:
                pieces += [body[done:value_start], values[target]]
            done = end
        return "".join([*pieces, body[done:]])


#: Where a PROTO body links a field (``field IS name``): the field's start, its value's start and
#: its value's end, the name linked, the field and its node's type.
_Reference = tuple[tuple[int, int, int], str, str, str]


def _references(body: str, origin: str) -> list[_Reference]:
    """The ``IS`` links of a PROTO body, in text order (read once per body: a body of 0.9 MB
    took a second to read for each instance)."""
    found: list[_Reference] = []

    def walk(node: Node) -> None:
        for item in node.fields:
            target = item.is_reference
            if target is not None:
                place = (item.start, item.value_start, item.value_end)
                found.append((place, target, item.name, node.type_name))
            for child in item.nodes:
                walk(child)

    for node in parse_nodes(body, origin):
        walk(node)
    return sorted(found)


def _with_def(flat: str, def_name: str) -> str:
    """The expansion with the instance's DEF name on its root node."""
    words = flat.split(" ", 2)
    if words and words[0] == "DEF" and len(words) == 3:
        return f"DEF {def_name} {words[2]}"
    return f"DEF {def_name} {flat}"


def _kinds(devices: list[tuple[str, str]]) -> list[tuple[str, str]]:
    """``(name, node type)`` of each ``(name, node text)``."""
    return [(name, node.split("{", 1)[0].split()[-1]) for name, node in devices]
