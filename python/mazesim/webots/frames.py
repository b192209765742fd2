"""Webots' old NUE frame (worlds before R2022a: x north, y up, z east) and mazesim's ENU frame,
the matrix of a Webots axis-angle rotation, and the frame of a node placed inside another's.

Webots' R2022a world converter maps a translation ``(x, y, z)`` of an NUE world to ``(-z, -x,
y)`` and a rotation's axis likewise; the importer (``mazesim-core``'s ``wbt::frames``) does the
same, so every position the controller module reads from an NUE world file must be converted
here by the same map, and every value a device of such a world reports in Webots' old frame
(a GPS) by its inverse.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

__all__ = [
    "ENU_TO_NUE",
    "SLOT_ORIGINS",
    "WORLD_FRAME",
    "Axes",
    "Frame",
    "axes_or_none",
    "axis_angle",
    "body_turn",
    "camera_heading",
    "heading_of",
    "enu_to_nue",
    "enu_to_nue_matrix",
    "nue_to_enu",
    "placed",
    "rotation_matrix",
    "turned",
]

#: The matrix of :func:`enu_to_nue` (rows).
ENU_TO_NUE = ((0.0, -1.0, 0.0), (0.0, 0.0, 1.0), (-1.0, 0.0, 0.0))

#: A device's axes (x, y, z) in the robot's frame, x forward, y left, z up.
Axes = tuple[tuple[float, float, float], ...]


def axes_or_none(value: object) -> Axes | None:
    """Three axes of three finite numbers (the import report's ``axes`` of a device), or
    None."""
    try:
        axes = tuple((float(a[0]), float(a[1]), float(a[2])) for a in value)  # type: ignore[attr-defined]
    except (TypeError, ValueError, IndexError, KeyError):
        return None
    if len(axes) != 3 or not all(math.isfinite(c) for axis in axes for c in axis):
        return None
    return axes


def nue_to_enu(x: float, y: float, z: float) -> tuple[float, float, float]:
    """A vector of an NUE world file in the world frame (ENU) of the imported world."""
    return -z, -x, y


def enu_to_nue(x: float, y: float, z: float) -> tuple[float, float, float]:
    """A world-frame (ENU) vector in the NUE frame of the world file it came from."""
    return -y, z, -x


def enu_to_nue_matrix(matrix: list[float]) -> list[float]:
    """A world-frame (ENU) rotation matrix, row after row, as the NUE world file's frame sees it:
    ``M R M^T``, M the matrix of :func:`enu_to_nue`."""
    m = ENU_TO_NUE
    return [
        sum(m[i][k] * matrix[3 * k + n] * m[j][n] for k in range(3) for n in range(3))
        for i in range(3)
        for j in range(3)
    ]


def rotation_matrix(ax: float, ay: float, az: float, angle: float) -> list[float]:
    """The 3 x 3 matrix of an axis-angle rotation (a Webots ``rotation`` field), row after row
    (Rodrigues' formula; a zero axis is taken as it is)."""
    norm = math.sqrt(ax * ax + ay * ay + az * az) or 1.0
    x, y, z = ax / norm, ay / norm, az / norm
    c, s = math.cos(angle), math.sin(angle)
    t = 1.0 - c
    return [
        *(t * x * x + c, t * x * y - s * z, t * x * z + s * y),
        *(t * x * y + s * z, t * y * y + c, t * y * z - s * x),
        *(t * x * z - s * y, t * y * z + s * x, t * z * z + c),
    ]


def camera_heading(forward: Sequence[float]) -> tuple[float, float]:
    """Where a camera whose view runs along ``forward`` (in the robot's frame, x forward, y
    left, z up) looks: its heading left of the robot's forward and its tilt down, radians."""
    fx, fy, fz = (float(v) for v in forward[:3])
    norm = math.sqrt(fx * fx + fy * fy + fz * fz) or 1.0
    heading = math.atan2(fy, fx) if math.hypot(fx, fy) > 1e-12 else 0.0
    return heading, math.asin(max(-1.0, min(1.0, -fz / norm)))


def body_turn(y_up: bool, nue: bool) -> list[float]:
    """The rotation matrix (row after row) taking a robot node's own frame, as the import
    reads the file (an NUE file's axes turned to ENU by :func:`nue_to_enu`), to the robot's
    frame at heading 0 (x forward, y left, z up): none for a Z-up body in an ENU file; for a
    body built Y-up (``y_up``: forward its local -z, up its local y) the turn that stands it
    upright; in an NUE file (``nue``) after the turn back to the file's own axes, so that a Z-up
    E-puck stood up in such a file by ``rotation 1 0 0 -1.5708`` reads that rotation. A robot
    at heading ``a`` is turned ``Rz(a) T`` (T this matrix), as Webots' ``rotation`` field and
    ``getOrientation`` give it."""
    columns = []
    for j in range(3):
        axis = tuple(1.0 if k == j else 0.0 for k in range(3))
        if nue:
            axis = enu_to_nue(*axis)
        if y_up:
            axis = nue_to_enu(*axis)
        columns.append(axis)
    return [columns[j][i] for i in range(3) for j in range(3)]


def heading_of(matrix: Sequence[float], turn: Sequence[float] | None = None) -> float:
    """The heading (rad, counter-clockwise from x) of a node turned by ``matrix`` (row after
    row): where its forward points, the x axis of the robot's frame that ``turn`` (a
    :func:`body_turn`; none by default) takes its own frame to."""
    # The forward axis in the node's own frame is T^T x: the first row of T.
    forward = turn[0:3] if turn is not None else (1.0, 0.0, 0.0)
    x = sum(matrix[k] * forward[k] for k in range(3))
    y = sum(matrix[3 + k] * forward[k] for k in range(3))
    return math.atan2(y, x)


def turned(yaw: float, turn: Sequence[float]) -> list[float]:
    """``Rz(yaw) T``, row after row: a robot at heading ``yaw`` whose :func:`body_turn` is
    ``turn``."""
    c, s = math.cos(yaw), math.sin(yaw)
    rows = ((c, -s, 0.0), (s, c, 0.0), (0.0, 0.0, 1.0))
    return [sum(rows[i][k] * turn[3 * k + j] for k in range(3)) for i in range(3) for j in range(3)]


def axis_angle(matrix: Sequence[float]) -> tuple[float, float, float, float]:
    """The axis-angle rotation (a Webots ``rotation`` field) of a rotation matrix, row after
    row: the inverse of :func:`rotation_matrix` (a half turn's axis read from the diagonal)."""
    m = matrix
    cos = max(-1.0, min(1.0, (m[0] + m[4] + m[8] - 1.0) / 2.0))
    x, y, z = m[7] - m[5], m[2] - m[6], m[3] - m[1]
    norm = math.sqrt(x * x + y * y + z * z)
    if norm > 1e-9:
        return x / norm, y / norm, z / norm, math.acos(cos)
    if cos > 0.0:
        return 0.0, 0.0, 1.0, 0.0
    # A half turn: R = 2 a a^T - I, so a_i^2 = (R_ii + 1) / 2 and a_i a_j = R_ij / 2.
    squares = [max(0.0, (m[4 * i] + 1.0) / 2.0) for i in range(3)]
    i = max(range(3), key=lambda k: squares[k])
    largest = math.sqrt(squares[i])
    axis = [largest if j == i else m[3 * i + j] / (2.0 * largest) for j in range(3)]
    return axis[0], axis[1], axis[2], math.pi


#: A frame: its origin and its rotation matrix (row after row), in the frame it is placed in.
Frame = tuple[list[float], list[float]]
#: Where the E-puck PROTO (R2022a on) mounts a slot, in the robot's frame (m): its
#: ``turretSlot`` 9.5 mm behind the centre on top of the turret, 48.6 mm up; its
#: ``groundSensorsSlot`` 3 cm forward, 0.3 mm up (the core's import places the devices of these
#: slots there too). Another slot, or another robot's, is at the robot's origin.
SLOT_ORIGINS: dict[tuple[str, str], tuple[float, float, float]] = {
    ("E-puck", "turretSlot"): (-0.0095, 0.0, 0.0486),
    ("E-puck", "groundSensorsSlot"): (0.03, 0.0, 0.0003),
}
#: The world's frame in itself.
WORLD_FRAME: Frame = ([0.0, 0.0, 0.0], rotation_matrix(0.0, 0.0, 1.0, 0.0))


def placed(
    frame: Frame, translation: Sequence[float], rotation: Sequence[float] | None = None
) -> Frame:
    """The frame of a node placed inside ``frame`` by its ``translation`` and its axis-angle
    ``rotation`` (none by default), as Webots composes a node's pose through its parents'."""
    origin, matrix = frame
    moved = [
        origin[i] + sum(matrix[3 * i + k] * translation[k] for k in range(3)) for i in range(3)
    ]
    if rotation is None:
        return moved, matrix
    turn = rotation_matrix(*rotation)
    return moved, [
        sum(matrix[3 * i + k] * turn[3 * k + j] for k in range(3))
        for i in range(3)
        for j in range(3)
    ]
