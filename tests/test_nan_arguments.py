"""NaN is no number a public function takes, nor an infinity unless the parameter says so. Every
comparison with NaN is False, so a range check written ``if not low <= x <= high`` refuses it
but one written ``if x < low or x > high`` lets it through, and a sum carries it on; an infinity
passes every check written for a range. 48 entry points once stored or used a NaN given for a
``float`` parameter, and 34 an infinity (``Scene(camera_fov=nan)``, ``CameraView(x=inf)``,
``EpisodeTrace(x=nan)``, ``StudyResult(default_speed=nan)``, poses and starts given as lists
holding NaN).

Two mechanisms make the next such parameter right by construction:

- the surface check (``mazesim._checks``) refuses NaN before the call for every parameter
  annotated as a number (``float``, alone or in a union) or as a list or tuple of numbers (a
  numpy array in its place too), and an infinity unless the annotation is
  ``mazesim.errors.MaybeInfinite``; the walk of the public surface gives every such parameter
  NaN and an infinity, found by its annotation (``surface.registry.number_parameters``). Webots'
  API is the exception: it answers NaN as Webots does (``Motor.setVelocity(nan)`` prints Webots'
  error and is ignored);
- an array argument (annotated ``ArrayLike``, which may hold anything, infinite distances
  among them) is converted to floats only through ``mazesim._sizes.number_array``, which refuses
  NaN and infinities unless the place says what one means there (``nan_means="a gap in the
  path"``, ``inf_means="nothing in range"``); the scan
  below fails on a function that hands one of its parameters to numpy with a float dtype. 54
  conversions in 22 modules once did (a few refusing NaN later), and a NaN front reading drove
  ``AvoidCollision`` straight on, ``HierarchicalPolicy.reset`` stored NaN poses.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import pytest

import mazesim
from mazesim._checks import checked
from mazesim.errors import MaybeInfinite
from test_whole_numbers import conversions_in_package, conversions_of_parameters, dtype_of

INVALID = mazesim.InvalidArgumentError


@checked
def _scaled(
    gain: float,
    pose: tuple[float, float, float] = (0.0, 0.0, 0.0),
    path: Sequence[Sequence[float]] = (),
    count: int | float = 1,
    reach: MaybeInfinite = math.inf,
    bounds: tuple[MaybeInfinite, MaybeInfinite] = (-math.inf, math.inf),
) -> float:
    return min(gain * (sum(pose) + sum(sum(p) for p in path)) * count, reach)


@pytest.mark.parametrize(
    ("arguments", "words"),
    [
        ({"gain": math.nan}, "gain refused: expected a number, found NaN"),
        ({"gain": np.float32("nan")}, "gain refused: expected a number, found NaN"),
        ({"gain": np.float64("nan")}, "gain refused: expected a number, found NaN"),
        ({"gain": 1.0, "count": math.nan}, "count refused: expected a number, found NaN"),
        ({"gain": 1.0, "pose": (0.0, math.nan, 0.0)}, "pose refused: item 1: expected a number"),
        ({"gain": 1.0, "pose": np.array([0.0, np.nan, 0.0])}, "pose refused: expected finite"),
        # An infinity, unless the annotation is MaybeInfinite.
        ({"gain": math.inf}, "gain refused: expected a finite number, found inf"),
        ({"gain": 1.0, "pose": (0.0, -math.inf, 0.0)}, "pose refused: item 1: expected a finite"),
        ({"gain": 1.0, "pose": np.array([0.0, np.inf, 0.0])}, "pose refused: expected finite"),
        ({"gain": 1.0, "reach": math.nan}, "reach refused: expected a number, found NaN"),
        ({"gain": 1.0, "reach": 2.0, "bounds": (0.0, math.nan)}, "bounds refused: item 1:"),
        ({"gain": 1.0, "path": [[0.0, 1.0], [2.0, math.nan]]}, "path refused: item 1: item 1"),
        ({"gain": 1.0, "path": [np.array([0.0, np.nan])]}, "path refused: item 0: expected"),
        # A masked array's values are read whatever its mask.
        (
            {"gain": 1.0, "pose": np.ma.masked_array([0.0, np.nan, 0.0], mask=True)},
            "pose refused: expected finite numbers, found NaN or an infinity",
        ),
    ],
)  # fmt: skip
def test_nan_given_for_a_number_is_refused_before_the_call(
    arguments: dict[str, object], words: str
) -> None:
    with pytest.raises(INVALID, match=words):
        _scaled(**arguments)  # type: ignore[arg-type]


def test_numbers_and_infinities_are_taken_as_they_are() -> None:
    assert _scaled(2.0, (1.0, 2, 3.0), [[1.0], np.array([1.0, 1.0])]) == 18.0
    assert _scaled(np.float32(0.5), np.array([1.0, 1.0, 0.0]), count=2) == 2.0
    assert _scaled(1.0, reach=math.inf, bounds=(0.0, math.inf)) == 0.0  # MaybeInfinite
    assert _scaled(1.0, pose=np.array([1, 2, 3])) == 6  # an array of ints holds no NaN


class _WebotsLike:
    """A class that answers NaN itself, as Webots' API does."""

    _takes_nan = True

    def set_velocity(self, velocity: float) -> str:
        return "ignored" if math.isnan(velocity) else "set"


