"""The walls and floor that a robot's own casts (its camera, a distance sensor the world adds)
meet now: where a supervisor moved them, with what it imported and without what it removed.

The walls are the robot's own import of the running world (the world file, or its text as a
supervisor's imports and removals changed it: :mod:`mazesim.webots.scene_edits`), each node a
supervisor moved moved again by the motion from its pose in the file to its pose now
(:func:`~mazesim.webots.line_of_sight.moved_walls`). In a run of one robot both are at hand
(the simulation's world and its :class:`~mazesim.webots.solids.WorldSolids`); in a world run
the world's process holds them, and each step's answer says how many times the walls have
changed (``wall_changes``), so a robot asks for the changed world only after a change. The
world's process reads its own walls the same way (:class:`WorldWalls`: what stops the radio's
infra-red packets, what a recorded run draws), from the same count.

What else a robot's casts meet: the other robots of a world run (:class:`OtherRobots`, also
what its touch sensors touch and its camera draws) and, for the rays of the devices the world
adds, the movable bodies too (:class:`ObstaclesNow`).
"""

from __future__ import annotations

import weakref
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from mazesim.webots.line_of_sight import moved_walls
from mazesim.webots.rays import FloorPaint, WallBoxes
from mazesim.webots.solids import Held, held_by_line, world_objects

if TYPE_CHECKING:
    from mazesim._core import World
    from mazesim.webots.lockstep import Fleet
    from mazesim.webots.robot_frames import RobotShape
    from mazesim.webots.simulation import RobotSimulation

__all__ = ["ObstaclesNow", "OtherRobots", "WallsNow", "WorldWalls", "walls_seen"]

#: What a node that holds nothing holds.
_NONE = Held()


def walls_seen(simulation: RobotSimulation | WorldWalls) -> Any:
    """What the walls of ``simulation``'s world are made from now, which changes when a
    supervisor changes them: in a world run the world's count of changes (told with each
    step's answer), else the simulation's world (a supervisor's imports and removals replace
    it) and the moves of its nodes."""
    if simulation.fleet is not None:
        return getattr(simulation.simulator, "wall_changes", 0)
    return (id(simulation.world), sorted(world_objects(simulation).node_moves().items()))


class WallsNow:
    """The walls and floor paint of a robot's world as they are now, read again only after a
    change.

    Args:
        simulation: The robot's simulation (or the world's own, :class:`WorldWalls`).
        sensed: Whether the walls include the sensed-only ones (infra-red rays and cameras).
    """

    def __init__(self, simulation: RobotSimulation | WorldWalls, sensed: bool = False) -> None:
        self._simulation = simulation
        self._sensed = sensed
        #: The import the walls are made of (world, report) and the world-run text it read.
        self._world: World | None = None
        self._report: Mapping[str, Any] = {}
        self._text: str | None = None
        self._base: WallBoxes | None = None
        self._floor: FloorPaint | None = None
        #: The world and the moves of paint-holding nodes the floor paint was made from, and
        #: what the walls were made from then (:attr:`_seen`).
        self._floor_seen: Any = None
        self._floor_walls: Any = None
        #: What the walls were made from last: the world and the moves (a run of one robot),
        #: or the world's count of changes (a world run).
        self._seen: Any = None
        self._walls: WallBoxes | None = None

    def _import(self) -> None:
        """Takes the running world's import: the simulation's own in a run of one robot (a
        supervisor's change replaces it); in a world run, the world's text as changed, imported
        for this robot as at its start."""
        simulation = self._simulation
        world: World = simulation.world
        report: Mapping[str, Any] = simulation.report
        if simulation.fleet is not None:
            text = simulation.fleet.text
            if text is not None and text != self._text:
                from mazesim.webots.importer import import_wbt_text

                robot_line = simulation.report.get("robot_line")
                world, report = import_wbt_text(
                    text, str(simulation.report.get("path") or ""), robot_line=robot_line
                )
                self._text = text
            elif text is not None and self._world is not None:
                world, report = self._world, self._report
        if world is not self._world:
            self._world, self._report = world, report
            self._base = WallBoxes(world, sensed=self._sensed)
            self._floor = None

    def walls(self) -> WallBoxes:
        """The walls now."""
        seen = walls_seen(self._simulation)
        # The world the last walls were made of is held, so its id is not another's.
        if self._walls is not None and seen == self._seen:
            return self._walls
        self._import()
        assert self._base is not None
        held = {line: h.walls for line, h in held_by_line(self._report).items() if h.walls}
        moves = dict(world_objects(self._simulation).node_moves())
        self._walls = moved_walls(self._base, held, moves)
        self._seen = seen
        return self._walls

    def base(self) -> WallBoxes:
        """The walls of the running world's import, none moved (what a camera's recognition
        moves itself)."""
        self.walls()
        assert self._base is not None
        return self._base

    def floor(self) -> FloorPaint:
        """The floor paint now: the floor marks of the nodes a supervisor moved where it put
        them."""
        self.walls()
        assert self._world is not None
        if self._floor is not None and self._floor_walls == self._seen:
            return self._floor  # nothing moved since
        self._floor_walls = self._seen
        held = held_by_line(self._report)
        moves = world_objects(self._simulation).node_moves()
        # Only the moves of nodes holding paint change the floor (a supervisor that moves a box
        # at every step leaves a textured floor's paint as it was read).
        painted = sorted(
            (line, move) for line, move in moves.items() if held.get(line, _NONE).paint
        )
        seen = (id(self._world), painted)
        if self._floor is None or self._floor_seen != seen:
            world = self._world
            for line, (start, now) in painted:
                world = world.with_paint_moved(held[line].paint, start, now)
            self._floor = FloorPaint(world)
            self._floor_seen = seen
        return self._floor


