"""Domain randomisation over the transfer study's axes: ranges, and a perturbed robot per env.

A :class:`RandomisationSpec` holds a range ``[low, high]`` for some of the axes that perturb the
robot profile (:data:`RANDOMISED_AXES`: all of :mod:`mazesim.transfer.axes` but ``robot``,
``latency`` and ``link``, which are not properties of a profile). It is written inline,
``"wheel_radius=0.95:1.05,noise_scale=0.5:4"``, or as a small TOML file::

    [randomise]
    wheel_radius = [0.95, 1.05]
    noise_scale = [0.5, 4.0]
    ir_angle = [-10.0, 10.0]      # degrees, as the study's levels

Each range must lie within its axis's documented range. :func:`sample_settings` draws one
setting per env (each axis uniformly in its range) from the named stream ``randomise/profiles``
of a seed and a round, and :func:`sample_profiles` turns them into robot profiles for a batch
(``EpisodeBatch(..., robot=sample_profiles(spec, num_envs, seed, round))``).
"""

from __future__ import annotations

import math
import os
import sys
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from mazesim._core import RobotProfile
from mazesim._paths import read_text
from mazesim._seeding import stream
from mazesim.errors import InvalidArgumentError, MissingDependencyError
from mazesim.transfer.axes import AXIS_NAMES, Setting, axis_named
from mazesim.transfer.cells import profile_of

__all__ = [
    "RANDOMISED_AXES",
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


@dataclass(frozen=True)
class RandomisationSpec:
    """Ranges of the randomised axes.

    Attributes:
        ranges: Each randomised axis and its ``(low, high)``, in the study's axis order.
    """

    ranges: tuple[tuple[str, tuple[float, float]], ...]

    @staticmethod
    def of(ranges: Mapping[str, Any], where: str = "randomisation") -> RandomisationSpec:
        """A spec from axis names and ``(low, high)`` pairs, each checked.

        Raises:
            InvalidArgumentError: An axis that is not randomised, a range that is not two
                numbers with ``low <= high``, or one outside the axis's documented range.
            UnknownNameError: An axis that does not exist.
        """
        checked: dict[str, tuple[float, float]] = {}
        for name, pair in ranges.items():
            axis = axis_named(name)
            if name not in RANDOMISED_AXES:
                raise InvalidArgumentError(
                    f"{where}: axis {name!r} is not a property of the robot profile; expected "
                    f"one of {', '.join(RANDOMISED_AXES)}"
                )
            numbers = list(pair) if isinstance(pair, (list, tuple)) else [pair]
            if len(numbers) != 2 or not all(
                isinstance(n, (int, float)) and not isinstance(n, bool) for n in numbers
            ):
                raise InvalidArgumentError(
                    f"{where}: {name}: expected a range of two numbers [low, high], found {pair!r}"
                )
            low, high = (float(axis.check(float(n))) for n in numbers)
            if low > high:
                raise InvalidArgumentError(
                    f"{where}: {name}: expected low <= high, found {low:g} > {high:g}"
                )
            checked[name] = (low, high)
        if not checked:
            raise InvalidArgumentError(f"{where}: expected at least one axis range, found none")
        return RandomisationSpec(tuple((n, checked[n]) for n in AXIS_NAMES if n in checked))

    def text(self) -> str:
        """The spec inline, ``axis=low:high,...`` in the study's axis order (:func:`parse_spec`
        reads it back as the same spec)."""
        return ",".join(f"{name}={low!r}:{high!r}" for name, (low, high) in self.ranges)


def _inline(text: str) -> dict[str, list[float]]:
    ranges: dict[str, list[float]] = {}
    for part in (p.strip() for p in text.split(",")):
        if not part:
            continue
        name, equals, bounds = part.partition("=")
        low, colon, high = bounds.partition(":")
        try:
            values = [float(low), float(high)]
        except ValueError:
            values = []
        if not equals or not colon or not all(math.isfinite(v) for v in values) or not values:
            raise InvalidArgumentError(
                f"randomisation: expected a TOML file or axis=low:high, found {part!r} in {text!r}"
            )
        if name.strip() in ranges:
            raise InvalidArgumentError(
                f"randomisation: expected each axis once, found {name.strip()!r} twice in {text!r}"
            )
        ranges[name.strip()] = values
    return ranges


def _toml_table(path: Path) -> Mapping[str, Any]:
    if sys.version_info >= (3, 11):
        import tomllib as toml
    else:  # pragma: no cover - Python 3.9 and 3.10
        try:
            import tomli as toml
        except ImportError:
            raise MissingDependencyError(
                "a randomisation file on Python < 3.11 needs 'tomli' (pip install tomli)"
            ) from None
    text = read_text(path, "the randomisation file (a TOML [randomise] table)")
    try:
        document = toml.loads(text)
    except toml.TOMLDecodeError as error:
        raise InvalidArgumentError(f"{path}: not a valid TOML file: {error}") from None
    table = document.get("randomise")
    if not isinstance(table, dict) or set(document) != {"randomise"}:
        raise InvalidArgumentError(
            f"{path}: expected one table [randomise] of axis = [low, high], found the keys "
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
    """``count`` settings, each axis uniform in its range, from the stream of ``seed`` and
    ``round_index`` (the same arguments give the same settings; env ``i``'s does not depend on
    ``count``)."""
    if count < 1:
        raise InvalidArgumentError(f"expected at least one env, found {count}")
    # One row of draws per env, filled in order: env i's row does not depend on ``count``.
    unit = stream(seed, "randomise/profiles", round_index).random((count, len(spec.ranges)))
    return [
        Setting.of(
            {
                name: low + (high - low) * float(unit[env, column])
                for column, (name, (low, high)) in enumerate(spec.ranges)
            }
        )
        for env in range(count)
    ]


def sample_profiles(
    spec: RandomisationSpec, count: int, seed: int, round_index: int = 0
) -> list[RobotProfile]:
    """The seed robot perturbed as :func:`sample_settings` draws, one profile per env."""
    return [profile_of(setting) for setting in sample_settings(spec, count, seed, round_index)]


def robot_draw(spec: RandomisationSpec, seed: int) -> Callable[[int, int], list[RobotProfile]]:
    """The robots of a randomised training run (a :data:`mazesim.learn.train.RobotDraw`):
    ``draw(round_index, count)`` is :func:`sample_profiles` of that round, but for robot 0, the
    unperturbed seed robot. A batch's first robot sets what every robot's controller believes of
    its wheels, and a real robot's controller knows only the nominal numbers."""

    def draw(round_index: int, count: int) -> list[RobotProfile]:
        profiles = sample_profiles(spec, count, seed, round_index)
        profiles[0] = profile_of(Setting())
        return profiles

    return draw