def test_a_class_that_answers_nan_itself_is_given_it() -> None:
    from mazesim._checks import _guard_class

    class Own(_WebotsLike):
        pass

    _guard_class(_WebotsLike)
    _guard_class(Own)
    assert Own().set_velocity(math.nan) == "ignored"

    class Strict:
        def set_velocity(self, velocity: float) -> str:
            return "set"

    _guard_class(Strict)
    with pytest.raises(INVALID, match="velocity refused: expected a number, found NaN"):
        Strict().set_velocity(math.nan)


def test_the_entry_points_that_once_took_nan_refuse_it() -> None:
    from mazesim.render.episode import EpisodeTrace
    from mazesim.webots.camera import CameraView
    from mazesim.webots.devices import Motor

    with pytest.raises(INVALID, match="fov refused: expected a number, found NaN"):
        CameraView(fov=math.nan)
    with pytest.raises(INVALID, match="x refused: expected a number, found NaN"):
        EpisodeTrace(x=math.nan)
    assert getattr(Motor, "_takes_nan", False)  # Webots' API: answers NaN as Webots does


def test_the_walk_gives_nan_to_every_number_parameter_it_finds() -> None:
    """The registry finds number parameters by annotation, and leaves Webots' API out."""
    from surface.registry import python_entry_points, refusals_of

    entries = {e.path: e for e in python_entry_points()}
    scene = entries["mazesim.webots.scene:Scene"]
    assert "camera_fov" in scene.numbers
    assert {"start", "goal"} <= set(entries["mazesim.render.topdown:TopDownRenderer"].number_lists)
    assert not entries["mazesim.webots.devices:Motor.setVelocity"].numbers
    refused = refusals_of(entries["mazesim.render.episode:EpisodeTrace"])
    assert {"x": ("nan", "inf")} in [r.absurd for r in refused]
    axis = entries["mazesim.transfer.axes:Axis"]  # bounds of no limit: MaybeInfinite
    assert {"low", "high"} <= set(axis.unbounded_numbers) and "low" not in axis.numbers
    walked = [e for e in entries.values() if e.numbers or e.number_lists]
    assert len(walked) >= 150, len(walked)


#: numpy's float types, as a dtype argument names them.
FLOAT_TYPES = {"float", "float16", "float32", "float64", "double", "single", "longdouble"}


_float_dtype = dtype_of(FLOAT_TYPES, ("float", "f"))


def test_the_scan_finds_the_conversions_that_take_nan_silently() -> None:
    source = """
def act(self, readings, poses, held):
    a = np.asarray(readings, dtype=np.float64)
    b = np.ascontiguousarray(np.ravel(poses), np.float32)
    c = held.astype(float)
    d = np.asarray(self.table, dtype=np.float64)  # the object's own: not a parameter
    e = number_array(readings, "readings")  # the one way
"""
    assert conversions_of_parameters(source, _float_dtype) == [
        "act(readings) line 3",
        "act(poses) line 4",
        "act(held) line 5",
    ]


