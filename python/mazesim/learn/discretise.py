"""The lower level's state: six Sharp distances, discretised by the report's Table 4.1.

The ``seed`` robot reads six Sharp GP2Y0A41SK0F sensors in volts, in the report's order
(:data:`SENSOR_ORDER`: front, back, left, right, left-front, right-front). Each reading is
turned back into a distance in cm by inverting the sensor's table (:func:`volts_to_cm`, the
arithmetic of :func:`mazesim.sharp_volts_to_cm`), then into a level by Table 4.1, both by the
core's discretiser (:func:`distances_and_levels` gives the two at once):

=====================  =====
distance d (cm)        level
=====================  =====
0 <= d < 7             0
7 <= d < 13            1
13 <= d < 20           2
d >= 20                3
=====================  =====

The six levels form one number, ``state = sum(level[i] * 4**i)`` with ``i`` the sensor's place
in :data:`SENSOR_ORDER`: the front sensor is the least significant base-4 digit, the right-front
sensor the most significant. There are ``4**6 = 4096`` states (:data:`NUM_STATES`).

Example:
    >>> import numpy as np
    >>> from mazesim.learn.discretise import distance_levels, encode_state, decode_state
    >>> levels = distance_levels(np.array([25.0, 30.0, 8.3, 8.3, 13.3, 13.3]))
    >>> levels.tolist()
    [3, 3, 1, 1, 2, 2]
    >>> encode_state(levels)
    2655
    >>> decode_state(2655).tolist()
    [3, 3, 1, 1, 2, 2]
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from mazesim._core import RobotProfile
from mazesim._sizes import index_array
from mazesim.errors import InvalidArgumentError

__all__ = [
    "LEVEL_EDGES_CM",
    "NUM_LEVELS",
    "NUM_SENSORS",
    "NUM_STATES",
    "SENSOR_ORDER",
    "SHARP_TABLE",
    "decode_state",
    "distance_levels",
    "distances_and_levels",
    "encode_state",
    "format_levels",
    "observation_states",
    "volts_to_cm",
]

#: The six distance sensors in the report's order (Fig. 4.7), as the ``seed`` robot lists them.
SENSOR_ORDER: tuple[str, ...] = ("front", "back", "left", "right", "left-front", "right-front")
#: Number of distance sensors in the state.
NUM_SENSORS = len(SENSOR_ORDER)
#: Table 4.1: a distance is at level k when it is at least ``LEVEL_EDGES_CM[k - 1]`` cm and below
#: ``LEVEL_EDGES_CM[k]`` cm.
LEVEL_EDGES_CM: tuple[float, ...] = (7.0, 13.0, 20.0)
#: Levels per sensor (0 to 3).
NUM_LEVELS = len(LEVEL_EDGES_CM) + 1
#: Number of lower-level states, ``4**6``.
NUM_STATES = NUM_LEVELS**NUM_SENSORS
#: The Sharp GP2Y0A41SK0F table of the ``seed`` robot profile (``robots/seed.toml``), read from
#: it: distance in metres and the output in volts, the volts falling as the distance grows.
SHARP_TABLE: tuple[tuple[float, float], ...] = tuple(
    (float(metres), float(volts))
    for metres, volts, _ in RobotProfile.builtin("seed").distance_sensor_table(0)
)
_PLACE_VALUES = NUM_LEVELS ** np.arange(NUM_SENSORS, dtype=np.int64)


def volts_to_cm(volts: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Converts Sharp readings in volts to distances in cm, element by element.

    The ``seed`` robot's table is inverted piecewise linearly and clamped: 3.03 V or more reads
    3 cm, 0.31 V or less reads 40 cm. The core's discretiser computes it, the arithmetic of
    :func:`mazesim.sharp_volts_to_cm`.

    Args:
        volts: Readings of any shape.

    Returns:
        The distances in cm, float64, of the same shape.

    Raises:
        InvalidArgumentError: A reading is below 0 V, infinite or not a number.
    """
    return distances_and_levels(volts)[0]


