"""What stands between two points of a Webots world seen from above: the line of sight an
infra-red Emitter's packets need, and the robot bodies that hide an object from a camera.

Webots' reference manual (https://cyberbotics.com/doc/reference/emitter) says of the infra-red
type: "Any solid object (solid, robots, etc ...) with a defined bounding object is a potential
obstacle to an "infra-red" communication. The structure of the emitting or receiving robot
itself will not block an "infra-red" transmission." A :class:`LineOfSight` holds those obstacles
of a world: its walls (where a supervisor moved them; in a world run, also with what it imported
and without what it removed), the bodies of its robots simulated as e-pucks (discs seen from
above, at their live poses, a robot a supervisor imported included) and its movable bodies
(boxes and discs, at their live poses, those a supervisor imported included).
:func:`disc_entries` meets rays with robots' bodies, for the radio and for a camera's
recognition alike.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from typing import Any, Optional, Union

import numpy as np
import numpy.typing as npt

from mazesim.webots.rays import WallBoxes
from mazesim.webots.solids import Pose2, held_by_line

__all__ = ["LineOfSight", "disc_entries", "moved_walls", "robot_body_radii"]

Floats = npt.NDArray[np.float64]


def disc_entries(
    origin: tuple[float, float], units: Floats, centres: Floats, radii: Floats
) -> Floats:
    """How far along each ray from ``origin`` (``units``: (R, 2) unit directions) its line
    enters each disc (``centres`` (N, 2), ``radii`` (N,); a NaN radius is no disc): (R, N)
    distances, negative when the disc holds the origin, ``inf`` where the line misses the
    disc."""
    wx = centres[:, 0] - origin[0]
    wy = centres[:, 1] - origin[1]
    along = units[:, 0:1] * wx + units[:, 1:2] * wy
    across = wx * wx + wy * wy - along * along
    squared = radii * radii
    with np.errstate(invalid="ignore"):
        enter = along - np.sqrt(squared - across)
        return np.where(across < squared, enter, np.inf)


def robot_body_radii(report: Mapping[str, Any]) -> list[float | None]:
    """The body radius of each robot of an import report's ``robots`` that is simulated as
    one (None: a robot whose collision shapes are walls)."""
    from mazesim._core import RobotProfile
    from mazesim.webots.simulation import robot_profile_name

    radii: list[float | None] = []
    for robot in report.get("robots") or []:
        profile = robot.get("profile")
        name = robot_profile_name({"robot_profile": profile})
        radius = float(RobotProfile.builtin(name).body_radius)
        radii.append(radius if profile is not None else None)
    return radii


def moved_walls(
    walls: WallBoxes,
    held_walls: Mapping[int, list[int]],
    moves: Mapping[int, tuple[Pose2, Pose2]],
) -> WallBoxes:
    """The walls where a supervisor moved them: ``moves`` by the line of the node moved (its
    pose in the file and now), ``held_walls`` the walls each node's line holds."""
    for line, (before, now) in moves.items():
        walls = walls.moved(held_walls.get(int(line), []), before, now)
    return walls


#: The robots' body radii by index (None: no body of its own), or what gives them now.
# Union and Optional, not `|`: an alias is evaluated at import, and Python 3.9 has no `|` of types.
Radii = Union[Sequence[Optional[float]], Callable[[], Sequence[Optional[float]]]]


