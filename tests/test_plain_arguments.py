"""The surface check's short way (``mazesim._checks``): a call whose every argument is one its
parameter takes with no check to make (``display.drawPixel(3, 4)``, ``motor.setVelocity(6.28)``)
skips the checks made before the call, which cost about 3 µs a call: a controller drawing its
map pixel by pixel on a Display spent half its time in them. The short way must decide as the
long way does: a value given by position (which may take it) and by name (which never does)
are answered alike, for every kind of annotation and every kind of value tried here."""

from __future__ import annotations

import enum
import math
from collections.abc import Sequence
from typing import Any

import numpy as np
import pytest

from mazesim._checks import checked
from mazesim.errors import MaybeInfinite


class _Level(enum.IntEnum):
    LOW = 1


class _Ratio(float):
    pass


HINTS: list[Any] = [
    int,
    float,
    MaybeInfinite,
    bool,
    str,
    Any,
    int | None,
    float | None,
    list[int],
    tuple[float, float],
    Sequence[float],
    np.ndarray,
]
VALUES: list[Any] = [
    0,
    -1,
    7,
    1 << 63,
    1 << 64,
    -(1 << 63) - 1,
    1.5,
    2.0,
    -0.0,
    math.nan,
    math.inf,
    -math.inf,
    1e308,
    True,
    np.True_,
    None,
    "3",
    b"x",
    [1],
    (1.0, 2.0),
    [math.nan, 1.0],
    np.float64(math.nan),
    np.float32(2.5),
    np.int64(3),
    np.array([1.0, 2.0]),
    np.array([math.nan]),
    object(),
    _Level.LOW,
    _Ratio(0.5),
    _Ratio(math.nan),
]


def _answer(call: Any) -> str:
    try:
        call()
    except Exception as failure:  # noqa: BLE001 - the answer compared, whatever it is
        return f"{type(failure).__name__}: {failure}"
    return "taken"


def _device(hint: Any, takes_nan: bool) -> Any:
    def setValue(self: Any, value: Any) -> None:  # noqa: N802 - as Webots names its methods
        del self, value

    setValue.__annotations__ = {"value": hint, "return": None}
    device = type("Device", (), {"setValue": checked(setValue, method=True, takes_nan=takes_nan)})
    return device()


@pytest.mark.parametrize("takes_nan", [False, True], ids=["mazesim", "webots-api"])
@pytest.mark.parametrize("hint", HINTS, ids=str)
def test_a_value_by_position_is_answered_as_by_name(hint: Any, takes_nan: bool) -> None:
    device = _device(hint, takes_nan)
    _answer(lambda: device.setValue(value=0))  # the first call reads the annotations
    differ = {}
    for value in VALUES:
        by_position = _answer(lambda v=value: device.setValue(v))
        by_name = _answer(lambda v=value: device.setValue(value=v))
        if by_position != by_name:
            differ[repr(value)] = (by_position, by_name)
    assert not differ, differ


def test_the_short_way_refuses_what_the_long_way_refuses() -> None:
    device = _device(int, takes_nan=True)
    device.setValue(1)
    for refused in (True, 1.5, 1 << 64, None, "1"):
        with pytest.raises(Exception, match="value refused"):
            device.setValue(refused)