def distance_levels(distances_cm: npt.ArrayLike) -> npt.NDArray[np.int64]:
    """Table 4.1: the level (0 to 3) of each distance in cm.

    Args:
        distances_cm: Distances of any shape.

    Returns:
        The levels, int64, of the same shape.

    Raises:
        InvalidArgumentError: A distance is below 0 cm or not a number.
    """
    return _discretised(distances_cm, "distances in cm", in_cm=True)[1]


def distances_and_levels(
    volts: npt.ArrayLike,
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
    """:func:`volts_to_cm` and :func:`distance_levels` of Sharp readings in one call to the
    core's discretiser: the distances in cm (float64) and their levels (int64), each of the
    readings' shape."""
    return _discretised(volts, "Sharp readings in volts", in_cm=False)


def _discretised(
    values: npt.ArrayLike, what: str, *, in_cm: bool
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
    """The core's distances and levels of ``values``, any shape."""
    from mazesim._core import sharp_distances

    array = _real_values(values, what)
    cm, levels = sharp_distances(np.ascontiguousarray(array).reshape(-1), in_cm=in_cm)
    return cm.reshape(array.shape), levels.reshape(array.shape)


def _real_values(values: npt.ArrayLike, what: str) -> npt.NDArray[np.float64]:
    """``values`` as float64, refused unless they are real numbers (bools, integers, floats):
    complex numbers, text and objects are no readings, and numpy would drop an imaginary part or
    turn None into NaN without a word."""
    try:
        array = np.asarray(values)
    except (ValueError, TypeError) as error:  # ragged nesting, unconvertible objects
        raise InvalidArgumentError(f"expected {what} as an array of numbers: {error}") from None
    if array.dtype.kind not in "biuf":
        raise InvalidArgumentError(
            f"expected {what} as real numbers (a bool, integer or float array), found an array "
            f"of dtype {array.dtype}"
        )
    return array.astype(np.float64, copy=False)


def encode_state(levels: npt.ArrayLike) -> npt.NDArray[np.int64] | int:
    """The state number of six levels: ``sum(level[i] * 4**i)``.

    Args:
        levels: Six levels in :data:`SENSOR_ORDER`, or an (N, 6) array of them.

    Returns:
        An ``int`` for one set of levels, an (N,) int64 array for N.

    Raises:
        InvalidArgumentError: The last axis is not 6 long or a level is not a whole number
            from 0 to 3.
    """
    array = index_array(levels, "levels", NUM_LEVELS)
    if array.ndim == 0 or array.shape[-1] != NUM_SENSORS:
        raise InvalidArgumentError(
            f"expected {NUM_SENSORS} levels per state (last axis), found shape {array.shape}"
        )
    states = array @ _PLACE_VALUES
    return int(states) if array.ndim == 1 else states


def decode_state(state: npt.ArrayLike) -> npt.NDArray[np.int64]:
    """The six levels of a state number (the inverse of :func:`encode_state`).

    Args:
        state: A state number or an array of them, each in ``[0, 4096)``.

    Returns:
        The levels, shape ``state.shape + (6,)``.

    Raises:
        InvalidArgumentError: A state is not a whole number in ``[0, 4096)``.
    """
    array = index_array(state, "states", NUM_STATES)
    return (array[..., None] // _PLACE_VALUES) % NUM_LEVELS


def observation_states(observations: npt.ArrayLike) -> npt.NDArray[np.int64]:
    """The (N,) states of batch observations (the first six columns, volts): the core's
    discretiser, :func:`mazesim._core.lower_level_states`, on them as float32 (real numbers
    only, as :func:`volts_to_cm` takes them)."""
    from mazesim._core import lower_level_states

    array = _real_values(observations, "observations in volts")
    return lower_level_states(np.asarray(array, dtype=np.float32))


def format_levels(levels: npt.ArrayLike) -> str:
    """Six levels as the report prints them (Fig. 4.7), e.g. ``"[3, 3, 1, 1, 2, 2]"``."""
    return "[" + ", ".join(str(int(level)) for level in np.asarray(levels).ravel()) + "]"