class LineOfSight:
    """The obstacles of a world that stop an infra-red packet.

    Args:
        walls: The world's walls, moved where ``objects`` says a supervisor moved them; or
            what gives the walls now, moved, imported and removed (a world run's
            :class:`~mazesim.webots.walls_now.WallsNow`' ``walls``); None: none.
        radii: The body radius of each robot, by index (None: no body of its own), or what
            gives them now (robots a supervisor imported included).
        report: The world's import report: its movable ``bodies`` and the walls its nodes
            hold (None: neither).
        objects: What answers ``body_poses()`` and ``node_moves()`` now (the world's
            :class:`~mazesim.webots.lockstep.Fleet`), and ``drawn_bodies()`` when the
            world's bodies change (a supervisor's imports); None: the bodies stay where the
            import put them and the walls where the file has them.
    """

    def __init__(
        self,
        walls: WallBoxes | Callable[[], WallBoxes] | None,
        radii: Radii = (),
        report: Mapping[str, Any] | None = None,
        objects: Any = None,
    ) -> None:
        self.walls = walls
        self._radii = radii
        report = report or {}
        held = held_by_line(report)
        self._held_walls = {line: h.walls for line, h in held.items() if h.walls}
        self._objects = objects
        self._bodies = list(report.get("bodies") or [])

    def _walls_now(self) -> WallBoxes | None:
        """The walls now."""
        if self.walls is None or isinstance(self.walls, WallBoxes):
            moves = self._objects.node_moves() if self._objects is not None else {}
            if self.walls is not None and moves:
                return moved_walls(self.walls, self._held_walls, moves)
            return self.walls
        return self.walls()

    def _bodies_now(self) -> list[tuple[Pose2, Mapping[str, Any]]]:
        """Each movable body's pose now and its import report entry."""
        drawn = getattr(self._objects, "drawn_bodies", None)
        if drawn is not None:
            return list(drawn())
        now = self._objects.body_poses() if self._objects is not None and self._bodies else []
        bodies = []
        for index, body in enumerate(self._bodies):
            cx, cy = (float(v) for v in body.get("center") or (0.0, 0.0))
            start = (cx, cy, float(body.get("yaw") or 0.0))
            bodies.append((now[index] if index < len(now) else start, body))
        return bodies

    def at(self, poses: Mapping[int, tuple[float, float, float]]) -> Sight:
        """The obstacles now, the robots at ``poses`` (x, y, yaw by robot index)."""
        boxes, discs = [], []
        for (x, y, yaw), body in self._bodies_now():
            if body.get("kind") == "circle":
                discs.append((x, y, float(body.get("radius") or 0.0)))
            else:
                sx, sy = (float(v) for v in body.get("size") or (0.0, 0.0))
                boxes.append((x, y, sx, sy, yaw, 0.0))
        given = self._radii() if callable(self._radii) else self._radii
        radii = [math.nan if r is None else float(r) for r in given]
        walls = self._walls_now()
        return Sight(poses, radii, walls, WallBoxes.of_boxes(boxes) if boxes else None, discs)


class Sight:
    """The obstacles of a world at one instant; :meth:`blocked` answers for a pair of robots,
    casting once from each sending robot to every other."""

    def __init__(
        self,
        poses: Mapping[int, tuple[float, float, float]],
        radii: Sequence[float],
        walls: WallBoxes | None,
        boxes: WallBoxes | None,
        discs: Sequence[tuple[float, float, float]],
    ) -> None:
        self._robots = sorted(poses)
        self._column = {robot: i for i, robot in enumerate(self._robots)}
        points = [(float(poses[r][0]), float(poses[r][1])) for r in self._robots]
        self._points = np.array(points, dtype=np.float64).reshape(-1, 2)
        own = [radii[r] if 0 <= r < len(radii) else math.nan for r in self._robots]
        centres = points + [(x, y) for x, y, _ in discs]
        self._centres = np.array(centres, dtype=np.float64).reshape(-1, 2)
        self._radii = np.array(own + [r for _, _, r in discs], dtype=np.float64)
        self._any_disc = bool(np.any(np.isfinite(self._radii)))
        self._walls = [w for w in (walls, boxes) if w is not None]
        self._blocked: dict[int, npt.NDArray[np.bool_]] = {}

    def blocked(self, sender: int, receiver: int) -> bool:
        """Whether an obstacle stands on the segment between the two robots' centres (the
        two robots' own bodies stop nothing)."""
        if sender not in self._blocked:
            self._blocked[sender] = self._cast_from(sender)
        return bool(self._blocked[sender][self._column[receiver]])

    def _cast_from(self, sender: int) -> npt.NDArray[np.bool_]:
        """For each robot, whether an obstacle stands between ``sender`` and it."""
        column = self._column[sender]
        origin = (float(self._points[column, 0]), float(self._points[column, 1]))
        towards = self._points - self._points[column]
        blocked = np.zeros(len(self._robots), dtype=bool)
        for walls in self._walls:
            along, _ = walls.cast_walls(origin, towards)
            blocked |= along < 1.0
        if self._any_disc:
            length = np.hypot(towards[:, 0], towards[:, 1])
            units = towards / np.where(length > 0.0, length, 1.0)[:, None]
            enter = disc_entries(origin, units, self._centres, self._radii)
            met = (enter >= 0.0) & (enter < length[:, None])
            count = len(self._robots)
            met[:, column] = False
            met[np.arange(count), np.arange(count)] = False
            blocked |= met.any(axis=1)
        return blocked
