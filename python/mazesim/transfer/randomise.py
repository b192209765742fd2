"""Domain randomisation over the transfer study's axes: ranges, and a perturbed robot per env.

A :class:`RandomisationSpec` holds a range ``[low, high]`` for some of the axes that perturb the
robot profile (:data:`RANDOMISED_AXES`: all of :mod:`mazesim.transfer.axes` but ``robot``,
``latency`` and ``link``, which are not properties of a profile), and perhaps a list of base
robot profiles (the ``robot`` axis's names). It is written inline,
``"robot=seed|e-puck,wheel_radius=0.95:1.05,noise_scale=0.5:4"``, or as a small TOML file::

    [randomise]
    robot = ["seed", "e-puck"]    # each env's base profile, drawn uniformly from the list
    wheel_radius = [0.95, 1.05]
    noise_scale = [0.5, 4.0]
    ir_angle = [-10.0, 10.0]      # degrees, as the study's levels

Each range must lie within its axis's documented range. A name listed twice is drawn twice as
often; an axis given several ranges (``wall_reflectance=0.2:0.4|0.2:1``, or
``[[0.2, 0.4], [0.2, 1.0]]`` in the TOML) draws one of them, each as likely, then uniformly
within it: a distribution weighted to one end.

:func:`sample_settings` draws one setting per env: its base profile from the named stream
``randomise/robots``, each ranged axis from ``randomise/profiles``, both of a seed and a round;
:func:`sample_profiles` turns them into robot profiles
(``EpisodeBatch(..., robot=sample_profiles(spec, num_envs, seed, round))`` when every env is of
one base profile), and :func:`robot_draw` into a training run's robots, several base profiles
as a :class:`~mazesim.learn.fleet.Fleet` whose robots read in the seed robot's volts, as the
study drives them.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from mazesim._core import RobotProfile
from mazesim._paths import read_text
from mazesim._seeding import stream
from mazesim._toml import load_toml
from mazesim.batch import RobotChoice
from mazesim.errors import InvalidArgumentError, _known_name, _shown
from mazesim.learn.fleet import Fleet, ReadingsMap
from mazesim.transfer.axes import AXIS_NAMES, Setting, axis_named
from mazesim.transfer.cells import SEED_ROBOT, profile_of
from mazesim.transfer.readings import SeedReadings

__all__ = [
    "RANDOMISED_AXES",
    "ROBOT_AXIS",
    "RandomisationSpec",
    "parse_spec",
    "robot_draw",
    "sample_profiles",
    "sample_settings",
]

#: The axes a spec may randomise: those that perturb the robot profile.
RANDOMISED_AXES: tuple[str, ...] = tuple(
    name for name in AXIS_NAMES if name not in ("robot", "latency", "link")
)
#: The axis naming the base robot profiles a spec draws from.
ROBOT_AXIS = "robot"


def _robot_names(value: Any, where: str) -> tuple[str, ...]:
    """The base profiles of a spec's ``robot`` entry, each a name of the ``robot`` axis."""
    names = list(value) if isinstance(value, (list, tuple)) else [value]
    valid = axis_named(ROBOT_AXIS).names
    if not names or not all(isinstance(name, str) for name in names):
        raise InvalidArgumentError(
            f"{where}: robot: expected a list of robot profile names ({', '.join(valid)}), "
            f"found {_shown(value)}"
        )
    for name in names:
        _known_name(name, f"robot (in {where})", tuple(valid))
    return tuple(names)


def _checked_range(name: str, pair: Any, where: str) -> tuple[float, float]:
    """One ``[low, high]`` of axis ``name``, within its documented range."""
    axis = axis_named(name)
    numbers = list(pair) if isinstance(pair, (list, tuple)) else [pair]
    if len(numbers) != 2 or not all(
        isinstance(n, (int, float)) and not isinstance(n, bool) for n in numbers
    ):
        raise InvalidArgumentError(
            f"{where}: {name}: expected a range of two numbers [low, high], found {_shown(pair)}"
        )
    try:
        low, high = (float(axis.check(float(n))) for n in numbers)
    except OverflowError:  # a whole number too large for a float
        raise InvalidArgumentError(
            f"{where}: {name}: expected a range of two finite numbers, found {_shown(pair)}"[:300]
        ) from None
    if low > high:
        raise InvalidArgumentError(
            f"{where}: {name}: expected low <= high, found {low:g} > {high:g}"
        )
    return low, high


