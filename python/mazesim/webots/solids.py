"""What a supervisor moves when it moves a node that is not a robot's.

The import report names, for each obstacle and each sensed-only wall (a visual-only shape the
infra-red rays and cameras see, as walls of the world) and each movable body, the lines of the
world file's nodes that hold it (its ``owners``). A supervisor's node of one of
those lines holds them: setting its ``translation`` or ``rotation`` moves them all by the rigid
motion that takes the node's old pose (seen from above) to its new one, in the simulation, at
the next step. A node that holds one movable body and nothing else follows that body: its
position, orientation and velocity are the body's, live (a box the robot pushed is where it was
pushed to).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = [
    "Held",
    "Pose2",
    "WorldSolids",
    "as_given",
    "carried_over",
    "composed",
    "held_by_line",
    "relative",
    "world_objects",
]

#: A pose seen from above: x, y (m, world frame) and yaw (rad).
Pose2 = tuple[float, float, float]


@dataclass
class Held:
    """The obstacles and movable bodies a node holds.

    Attributes:
        walls: The indices of its walls among the world's ``[[walls]]``.
        bodies: The indices of its movable bodies, world order.
        paint: The indices of its floor marks among the world's ``[[paint]]``.
        obstacle: Whether it is a robot that is no e-puck, whose collision shapes are the
            world's obstacles where the world is simulated (not in its own import, where the
            e-puck stands in for it).
    """

    walls: list[int] = field(default_factory=list)
    bodies: list[int] = field(default_factory=list)
    paint: list[int] = field(default_factory=list)
    obstacle: bool = False

    def __bool__(self) -> bool:
        return bool(self.walls or self.bodies or self.paint or self.obstacle)


def held_by_line(report: Mapping[str, Any]) -> dict[int, Held]:
    """What the nodes of each line of the world file hold, read from an import report's
    ``obstacles`` and ``sensed_only`` walls (their ``owners`` and ``walls``) and ``bodies``
    (their ``owners``) and ``floor_marks`` (their ``owners`` and ``paint``)."""
    held: dict[int, Held] = {}
    for obstacle in [*report.get("obstacles", []), *report.get("sensed_only", [])]:
        first, count = obstacle.get("walls", (0, 0))
        for line in obstacle.get("owners", []):
            held.setdefault(int(line), Held()).walls.extend(range(first, first + count))
    for index, body in enumerate(report.get("bodies", [])):
        for line in body.get("owners", []):
            held.setdefault(int(line), Held()).bodies.append(index)
    for mark in report.get("floor_marks", []):
        for line in mark.get("owners", []):
            held.setdefault(int(line), Held()).paint.append(int(mark["paint"]))
    return held


class WorldSolids:
    """The walls and movable bodies of a world's simulators, moved by the line of the node
    that holds them (a world's wall indices depend on the robot it was imported for: a robot
    that is not an e-puck is no obstacle in its own import, so the nodes are named by line)."""

    def __init__(self, simulators: list[Any], report: Mapping[str, Any]) -> None:
        """Over ``simulators`` (each holding a copy of the world, the one whose bodies are read
        first), imported with ``report``."""
        self._simulators = simulators
        self._held = held_by_line(report)
        self._bodies = list(report.get("bodies") or [])
        #: The nodes moved since the start or the last reset, by line: their pose in the file
        #: and now, seen from above.
        self._moves: dict[int, tuple[Pose2, Pose2]] = {}
        #: The fields a supervisor set on light nodes since the start or the last reset, by
        #: the line of the light's node, and how many times it set one or a reset undid them.
        self._light_fields: dict[int, dict[str, Any]] = {}
        self.light_changes = 0

    def edit_light(self, line: int, name: str, value: Any) -> None:
        """Notes that a supervisor set field ``name`` of the light node on ``line`` to
        ``value`` (numbers, or a flag for ``on``): every robot's light sensors see the light
        so from then on (:func:`~mazesim.webots.lights.lit`)."""
        self._light_fields.setdefault(int(line), {})[str(name)] = value
        self.light_changes += 1

    def light_edits(self) -> dict[int, dict[str, Any]]:
        """The fields a supervisor set on light nodes, by the line of each light's node."""
        return {line: dict(fields) for line, fields in self._light_fields.items()}

    def node_moves(self) -> dict[int, tuple[Pose2, Pose2]]:
        """The nodes holding walls or floor marks that a supervisor moved since the start or
        the world's last reset, by line: their pose seen from above in the file and now."""
        return dict(self._moves)

    def forget_moves(self) -> None:
        """The world's reset put every node back where the file has it, and every light's
        fields as the file gives them."""
        self._moves.clear()
        if self._light_fields:
            self._light_fields.clear()
            self.light_changes += 1

    def body_poses(self) -> list[tuple[float, float, float]]:
        """The movable bodies' poses (x, y, yaw) now, in world order."""
        return [tuple(p) for p in self._simulators[0].body_poses()]

    def body_velocities(self) -> list[tuple[float, float, float]]:
        """The movable bodies' velocities (vx, vy, turn rate) now, in world order."""
        return [tuple(v) for v in self._simulators[0].body_velocities()]

    def drawn_bodies(self) -> list[tuple[Pose2, Mapping[str, Any]]]:
        """Each movable body of the world as it is now (a supervisor's changes included): its
        pose (x, y, yaw) and its entry of the import report (shape, ``colour``, ``sphere``,
        ``height``), in world order; what a camera draws."""
        if not self._bodies:
            return []
        return list(zip(self.body_poses(), self._bodies))

    def move_node(self, line: int, from_pose: Pose2, to_pose: Pose2) -> None:
        """Moves what the node on ``line`` holds by the motion from ``from_pose`` to
        ``to_pose`` (a motion that moves nothing stops its bodies).

        Raises:
            InvalidArgumentError: A pose beyond the limits; nothing moved.
        """
        held = self._held.get(int(line))
        if not held:
            return
        still = tuple(from_pose) == tuple(to_pose)
        walls, paint = ([], []) if still else (held.walls, held.paint)
        for simulator in self._simulators:
            simulator.move_solid(walls, held.bodies, from_pose, to_pose, paint)
        if walls or paint:
            first = self._moves.get(int(line), (tuple(from_pose), tuple(from_pose)))[0]
            self._moves[int(line)] = (first, tuple(to_pose))  # type: ignore[assignment]

    def set_body_velocity(self, index: int, vx: float, vy: float, turn_rate: float) -> None:
        """Sets the velocity of movable body ``index`` (world order) in every simulator.

        Raises:
            InvalidArgumentError: An index past the bodies or a speed beyond the limits.
        """
        for simulator in self._simulators:
            simulator.set_body_velocity(index, vx, vy, turn_rate)