class OtherRobots:
    """The other robots of a robot's world run where they are now, as its touch sensors, its
    camera and the rays of the devices the world adds meet them: one per simulation
    (:meth:`of`), which asks for their places once a step.

    Args:
        simulation: The robot's simulation.
    """

    _made: weakref.WeakKeyDictionary[Any, OtherRobots] = weakref.WeakKeyDictionary()

    @classmethod
    def of(cls, simulation: RobotSimulation) -> OtherRobots:
        """The simulation's one :class:`OtherRobots` (its devices share it)."""
        made = cls._made.get(simulation)
        if made is None:
            made = cls._made[simulation] = cls(simulation)
        return made

    def __init__(self, simulation: RobotSimulation) -> None:
        self._simulation = simulation
        #: The step the other robots' places were last asked at, and those places.
        self._asked: tuple[int, list[tuple[float, float, float]]] | None = None
        #: The shared simulator's ``other_robots`` call, False where the simulator holds this
        #: robot alone; asked once (over a controller's pipe, each question is a round trip).
        self._call: Any = None
        #: Each robot of the world run (its import report entry) with its visual shapes, once
        #: read.
        self._shapes: list[tuple[Mapping[str, Any], list[RobotShape]]] | None = None

    def shared(self) -> bool:
        """Whether the robot's simulator holds the other robots too (a
        :class:`~mazesim.webots.shared_world.RobotView`, here or over a controller's pipe)."""
        if self._call is None:
            self._call = getattr(self._simulation.simulator, "other_robots", None) or False
        return self._call is not False

    def now(self) -> list[tuple[float, float, float]]:
        """(x, y, body radius) of each other robot now: those of a simulator shared with them,
        else each e-puck of the world run (a robot of a profile) of the E-puck's body radius;
        none in a run of one robot."""
        simulation = self._simulation
        if self.shared():
            # Over a controller's pipe each question is a round trip: asked once a step.
            step = int(simulation.steps)
            if self._asked is None or self._asked[0] != step:
                places = [(float(x), float(y), float(r)) for x, y, r in self._call()]
                self._asked = (step, places)
            return list(self._asked[1])
        if simulation.fleet is None:
            return []
        from mazesim.webots.shared_world import E_PUCK_BODY_RADIUS

        robots = simulation.report.get("robots") or []
        return [
            (float(pose[0]), float(pose[1]), E_PUCK_BODY_RADIUS)
            for index, pose in enumerate(simulation.fleet.poses())
            if pose is not None and index != simulation.robot_index
            if index < len(robots) and robots[index].get("profile") is not None
        ]

    def shapes_now(self) -> list[tuple[RobotShape, tuple[float, float, float], bool]]:
        """The visual shapes of the other robots of a world run (those of their nodes that are
        primitives: :func:`~mazesim.webots.robot_frames.robot_shapes`), each with its robot's
        pose now and whether that robot is an e-puck (a robot of a profile); empty in a run of
        one robot."""
        simulation = self._simulation
        if simulation.fleet is None:
            return []
        if self._shapes is None:
            from mazesim.webots.robot_frames import robot_shapes

            by_line = robot_shapes(simulation.scene)
            self._shapes = [
                (robot, by_line.get(int(robot.get("line") or 0), []))
                for robot in simulation.report.get("robots") or []
            ]
        if not any(shapes for _, shapes in self._shapes):
            return []
        found: list[tuple[RobotShape, tuple[float, float, float], bool]] = []
        for index, pose in enumerate(simulation.fleet.poses()):
            if index == simulation.robot_index or index >= len(self._shapes) or pose is None:
                continue
            robot, shapes = self._shapes[index]
            placed = (float(pose[0]), float(pose[1]), float(pose[2]))
            e_puck = robot.get("profile") is not None
            found.extend((shape, placed, e_puck) for shape in shapes)
        return found


