"""Observation and action spaces of the maze environments, and the checks of every action.

Observation
    A float32 vector of the robot's sensor readings, in the order of its profile: the distance
    sensors, then the ground sensors, then (with ``include_pose=True``) the pose x, y in metres and
    yaw in radians. For the e-puck (11 values):

    =====  ========  ===================================================================
    index  sensor    reading
    =====  ========  ===================================================================
    0-7    ps0-ps7   infra-red proximity, raw counts: about 67 with nothing within 7 cm,
                     rising to 4095 at contact (ps0 front-right ... ps7 front-left)
    8-10   gs0-gs2   ground sensors (left, centre, right), raw: 300 on black, about 856
                     on white, 1000 at most
    =====  ========  ===================================================================

    The ``seed`` robot gives 7 values: Sharp distances in volts (front, back, left, right,
    left-front, right-front; 0.31 V far ... 3.03 V at 3 cm and closer), then its centre ground
    sensor. ``alphabot2`` gives 11: the same six Sharp sensors, then line sensors line0-line4
    (10-bit, 1023 at most). The bounds of the space are 0 and 1.25 times the largest value of each
    sensor's lookup table, so they hold every noisy reading (relative noise never exceeds 9 % at
    the top of a table); observations are also clipped to the space, so they always lie inside it.

    This is the ``observation="sensors"`` vector. The goal-conditioned ones of the task suite
    (``"goal"``, ``"explore"``, ``"guided"`` and ``"plan"``: normalised readings, the goal, the
    explored map, a waypoint, the previous action) are listed index by index in
    :mod:`mazesim.envs.navigation`.

Action
    ``"continuous"``: ``Box(-1, 1, (2,), float32)``, the left and right wheel speeds as fractions
    of the motor limit (6.28 rad/s on the e-puck). ``"discrete"``: ``Discrete(12)``, the report's
    primitive actions of :mod:`mazesim.actions` (index ``i`` is ``ACTION_CODES[i]``).

A bad action (wrong shape or dtype, NaN or infinite) raises
:class:`~mazesim.errors.InvalidActionError` saying what was expected and what was found. A finite
continuous action outside [-1, 1] is clipped to it by default (``clip_actions=True``, as
``np.clip`` would, after the conversion to float32), or raises with ``clip_actions=False``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
from gymnasium import spaces

from mazesim._core import RobotProfile, World
from mazesim.actions import ACTION_CODES, WHEEL_SPEED_FRACTIONS
from mazesim.errors import InvalidActionError, RegisteredName, _a_type, _shown

__all__ = [
    "NOISE_MARGIN",
    "ActionConverter",
    "ObservationLayout",
    "SensorRanges",
    "action_array",
    "real_actions",
]


@dataclass(frozen=True)
class SensorRanges:
    """The extremes of a robot profile's sensor tables.

    Attributes:
        distance_max: Largest distance-sensor reading (the table's first row: contact).
        ray_length: Range of the distance sensors in metres (the table's last row).
        ground_max: Largest ground-sensor reading (at contact with a white floor).
    """

    distance_max: float
    ray_length: float
    ground_max: float


#: Upper bound of the observation space as a multiple of each table's largest value.
NOISE_MARGIN = 1.25

#: Margin in metres round the world's bounds for the pose in the observation.
_POSE_MARGIN = 0.5
#: The dtype of the actions the continuous space samples (numpy's one instance of it).
_FLOAT32 = np.dtype(np.float32)
_YAW_BOUND = float(np.float32(math.pi)) * 1.0001


def sensor_ranges(robot: RobotProfile) -> SensorRanges:
    """The extremes of a robot profile's sensor tables (read from the profile itself)."""
    return SensorRanges(
        distance_max=robot.distance_sensor_max,
        ray_length=robot.distance_sensor_range,
        ground_max=robot.ground_sensor_max,
    )


class ObservationLayout:
    """The names, bounds and space of an environment's observation vector.

    Args:
        robot: The robot profile.
        world: A world of the kind the episodes run in (for the bounds of the pose).
        include_pose: Whether the vector ends with x, y and yaw.
    """

    def __init__(self, robot: RobotProfile, world: World, include_pose: bool) -> None:
        ranges = sensor_ranges(robot)
        distance, ground = robot.distance_sensor_names, robot.ground_sensor_names
        self.names: list[str] = [*distance, *ground]
        low = [0.0] * (len(distance) + len(ground))
        high = [ranges.distance_max * NOISE_MARGIN] * len(distance)
        high += [ranges.ground_max * NOISE_MARGIN] * len(ground)
        self.sensor_width = len(low)
        if include_pose:
            xmin, ymin, xmax, ymax = world.bounds
            self.names += ["x", "y", "yaw"]
            low += [xmin - _POSE_MARGIN, ymin - _POSE_MARGIN, -_YAW_BOUND]
            high += [xmax + _POSE_MARGIN, ymax + _POSE_MARGIN, _YAW_BOUND]
        self.include_pose = include_pose
        self.low = np.array(low, dtype=np.float32)
        self.high = np.array(high, dtype=np.float32)
        self.space = spaces.Box(self.low, self.high, dtype=np.float32)

    @property
    def width(self) -> int:
        """Number of values in one observation."""
        return len(self.names)

    @property
    def position_bounds(self) -> tuple[float, float, float, float] | None:
        """The x, y bounds in metres (min x, min y, max x, max y) of the poses the space holds,
        or None without ``include_pose``."""
        if not self.include_pose:
            return None
        x, y = self.names.index("x"), self.names.index("y")
        low, high = self.low, self.high
        return (float(low[x]), float(low[y]), float(high[x]), float(high[y]))

    def assemble(
        self, sensors: npt.NDArray[np.float32], poses: npt.NDArray[np.float32]
    ) -> npt.NDArray[np.float32]:
        """A new (N, width) array of observations from (N, sensor_width) readings and (N, 3) poses,
        clipped to the space."""
        if self.include_pose:
            out = np.concatenate((sensors, poses), axis=1)
            np.maximum(out, self.low, out=out)
        else:
            out = np.maximum(sensors, self.low)
        np.minimum(out, self.high, out=out)
        return out

    def assemble_one(
        self, readings: npt.NDArray[np.float32], pose: npt.NDArray[np.float32]
    ) -> npt.NDArray[np.float32]:
        """One new (width,) observation from (sensor_width,) readings and a pose: a row of
        :meth:`assemble`, bit for bit."""
        if self.include_pose:
            out = np.empty(self.width, dtype=np.float32)
            out[: self.sensor_width] = readings
            out[self.sensor_width :] = pose
            np.maximum(out, self.low, out=out)
        else:
            out = np.maximum(readings, self.low)
        np.minimum(out, self.high, out=out)
        return out


class ActionConverter:
    """Checks actions and turns them into float32 wheel speeds in rad/s.

    Both give the wheel speeds of the float32 product ``fraction * max_speed``, so a single env and
    the vector env drive the same speeds bit for bit.

    Args:
        action_mode: ``"continuous"`` or ``"discrete"``.
        max_speed: The motor limit in rad/s.
        clip: Whether continuous actions outside [-1, 1] are clipped to it (else they raise).
    """

    def __init__(self, action_mode: RegisteredName, max_speed: float, clip: bool = False) -> None:
        self.discrete = action_mode == "discrete"
        self.clip = clip
        self.max_speed = np.float32(max_speed)
        self.table = (WHEEL_SPEED_FRACTIONS * max_speed).astype(np.float32)
        self._speeds = [(float(left), float(right)) for left, right in self.table]
        self._max = float(self.max_speed)
        self.space: spaces.Space[Any]
        if self.discrete:
            self.space = spaces.Discrete(len(ACTION_CODES))
        else:
            self.space = spaces.Box(-1.0, 1.0, shape=(2,), dtype=np.float32)

    def single(self, action: Any) -> tuple[float, float]:
        """The (left, right) wheel speeds in rad/s of one action.

        The speeds are the exact products of float32 values in double precision; the simulator
        rounds them to float32, which gives the float32 products the vector env computes.
        """
        # The common action (a native float32 array of two fractions, as the space samples it)
        # is read without conversions; any other goes through the full check below.
        array = action if type(action) is np.ndarray else action_array(action)
        if not self.discrete and array.dtype is _FLOAT32 and array.shape == (2,):
            left, right = array.tolist()
            if -1.0 <= left <= 1.0 and -1.0 <= right <= 1.0:  # False for NaN too
                return left * self._max, right * self._max
        if self.discrete:
            if array.shape != () or array.dtype.kind not in "iu":
                raise InvalidActionError(
                    f"expected an integer action in 0..{len(ACTION_CODES) - 1}, "
                    f"found {_shown(action)} of type {type(action).__name__}"
                )
            index = int(array)
            if not 0 <= index < len(ACTION_CODES):
                raise InvalidActionError(
                    f"expected an action in 0..{len(ACTION_CODES) - 1} (one of the codes "
                    f"{', '.join(ACTION_CODES)}), found {index}"
                )
            return self._speeds[index]
        _check_fractions(array, (2,), "", self.clip)
        left, right = np.clip(array.astype(np.float32), -1.0, 1.0).tolist()
        return left * self._max, right * self._max

    def batch(self, actions: Any, num_envs: int) -> npt.NDArray[np.float32]:
        """The (N, 2) float32 wheel speeds in rad/s of a batch of actions."""
        array = action_array(actions)
        if self.discrete:
            if array.shape != (num_envs,) or array.dtype.kind not in "iu":
                raise InvalidActionError(
                    f"expected actions of shape ({num_envs},) with integers in "
                    f"0..{len(ACTION_CODES) - 1}, found shape {array.shape} of {array.dtype}"
                )
            bad = np.flatnonzero((array < 0) | (array >= len(ACTION_CODES)))
            if bad.size:
                raise InvalidActionError(
                    f"expected actions in 0..{len(ACTION_CODES) - 1}, "
                    f"found {array[bad[0]]} in environment {bad[0]}"
                )
            return self.table[array]
        _check_fractions(array, (num_envs, 2), " in environment {env}", self.clip)
        # A new C-ordered array whatever the caller's layout (a Fortran-ordered or transposed
        # policy output kept its order through astype and was refused by the batch).
        fractions = np.array(array, dtype=np.float32, order="C")
        if self.clip:
            np.clip(fractions, -1.0, 1.0, out=fractions)
        return fractions * self.max_speed


def action_array(
    actions: Any, what: str = "actions", kind: str = "real numbers (float32)"
) -> npt.NDArray[Any]:
    """``actions`` as a numpy array: the one reader of the actions of every env, the
    multi-robot ones too. A masked array is refused (``np.asarray`` would drop its mask and read
    the masked entries as the numbers under them, as the core's buffers refuse it), and so is
    what numpy cannot read as an array (a ragged list, a value whose ``__array__`` fails).
    Arrays of any layout (non-contiguous, read-only, big-endian) are read as their values; the
    caller checks the dtype (an object or text array is no numbers) and converts.

    Raises:
        InvalidActionError: A masked array, or a value that is no array.
    """
    if isinstance(actions, np.ma.MaskedArray):
        raise InvalidActionError(
            f"expected {what} to be {kind} in a plain array, found a numpy masked array (its "
            "mask would be dropped): pass array.filled(value) with the value masked entries "
            "should take"
        )
    try:
        return np.asarray(actions)
    except (TypeError, ValueError, OverflowError, RecursionError) as error:
        raise InvalidActionError(
            f"expected {what} to be {kind}, found {_a_type(actions)} numpy cannot read: "
            f"{_shown(str(error))}"
        ) from None


def real_actions(
    actions: Any, what: str = "actions", kind: str = "real numbers (float32)"
) -> npt.NDArray[np.float32]:
    """``actions`` (:func:`action_array`) as a new C-ordered, native float32 array, refusing an
    array of anything but real numbers (objects, text, complex numbers, booleans): numpy would
    read the text ``"0.5"`` as a number, and drop a complex number's imaginary part with a
    warning.

    Raises:
        InvalidActionError: As :func:`action_array`, or an array of no real numbers.
    """
    array = action_array(actions, what, kind)
    if array.dtype.kind not in "fiu":
        raise InvalidActionError(
            f"expected {what} to be {kind}, found an array of dtype {array.dtype}"
        )
    return np.array(array, dtype=np.float32, order="C")


def _check_fractions(
    array: npt.NDArray[Any], shape: tuple[int, ...], where: str, clip: bool
) -> None:
    """Raises InvalidActionError unless ``array`` holds finite reals of ``shape``, in [-1, 1]
    unless they are to be clipped."""
    if array.dtype.kind not in "fiu":
        raise InvalidActionError(
            f"expected real wheel speed fractions (float32), found dtype {array.dtype}"
        )
    if array.shape != shape:
        raise InvalidActionError(
            f"expected an action of shape {shape} (left, right wheel speed as fractions of the "
            f"motor limit), found shape {array.shape}"
        )
    inside = np.isfinite(array) if clip else np.abs(array) <= 1.0  # False for NaN too
    if inside.all():
        return
    finite = np.isfinite(array)
    flat = int(np.flatnonzero(~inside.reshape(-1))[0])
    value = array.reshape(-1)[flat]
    wheel = "left" if flat % 2 == 0 else "right"
    place = where.format(env=flat // 2)
    if not finite.reshape(-1)[flat]:
        raise InvalidActionError(
            f"expected finite wheel speeds, found {value} ({wheel} wheel{place})"
        )
    raise InvalidActionError(
        f"expected wheel speed fractions in [-1, 1], found {value} ({wheel} wheel{place})"
    )