def carried_over(
    before: WorldSolids | None,
    simulators: list[Any],
    worlds: list[Any],
    report: Mapping[str, Any],
    kept_robots: list[int | None] | None = None,
    robot_profiles: list[Any] | None = None,
) -> WorldSolids:
    """The walls and movable bodies of ``simulators`` once each runs on in its world of
    ``worlds`` (imported with ``report``; a supervisor changed the world), the walls that
    ``before`` moved moved again where they were put. The first simulator's robots change as
    ``kept_robots`` says, when given, the new ones of ``robot_profiles`` where it gives one
    (``Simulator.change_world``).

    Raises:
        InvalidArgumentError: A world holds other robots than the running one (without
            ``kept_robots``).
    """
    moves = before.node_moves() if before is not None else {}
    for number, (simulator, world) in enumerate(zip(simulators, worlds)):
        if number == 0 and kept_robots is not None:
            simulator.change_world(world, kept_robots, robot_profiles)
        else:
            simulator.change_world(world)
    after = WorldSolids(simulators, report)
    if before is not None:  # the lights a supervisor set stay set
        after._light_fields = before.light_edits()
        after.light_changes = before.light_changes
    for line, (start, now) in moves.items():
        held = after._held.get(line)
        if held is not None and (held.walls or held.paint):
            for simulator in simulators:
                simulator.move_solid(held.walls, [], start, now, held.paint)
            after._moves[line] = (start, now)
    return after


def world_objects(simulation: Any) -> Any:
    """What answers ``body_poses``, ``body_velocities``, ``move_node``, ``node_moves`` and
    ``set_body_velocity`` for the world of a run (the same one all through it): the world's
    robots (the :class:`~mazesim.webots.lockstep.Fleet`) when another process
    owns the world, else the :class:`WorldSolids` of its simulator."""
    if simulation.fleet is not None:
        return simulation.fleet
    if simulation.solids is None:
        simulation.solids = WorldSolids([simulation.simulator], simulation.report)
    return simulation.solids


def relative(base: Pose2, pose: Pose2) -> Pose2:
    """``pose`` in the frame of ``base``."""
    dx, dy = pose[0] - base[0], pose[1] - base[1]
    c, s = math.cos(base[2]), math.sin(base[2])
    return c * dx + s * dy, -s * dx + c * dy, pose[2] - base[2]


def composed(base: Pose2, offset: Pose2) -> Pose2:
    """The pose ``offset`` gives in the frame of ``base``."""
    c, s = math.cos(base[2]), math.sin(base[2])
    x, y, yaw = offset
    return base[0] + c * x - s * y, base[1] + s * x + c * y, base[2] + yaw


def as_given(physics: Pose2, *given: Pose2 | None) -> Pose2:
    """The first of the poses ``given`` (one the world file or a supervisor gave a node, in
    double precision) that ``physics`` is, to the simulation's own precision, else ``physics``.

    The simulation keeps poses in single precision (float32, as its batched runs do), where
    Webots keeps them in double and its supervisor returns doubles (``const double
    *wb_supervisor_node_get_position``, Webots' reference manual, Supervisor): a node put at
    x = 0.1 would read 0.10000000149011612. While the simulation holds it still where it was
    put, the node reads the double it was given; once it moves, the simulation's pose. Each
    coordinate may differ by two float32 steps at its size (the rounding of the value stored,
    and of the poses it is composed with), a yaw by whole turns too; a robot moving at 1 mm/s
    moves 32 um in a step of 32 ms, far more."""
    for pose in given:
        if pose is not None and all(
            abs(math.remainder(p - g, math.tau) if i == 2 else p - g) <= _single_step(g)
            for i, (p, g) in enumerate(zip(physics, pose))
        ):
            return pose
    return physics


def _single_step(value: float) -> float:
    """Two float32 steps at ``value``'s size, and 1e-12 besides (a value of 0 computed two
    ways)."""
    return 2.0 * float(np.spacing(np.float32(min(abs(value), 3.0e38)))) + 1.0e-12