class ObstaclesNow:
    """What the rays of a distance sensor, lidar or range finder the world adds to a robot meet
    now: the walls (:class:`WallsNow`), the world's movable bodies and the other robots of a
    world run (:class:`OtherRobots`), as Webots' rays meet every solid.

    Args:
        simulation: The robot's simulation.
        sensed: Whether the walls include the sensed-only ones (infra-red rays, scanners).
    """

    def __init__(self, simulation: RobotSimulation, sensed: bool = False) -> None:
        self._simulation = simulation
        self._sensed = sensed
        self._walls = WallsNow(simulation, sensed)
        self._robots = OtherRobots.of(simulation)

    def boxes(self) -> WallBoxes:
        """The walls now and what else stands on the floor where it is now: what a camera draws
        beside the walls (:func:`~mazesim.webots.camera.solids_now`: the world's movable
        bodies; the other robots' visual shapes where the sensed-only walls are met too, as
        they are of the same kind), each standing from the floor to its top (a ball as the
        upright cylinder of its radius, a shape above the floor as if it reached down to it),
        and the other robots' bodies, upright cylinders of their body radius as high as the
        E-puck's bounding cylinder, of reflection factor
        :data:`~mazesim._core.ROBOT_REFLECTANCE` (as the E-puck's own rays meet them)."""
        from mazesim._core import ROBOT_REFLECTANCE
        from mazesim.webots.camera import ROBOT_TOP, Ball, solids_now

        boxes, box_tops, discs, disc_tops = [], [], [], []
        for solid in solids_now(self._simulation, self._robots, visual=self._sensed):
            if isinstance(solid, Ball):
                discs.append((solid.x, solid.y, solid.radius, solid.reflectance))
                disc_tops.append((solid.radius if solid.z is None else solid.z) + solid.radius)
            elif solid.size is None:
                discs.append((solid.x, solid.y, solid.radius, solid.reflectance))
                disc_tops.append(solid.height)
            else:
                width, depth = solid.size
                boxes.append((solid.x, solid.y, width, depth, solid.yaw, solid.reflectance))
                box_tops.append(solid.height)
        for x, y, radius in self._robots.now():
            discs.append((x, y, radius, ROBOT_REFLECTANCE))
            disc_tops.append(ROBOT_TOP)
        walls = self._walls.walls()
        if not boxes and not discs:
            return walls
        return walls.with_solids(
            np.asarray(boxes), np.asarray(box_tops), np.asarray(discs), np.asarray(disc_tops)
        )


@dataclass
class WorldWalls:
    """The running world as its own process holds it, read as a robot's simulation is by
    :class:`WallsNow`: the world's :class:`~mazesim.webots.lockstep.Fleet` (its text as a
    supervisor changed it, its moves, its count of changes) and the world file's import.

    Args:
        fleet: The world's robots, which count its changes.
        world: The world file's import (no robot chosen).
        report: Its import report.
    """

    fleet: Fleet
    world: World
    report: Mapping[str, Any]

    def __post_init__(self) -> None:
        # The world's own import chooses no robot, as the fleet imports the changed text.
        self.report = {**self.report, "robot_line": None}

    @property
    def simulator(self) -> Fleet:
        """What counts the world's changes (``wall_changes``)."""
        return self.fleet