@dataclass(frozen=True)
class RandomisationSpec:
    """Ranges of the randomised axes.

    Attributes:
        ranges: Each randomised axis and its ``(low, high)``, in the study's axis order. An axis
            listed with several ranges (one after the other) draws one of them, each as likely,
            then uniformly within it: ``wall_reflectance`` as ``(0.2, 0.4)`` and ``(0.2, 1.0)``
            draws five eighths of its values below 0.4.
        robots: The base robot profiles each env draws one of, uniformly (a name listed twice
            is drawn twice as often); empty for the seed robot alone.
    """

    ranges: tuple[tuple[str, tuple[float, float]], ...]
    robots: tuple[str, ...] = ()

    @staticmethod
    def of(ranges: Mapping[str, Any], where: str = "randomisation") -> RandomisationSpec:
        """A spec from axis names and ``(low, high)`` pairs (or lists of them), each checked.

        Raises:
            InvalidArgumentError: An axis that is not randomised, a range that is not two
                numbers with ``low <= high``, or one outside the axis's documented range.
            UnknownNameError: An axis that does not exist, or a robot profile that does not.
        """
        checked: dict[str, list[tuple[float, float]]] = {}
        robots: tuple[str, ...] = ()
        for name, pair in ranges.items():
            axis_named(name)
            if name == ROBOT_AXIS:
                robots = _robot_names(pair, where)
                continue
            _known_name(name, f"{where}: a property of the robot profile", RANDOMISED_AXES)
            several = isinstance(pair, (list, tuple)) and all(
                isinstance(part, (list, tuple)) for part in pair
            )
            parts = list(pair) if several and pair else [pair]
            checked[name] = [_checked_range(name, part, where) for part in parts]
        if not checked and not robots:
            raise InvalidArgumentError(f"{where}: expected at least one axis range, found none")
        ordered = tuple((n, span) for n in AXIS_NAMES if n in checked for span in checked[n])
        return RandomisationSpec(ordered, robots)

    def axes(self) -> list[tuple[str, list[tuple[float, float]]]]:
        """Each randomised axis once, with its ranges, in the study's axis order."""
        grouped: dict[str, list[tuple[float, float]]] = {}
        for name, span in self.ranges:
            grouped.setdefault(name, []).append(span)
        return list(grouped.items())

    def text(self) -> str:
        """The spec inline, ``robot=a|b,axis=low:high|low:high,...`` in the study's axis order
        (:func:`parse_spec` reads it back as the same spec)."""
        parts = [f"{ROBOT_AXIS}={'|'.join(self.robots)}"] if self.robots else []
        parts += [
            f"{name}=" + "|".join(repr(low) + ":" + repr(high) for low, high in spans)
            for name, spans in self.axes()
        ]
        return ",".join(parts)


def _inline(text: str) -> dict[str, Any]:
    ranges: dict[str, Any] = {}
    for part in (p.strip() for p in text.split(",")):
        if not part:
            continue
        name, equals, bounds = (piece.strip() for piece in part.partition("="))
        if name in ranges:
            raise InvalidArgumentError(
                f"randomisation: expected each axis once, found {_shown(name)} twice in "
                f"{_shown(text)}"
            )
        if name == ROBOT_AXIS and equals:
            ranges[name] = [robot.strip() for robot in bounds.split("|")]
            continue
        spans = []
        for span in bounds.split("|"):
            low, colon, high = span.partition(":")
            try:
                values = [float(low), float(high)]
            except ValueError:
                values = []
            if equals and colon and values and not all(math.isfinite(v) for v in values):
                raise InvalidArgumentError(
                    f"randomisation: expected the range of {name} as finite numbers "
                    f"low:high, found {_shown(span)} in {_shown(text)}"
                )
            if not equals or not colon or not values:
                raise InvalidArgumentError(
                    "randomisation: expected a TOML file or axis=low:high, found "
                    f"{_shown(part)} in "
                    f"{_shown(text)}"
                )
            spans.append(values)
        ranges[name] = spans[0] if len(spans) == 1 else spans
    return ranges


def _toml_table(path: Path) -> Mapping[str, Any]:
    text = read_text(path, "the randomisation file (a TOML [randomise] table)")
    document = load_toml(text, str(path))
    table = document.get("randomise")
    if not isinstance(table, dict) or set(document) != {"randomise"}:
        raise InvalidArgumentError(
            f"{path}: expected one table [randomise] of axis = [low, high] (and perhaps robot = "
            f"[names]), found the keys "
            f"{sorted(document)}"
        )
    return table