def test_no_function_of_the_package_hands_a_parameter_to_numpy_as_floats() -> None:
    found = conversions_in_package(_float_dtype)
    assert not found, (
        "convert with mazesim._sizes.number_array, which refuses NaN unless nan_means says "
        f"what a NaN stands for there: {sorted(found)}"
    )


def test_an_array_holding_nan_is_refused_where_no_nan_is_meant() -> None:
    from mazesim.controllers import AvoidCollision
    from mazesim.learn.higher import HigherLevel
    from mazesim.learn.policy import HierarchicalPolicy, lower_table_shape

    readings = np.zeros(8)
    readings[3] = np.nan
    with pytest.raises(INVALID, match="expected distance_sensors as numbers, found NaN"):
        AvoidCollision()(readings)
    with pytest.raises(INVALID, match="expected poses as numbers, found NaN"):
        policy = HierarchicalPolicy(np.zeros(lower_table_shape()), HigherLevel([[1]]), [0])
        policy.reset([0], [[0.1, np.nan, 0.0]])
    # Where a NaN means something, it is taken: a gap in a plotted path.
    from mazesim.plotting import trajectory_limits

    world = mazesim.World.builtin("seed-maze")
    assert trajectory_limits(world, [0.0, np.nan, 1.0], [0.0, np.nan, 1.0]) is not None


def test_an_array_holding_an_infinity_is_refused_where_none_is_meant() -> None:
    """An infinite reading drove ``AvoidCollision`` as if nothing were near (-inf) or turned it
    away from nothing (+inf); a number too large for float32 became one on conversion."""
    from mazesim._sizes import number_array
    from mazesim.barcode.odometry import WheelEncoders
    from mazesim.controllers import AvoidCollision
    from mazesim.learn.higher import HigherLevel
    from mazesim.learn.policy import HierarchicalPolicy, lower_table_shape

    for reading in (-math.inf, math.inf):
        with pytest.raises(INVALID, match="expected distance_sensors as finite numbers"):
            AvoidCollision()([reading, *[0.0] * 7])
    with pytest.raises(INVALID, match=r"as finite numbers \(at most 3.4e\+38 in size\)"):
        number_array([1e300], "speeds", np.float32)
    with pytest.raises(INVALID, match="expected actions as finite numbers"):
        WheelEncoders(mazesim.RobotProfile.builtin("e-puck"), 1, 64.0).step([[1e300, 0.0]])
    policy = HierarchicalPolicy(np.zeros(lower_table_shape()), HigherLevel([[1]]), [0])
    with pytest.raises(INVALID, match="expected poses as finite numbers"):
        policy.reset([0], [[0.1, math.inf, 0.0]])
    # Where an infinity means something, it is taken: a distance of nothing in range.
    policy.reset([0], [[0.1, 0.1, 0.0]])
    far = np.full((1, 6), math.inf)
    assert policy.act_on_distances(far, [[0.1, 0.1, 0.0]], [0]).shape == (1,)
    assert number_array([math.inf], "tops", inf_means="a wall of no top")[0] == math.inf
    assert number_array([math.nan, math.inf], "x", checked_after=True).shape == (2,)


def test_a_wire_format_and_a_command_answer_nan_themselves() -> None:
    """ROS 2's encoders carry any double (REP 117: a LaserScan's ranges may be NaN or
    infinite); a twist refuses NaN as a bad command (``InvalidActionError``), its own class."""
    from mazesim.ros.standard import twist_wheel_speeds
    from mazesim.ros2 import cdr
    from surface.registry import _signature

    with pytest.raises(mazesim.InvalidActionError, match="on cmd_vel"):
        twist_wheel_speeds(math.nan, 0.0, mazesim.RobotProfile.builtin("e-puck"))
    scan = _signature(cdr.encode_laser_scan, False, cdr)  # (the walk leaves ROS modules out)
    assert scan is not None and not scan.numbers and not scan.number_lists
    ends = (0.0, 1.0, 0.1)
    assert cdr.encode_laser_scan((0, 0), "scan", ends, (0.0, 0.0), (0.0, math.inf), [math.nan])
