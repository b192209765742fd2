"""The perturbation axes of the transfer study, their documented ranges and default levels.

A transfer study asks how a navigator trained on the ``seed`` robot in simulation fares when the
robot it drives is not quite that robot. Each :class:`Axis` is one way the real robot may differ;
its :attr:`Axis.levels` are the settings a default study runs (the unperturbed value is the
study's baseline and not repeated), spanning the axis's documented range. A :class:`Setting`
is one point of the grid: a value on any number of axes, the others at rest.

=================  ===============================================  ============================
axis               what changes                                     default levels
=================  ===============================================  ============================
robot              another robot profile drives (readings mapped    e-puck-hardware, e-puck,
                   into the seed robot's volts, see ``readings``)   e-puck2, alphabot2
wheel_radius       both wheels' radius, as a scale (+-5 %)          0.95, 0.975, 1.025, 1.05
axle_length        the wheel distance, as a scale (+-5 %)           0.95, 0.975, 1.025, 1.05
motor_mismatch     one motor weaker: -m = left at 1 - m, +m =       -0.1, -0.05, 0.05, 0.1
                   right at 1 - m
noise_scale        the IR sensors' noise sigma, times (x0.5-x4)     0.5, 2, 4
ir_angle           every IR sensor turned outward, degrees          5, 10, 15
ir_offset          every IR sensor moved outward along its          -10, -5, 5, 10
                   heading, mm
wall_reflectance   the walls' reflection factor, times (white 1     0.8, 0.6, 0.4, 0.2
                   to dark 0.2)
ground_drift       the ground readings, times (the decoder's        0.8, 0.9, 1.1, 1.2
                   threshold drifting the other way)
latency            control steps between reading and acting         1, 2, 3
link               the unsynchronised ROS link of the barcode       ros
                   study (:mod:`mazesim.barcode.link`)
slip               share of the motion lost while touching a wall   0.1, 0.25, 0.5
=================  ===============================================  ============================

The first ten axes but ``robot``, ``latency`` and ``link`` are robot-profile perturbations
(:meth:`mazesim.RobotProfile.perturbed`); ``latency`` and ``link`` change how the controller
meets the simulator (:mod:`mazesim.transfer.control_timing`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Union

from mazesim.barcode.link import LINKS
from mazesim.errors import (
    InvalidArgumentError,
    MaybeInfinite,
    RegisteredName,
    _known_name,
    _shown,
)

__all__ = [
    "AXES",
    "AXIS_NAMES",
    "LEVEL_ROBOTS",
    "Axis",
    "Level",
    "Setting",
    "axis_named",
    "parse_axes",
]

#: A level on an axis: a number, or a name (a robot profile, a link).
Level = Union[float, str]

#: The robot profiles the ``robot`` axis runs besides the ``seed`` robot.
LEVEL_ROBOTS = ("e-puck-hardware", "e-puck", "e-puck2", "alphabot2")


@dataclass(frozen=True)
class Axis:
    """One way the robot may differ from the one the navigator learned on.

    Attributes:
        name: The axis's name (in ``--axes`` and the JSON).
        description: What changes, in a line.
        unit: The unit of its levels ("" for scales and names).
        rest: The level of the unperturbed robot.
        levels: The levels a default study runs.
        low: The documented range's lower end (numeric axes).
        high: The documented range's upper end (numeric axes).
        names: The levels a named axis accepts.
    """

    name: str
    description: str
    unit: str
    rest: Level
    levels: tuple[Level, ...]
    low: MaybeInfinite = -math.inf
    high: MaybeInfinite = math.inf
    names: tuple[str, ...] = ()

    def check(self, level: Level) -> Level:
        """Returns ``level`` if the axis accepts it.

        Raises:
            InvalidArgumentError: A level of the wrong kind or outside the documented range.
        """
        if self.names:
            return _named_level(self, level)
        if isinstance(level, str) or not math.isfinite(level):
            raise InvalidArgumentError(
                f"axis {_shown(self.name)}: expected a number, found {_shown(level)}"
            )
        if not self.low <= level <= self.high:
            raise InvalidArgumentError(
                f"axis {_shown(self.name)}: expected a level in [{self.low:g}, {self.high:g}] "
                f"{self.unit}".rstrip()
                + f", found {level:g}"
            )
        return float(level)

    def label(self, level: Level) -> str:
        """A short text for a level, with its unit."""
        if isinstance(level, str):
            return level
        if self.name == "motor_mismatch":
            return f"{'left' if level < 0 else 'right'} -{abs(level):.0%}"
        text = f"{level:g}"
        if self.unit in ("", "x"):
            return f"x{text}" if self.unit == "x" else text
        return f"{text} {self.unit}"


#: Every axis of the study, in the order of the tables and pictures.


def _named_level(axis: Axis, level: RegisteredName | float) -> str:
    """``level`` when it is one of the levels ``axis`` names; else the refusal of a name."""
    return _known_name(level, f"a level of axis {_shown(axis.name)}", axis.names)


AXES: tuple[Axis, ...] = (
    Axis(
        "robot",
        "another robot profile drives, its readings mapped into the seed robot's volts",
        "",
        "seed",
        LEVEL_ROBOTS,
        names=("seed", *LEVEL_ROBOTS),
    ),
    Axis("wheel_radius", "both wheels' radius, scaled", "x", 1.0, (0.95, 0.975, 1.025, 1.05),
         0.5, 1.5),
    Axis("axle_length", "the distance between the wheels, scaled", "x", 1.0,
         (0.95, 0.975, 1.025, 1.05), 0.5, 1.5),
    Axis("motor_mismatch", "one motor weaker than the other (-: left, +: right)", "", 0.0,
         (-0.1, -0.05, 0.05, 0.1), -0.5, 0.5),
    Axis("noise_scale", "the IR sensors' noise, scaled", "x", 1.0, (0.5, 2.0, 4.0), 0.0, 20.0),
    Axis("ir_angle", "every IR sensor turned outward", "deg", 0.0, (5.0, 10.0, 15.0), -45.0,
         45.0),
    Axis("ir_offset", "every IR sensor moved outward along its heading", "mm", 0.0,
         (-10.0, -5.0, 5.0, 10.0), -20.0, 20.0),
    Axis("wall_reflectance", "the walls' reflection factor, scaled (1 white, 0.2 dark)", "x",
         1.0, (0.8, 0.6, 0.4, 0.2), 0.05, 1.0),
    Axis("ground_drift", "the ground readings, scaled (threshold drift seen from the decoder)",
         "x", 1.0, (0.8, 0.9, 1.1, 1.2), 0.25, 4.0),
    Axis("latency", "control steps between reading the sensors and acting", "steps", 0.0,
         (1.0, 2.0, 3.0), 0.0, 10.0),
    Axis("link", "how the controller meets the simulator (ros: unsynchronised node)", "",
         "lockstep", ("ros",), names=LINKS),
    Axis("slip", "share of the motion lost while touching a wall", "", 0.0, (0.1, 0.25, 0.5),
         0.0, 0.95),
)  # fmt: skip

#: The axes' names, in order.
AXIS_NAMES: tuple[str, ...] = tuple(axis.name for axis in AXES)


def axis_named(name: RegisteredName) -> Axis:
    """The axis called ``name``.

    Raises:
        UnknownNameError: No such axis.
    """
    return AXES[AXIS_NAMES.index(_known_name(name, "transfer axis", AXIS_NAMES))]


def parse_axes(text: str | Iterable[str]) -> tuple[Axis, ...]:
    """Axes from comma-separated names (or a list of names), in the study's order.

    Raises:
        UnknownNameError: A name that is no axis.
        InvalidArgumentError: No name at all.
    """
    names = text.split(",") if isinstance(text, str) else list(text)
    chosen = {axis_named(name.strip()).name for name in names if name.strip()}
    if not chosen:
        raise InvalidArgumentError(f"expected axes among {', '.join(AXIS_NAMES)}, found none")
    return tuple(axis for axis in AXES if axis.name in chosen)


@dataclass(frozen=True)
class Setting:
    """A point of the grid: a level on some axes, the others at rest.

    Attributes:
        values: The perturbed axes and their levels, in the study's axis order.
    """

    values: tuple[tuple[str, Level], ...] = ()
    _lookup: Mapping[str, Level] = field(default_factory=dict, compare=False, repr=False)

    @staticmethod
    def of(values: Mapping[str, Level] | Sequence[tuple[str, Level]]) -> Setting:
        """A setting from axis names and levels (each checked against its axis).

        Raises:
            UnknownNameError: An unknown axis.
            InvalidArgumentError: A level its axis does not accept.
        """
        pairs = dict(values.items() if isinstance(values, Mapping) else values)
        checked = {name: axis_named(name).check(level) for name, level in pairs.items()}
        ordered = tuple((name, checked[name]) for name in AXIS_NAMES if name in checked)
        return Setting(ordered, dict(ordered))

    def get(self, name: str) -> Level:
        """The level on axis ``name`` (its rest when not perturbed)."""
        return self._lookup.get(name, axis_named(name).rest)

    @property
    def axes(self) -> tuple[str, ...]:
        """The perturbed axes."""
        return tuple(name for name, _ in self.values)

    def label(self) -> str:
        """A short text for the setting (``baseline`` for none)."""
        if not self.values:
            return "baseline"
        return ", ".join(f"{name} {axis_named(name).label(level)}" for name, level in self.values)

    def as_json(self) -> dict[str, Any]:
        """The setting as the JSON's ``{"axis": level}`` object."""
        return dict(self.values)