def parse_spec(spec: str | os.PathLike[str]) -> RandomisationSpec:
    """A spec from a TOML file's path or an inline ``axis=low:high,...`` text.

    Raises:
        InvalidArgumentError: A malformed spec (the message names the part and what it expects).
        MazesimIOError: The file cannot be read.
    """
    text = os.fspath(spec)
    if text.endswith(".toml") or os.path.isfile(text):
        path = Path(text)
        return RandomisationSpec.of(_toml_table(path), where=str(path))
    return RandomisationSpec.of(_inline(text))


def sample_settings(
    spec: RandomisationSpec, count: int, seed: int, round_index: int = 0
) -> list[Setting]:
    """``count`` settings, each axis uniform in its range and (with ``spec.robots``) a base
    profile drawn from the list, from the streams of ``seed`` and ``round_index`` (the same
    arguments give the same settings; env ``i``'s does not depend on ``count``)."""
    if count < 1:
        raise InvalidArgumentError(f"expected at least one env, found {count}")
    # One row of draws per env, a column per axis, filled in order: env i's row does not depend
    # on ``count``. An axis of k ranges takes range floor(k u) and the rest of k u within it.
    axes = spec.axes()
    unit = stream(seed, "randomise/profiles", round_index).random((count, len(axes)))
    robots = [SEED_ROBOT] * count
    if spec.robots:
        picks = stream(seed, "randomise/robots", round_index).random(count) * len(spec.robots)
        robots = [spec.robots[min(int(pick), len(spec.robots) - 1)] for pick in picks]

    def level(spans: list[tuple[float, float]], u: float) -> float:
        place = min(int(u * len(spans)), len(spans) - 1)
        low, high = spans[place]
        return low + (high - low) * (u * len(spans) - place)

    return [
        Setting.of(
            {
                **({} if robots[env] == SEED_ROBOT else {ROBOT_AXIS: robots[env]}),
                **{
                    name: level(spans, float(unit[env, column]))
                    for column, (name, spans) in enumerate(axes)
                },
            }
        )
        for env in range(count)
    ]


def sample_profiles(
    spec: RandomisationSpec, count: int, seed: int, round_index: int = 0
) -> list[RobotProfile]:
    """Each env's base profile perturbed as :func:`sample_settings` draws, one profile per
    env."""
    return [profile_of(setting) for setting in sample_settings(spec, count, seed, round_index)]


def _on_seed_robot(setting: Setting) -> Setting:
    return Setting.of({name: level for name, level in setting.values if name != ROBOT_AXIS})


def robot_draw(spec: RandomisationSpec, seed: int) -> Callable[[int, int], RobotChoice | Fleet]:
    """The robots of a randomised training run (a :data:`mazesim.learn.train.RobotDraw`).

    Without other base profiles than the seed robot, ``draw(round_index, count)`` is
    :func:`sample_profiles` of that round, but for robot 0, the unperturbed seed robot: a
    batch's first robot sets what every robot's controller believes of its wheels, and a real
    robot's controller knows only the nominal numbers. With others, it is a
    :class:`~mazesim.learn.fleet.Fleet` of those profiles, one group per base profile (in the
    order of ``spec.robots``), whose first robot is that profile unperturbed; the robots of
    another profile than the seed robot read through
    :class:`~mazesim.transfer.readings.SeedReadings` of their base profile, as the transfer
    study drives them. The higher level trains on the same draws with every robot on the seed
    robot (its episodes drive the navigator on raw readings).
    """
    bases = list(dict.fromkeys(spec.robots))
    readings: dict[str, ReadingsMap | None] = {}

    def readings_of(name: str) -> ReadingsMap | None:
        if name not in readings:
            mapped = None if name == SEED_ROBOT else SeedReadings(RobotProfile.builtin(name))
            readings[name] = mapped
        return readings[name]

    def draw(round_index: int, count: int) -> RobotChoice | Fleet:
        settings = sample_settings(spec, count, seed, round_index)
        if not set(bases) - {SEED_ROBOT}:
            profiles = [profile_of(setting) for setting in settings]
            profiles[0] = profile_of(Setting())
            return profiles
        group = np.array([bases.index(str(s.get(ROBOT_AXIS))) for s in settings], dtype=np.int64)
        profiles = [profile_of(setting) for setting in settings]
        for index, name in enumerate(bases):
            members = np.flatnonzero(group == index)
            if members.size:
                profiles[int(members[0])] = RobotProfile.builtin(name)
        higher = [profile_of(_on_seed_robot(setting)) for setting in settings]
        higher[0] = profile_of(Setting())
        return Fleet(profiles, group, [readings_of(name) for name in bases], higher)

    return draw
