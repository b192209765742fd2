"""The world a supervisor changes while it runs: nodes imported into a ``children`` field
(``importMFNodeFromString``) or an empty single-node field such as a ``Slot``'s ``endPoint``
(``importSFNodeFromString``), and top-level or imported nodes removed (``Node.remove()``,
``removeMF``, ``removeSF``).

The running world's description is the world file's text with each removed node's lines left
blank and each imported node's text after it, in import order (so every node keeps its line,
by which the import report names what it holds). A node imported into another node's field
is written inside a ``Pose`` at that node's frame in the world, so that its ``translation`` and
``rotation`` are in its parent's frame, as Webots places it; it goes when its parent goes.
A supervisor's reset takes the imported nodes out and leaves the removed ones out, as Webots'
does. Each change imports that description again with the importer that read the world file
(PROTOs, DEF names, fields) and gives the result to the simulator, which runs on in it from the
next step (what the import says of the new nodes, a robot that is not an e-puck kept as an
obstacle whose controller does not start, is printed once as a warning): the robots keep their
poses, velocities, wheel encoders, noise streams and clocks, the movable bodies the change
keeps go on where they are (an imported Solid with physics is a new one, at rest), and the
walls a supervisor moved are moved again where it put them. In a world run (every robot with its
controller) e-pucks are imported and robots removed too (:mod:`mazesim.webots.robots_changed`);
a run of one controller refuses a change that would add or remove an e-puck, with an error
naming it.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from typing import Any

from mazesim.errors import MazesimError
from mazesim.webots.frames import Frame, axis_angle, enu_to_nue, enu_to_nue_matrix
from mazesim.webots.proto.syntax import unix_line_ends
from mazesim.webots.robots_changed import kept_robots
from mazesim.webots.scene import SceneNode, body_y_up, read_scene, read_world_text
from mazesim.webots.solids import carried_over, held_by_line

__all__ = ["Change", "SceneEdits", "scene_edits"]


@dataclass(frozen=True)
class Change:
    """What a change of the running world made.

    Attributes:
        added: The scene nodes of the nodes imported by it (none for a removal).
        held: What the nodes of each line hold now (:func:`~mazesim.webots.solids.held_by_line`
            of the new import report).
        bodies: The new import report's movable bodies.
    """

    added: list[SceneNode]
    held: dict[int, Any]
    bodies: list[dict[str, Any]]


class SceneEdits:
    """The running world's description as a supervisor changed it, for a run of one robot."""

    def __init__(self, simulation: Any) -> None:
        """Over the world file of ``simulation`` (its import report's ``path``).

        Raises:
            MazesimError: The run's world is no world file.
        """
        path = simulation.report.get("path")
        if not path:
            raise MazesimError("the run's world is no Webots world file")
        self._simulation = simulation
        self._path = str(path)
        #: The world file's lines, a removed node's left blank.
        self._lines = read_world_text(self._path).split("\n")
        #: The lines of each imported node's text, in import order (a removed one's blank).
        self._imported: list[list[str]] = []
        #: The first line of each top-level node of the file and of each imported node.
        self._starts = sorted({node.line for node in simulation.scene.nodes if node.line})
        #: The import's warnings said so far (the world file's at the run's start).
        self._said = set(simulation.report.get("warnings") or [])
        #: The first line of each node imported into another node's field -> that node's line.
        self._parents: dict[int, int] = {}

    def text(self) -> str:
        """The running world's description (see the module's documentation)."""
        return self._text()

    def _text(self) -> str:
        return "\n".join([*self._lines, *(line for lines in self._imported for line in lines)])

    def import_node(self, text: str, into: tuple[int, Frame] | None = None) -> Change:
        """Imports the nodes of ``text`` at the end of the root's ``children``, or into a field
        of the node on line ``into[0]``, whose frame in the world (ENU) is ``into[1]``.

        Raises:
            MazesimError: The text is not nodes the importer reads, or they hold a robot;
                nothing changed.
        """
        first = len(self._lines) + sum(len(lines) for lines in self._imported) + 1
        lines = unix_line_ends(text).split("\n")
        if into is not None:
            lines = [self._frame_line(into[1]), *lines, "] }"]
        self._imported.append(lines)
        try:
            change = self._apply(first, wrapped=into is not None)
        except MazesimError:
            self._imported.pop()
            raise
        self._starts.append(first)
        if into is not None:
            self._parents[first] = into[0]
        return change

    def _frame_line(self, frame: Frame) -> str:
        """The first line of the ``Pose`` (a ``Transform`` in an NUE world) that places the
        nodes of its ``children`` at ``frame``, written in the world file's frame."""
        origin, matrix = frame
        if self._simulation.scene.nue:
            origin, matrix = list(enu_to_nue(*origin)), enu_to_nue_matrix(matrix)
            kind = "Transform"
        else:
            kind = "Pose"
        turn = " ".join(repr(float(v)) for v in axis_angle(matrix))
        at = " ".join(repr(float(v)) for v in origin)
        return f"{kind} {{ translation {at} rotation {turn} children ["

    def remove_node(self, line: int) -> Change:
        """Removes the top-level or imported node whose node type is on ``line``, and the
        nodes imported into its fields.

        Raises:
            MazesimError: The node holds a robot, or the world without it is not one the
                importer reads; nothing changed.
        """
        start = max((s for s in self._starts if s <= line), default=line)
        end = self._end_of(start)
        kept = list(self._lines), [list(lines) for lines in self._imported], dict(self._parents)
        for number in range(start, end + 1):
            self._blank(number)
        self._blank_inside(start, end)
        try:
            return self._apply()
        except MazesimError:
            self._lines, self._imported, self._parents = kept
            raise

    def _end_of(self, start: int) -> int:
        """The last line of the node (top-level or imported) whose text starts on ``start``."""
        later = [s for s in self._starts if s > start]
        return later[0] - 1 if later else len(self._lines) + sum(map(len, self._imported))

    def _blank_inside(self, start: int, end: int) -> None:
        """Leaves blank the nodes imported into a field of a node on lines ``start`` to
        ``end`` (and those imported into theirs)."""
        pending = [(start, end)]
        while pending:
            low, high = pending.pop()
            for first, parent in list(self._parents.items()):
                if low <= parent <= high:
                    del self._parents[first]
                    last = self._end_of(first)
                    for number in range(first, last + 1):
                        self._blank(number)
                    pending.append((first, last))

    @property
    def file_lines(self) -> int:
        """The number of lines of the world file (the imported nodes' come after them)."""
        return len(self._lines)

    def take_out_imports(self, apply: bool = True) -> None:
        """Takes every imported node out, as a supervisor's reset does in Webots (its
        Reset/Reload matrix: a reset from a supervisor removes nodes and does not add removed
        ones back): their lines are left blank, so that later imports take new lines; the world
        runs on without them when ``apply`` (else the world's process changes it itself).

        Raises:
            MazesimError: The world without them is not one the importer reads.
        """
        if not any(line for lines in self._imported for line in lines):
            return
        self._imported = [[""] * len(lines) for lines in self._imported]
        self._parents.clear()
        if apply:
            self._apply()

    def _blank(self, number: int) -> None:
        """Leaves line ``number`` (from 1) of the description blank."""
        if number <= len(self._lines):
            self._lines[number - 1] = ""
            return
        number -= len(self._lines)
        for lines in self._imported:
            if number <= len(lines):
                lines[number - 1] = ""
                return
            number -= len(lines)

    def _apply(self, first: int | None = None, wrapped: bool = False) -> Change:
        """Imports the description and runs on in it (the nodes from line ``first`` on are
        the ones added, when it is given: the children of the ``Pose`` there when
        ``wrapped``)."""
        from mazesim.webots.importer import import_wbt_text

        simulation = self._simulation
        text = self._text()
        robot_line = simulation.report.get("robot_line")
        # The imported nodes come after the file's lines: what the import says of a robot
        # among them that is not an e-puck is what the run makes of it.
        imported_from = self.file_lines + 1 if self._imported else None
        world, report = import_wbt_text(
            text, self._path, robot_line=robot_line, imported_from=imported_from
        )
        lines = {int(r["line"]) for r in simulation.report.get("robots") or []}
        robots = len(kept_robots(report, lines))
        running = len(lines)
        if robots != running and simulation.owns_world:
            raise MazesimError(
                f"expected the world's {running} robots, found {robots}: a run of one "
                "controller adds no robot and removes none (`mazesim webots run WORLD` runs "
                "every robot with its controller, and those a supervisor imports)"
            )
        if simulation.owns_world:
            simulator = simulation.simulator
            simulation.solids = carried_over(simulation.solids, [simulator], [world], report)
            # The import itself: what casts against it moves the moved walls again.
            simulation.world = world
        else:
            simulation.fleet.change_world(text)
        for key in ("obstacles", "bodies"):
            simulation.report[key] = report.get(key, [])
        # What the import says of the new nodes, once (in a world run, what it shares).
        alone = set(report.get("one_controller_warnings") or []) if simulation.fleet else set()
        for warning in report.get("warnings") or []:
            if warning not in self._said and warning not in alone:
                self._said.add(warning)
                print(f"mazesim: warning: {warning}", file=sys.stderr)
        added: list[SceneNode] = []
        if first is not None:
            y_up = body_y_up(report.get("robots") or [], robot_line)
            scene = read_scene(text, report.get("robot_model"), robot_line, y_up)
            added = [node for node in scene.nodes if node.line >= first]
            if wrapped:
                added = [node for pose in added for node in pose.children]
        return Change(added, held_by_line(report), list(report.get("bodies", [])))


def scene_edits(simulation: Any) -> SceneEdits:
    """The :class:`SceneEdits` of ``simulation`` (made at its first change).

    Raises:
        MazesimError: The run's world cannot be changed (see :class:`SceneEdits`).
    """
    edits = getattr(simulation, "scene_edits", None)
    if edits is None:
        edits = SceneEdits(simulation)
        simulation.scene_edits = edits
    return edits
