"""An exception that reaches the public surface from below it is put into mazesim's error tree
(``mazesim._error_tree``): a built-in argument failure becomes InvalidArgumentError, an OSError
MazesimIOError, anything else of mazesim's or a library's InternalError; each chained to the
original, and still of the original's built-in class where Python allows it. The caller's own
exceptions are left alone."""

from __future__ import annotations

import collections
import io
import pickle
import shutil
import zipfile
from pathlib import Path

import numpy as np
import pytest

import mazesim
from mazesim._error_tree import in_the_tree
from mazesim.errors import InternalError, InvalidArgumentError, MazesimIOError


def _raised(call: object) -> BaseException:
    try:
        call()  # type: ignore[operator]
    except Exception as error:  # noqa: BLE001 - the error is what the test looks at
        return error
    raise AssertionError("expected the call to raise")


def test_an_array_of_the_wrong_shape_is_an_invalid_argument_and_still_an_index_error() -> None:
    from mazesim.odometry import advance

    with pytest.raises(
        InvalidArgumentError, match="advance: the arguments do not fit: IndexError"
    ) as caught:
        advance(np.zeros(0), [1.0], [1.0], 0.05)
    assert isinstance(caught.value, IndexError)
    assert isinstance(caught.value.__cause__, IndexError)
    again = pickle.loads(pickle.dumps(caught.value))
    assert isinstance(again, InvalidArgumentError) and isinstance(again, IndexError)
    assert str(again) == str(caught.value)


def test_text_for_an_array_is_named_as_not_numbers() -> None:
    from mazesim.learn.discretise import format_levels

    with pytest.raises(
        InvalidArgumentError, match="levels refused: expected an array of numbers, found a str"
    ):
        format_levels("/tmp/garbage.toml")  # type: ignore[arg-type]


def test_a_nesting_deeper_than_numpy_reads_is_named() -> None:
    from mazesim.odometry import wrap_angle

    nested: list[object] = []
    for _ in range(1000):
        nested = [nested]
    with pytest.raises(InvalidArgumentError, match="angle refused: expected an array of numbers"):
        wrap_angle(nested)  # type: ignore[arg-type]


def test_a_library_key_error_is_an_invalid_argument_that_is_still_a_key_error() -> None:
    error = _raised(lambda: collections.ChainMap({})["missing"])
    made = in_the_tree("f", error, True)
    assert isinstance(made, InvalidArgumentError) and isinstance(made, KeyError)
    assert "f: the arguments do not fit: KeyError" in str(made)


def test_a_library_os_error_names_the_file_and_the_reason(tmp_path: Path) -> None:
    missing = tmp_path / "no" / "such.toml"
    error = _raised(lambda: shutil.copyfile(missing, tmp_path / "copy.toml"))
    made = in_the_tree("f", error, False)
    assert isinstance(made, MazesimIOError) and isinstance(made, FileNotFoundError)
    assert str(made) == f"{missing}: No such file or directory"
    assert made.filename == str(missing) and made.errno == 2


def test_a_library_failure_of_another_kind_is_an_internal_error_quoting_it_briefly() -> None:
    error = _raised(lambda: zipfile.ZipFile(io.BytesIO(b"not a zip")))
    made = in_the_tree("f", error, False)
    assert isinstance(error, zipfile.BadZipFile) and isinstance(made, InternalError)
    assert "f: internal error, please report" in str(made)
    huge = _raised(lambda: collections.ChainMap({})["x" * 100_000])
    assert len(str(in_the_tree("f", huge, True))) < 500


def test_the_callers_own_exceptions_and_interrupts_are_left_alone() -> None:
    class Mine(Exception):
        pass

    def callback() -> None:
        raise Mine("the caller's")

    own = _raised(callback)
    assert in_the_tree("f", own, False) is own
    interrupt = KeyboardInterrupt()
    assert in_the_tree("f", interrupt, False) is interrupt
    refused = mazesim.InvalidArgumentError("x")
    assert in_the_tree("f", refused, True) is refused


def test_a_value_quoted_at_length_is_shown_shortened() -> None:
    """Every message of the tree, the compiled core's too, is shown at most MOST_MESSAGE
    characters long, its start and end kept: a name of a million characters is quoted in a
    line, not whole."""
    from mazesim.errors import MOST_MESSAGE, MazesimIOError, UnknownNameError

    with pytest.raises(UnknownNameError) as caught:
        mazesim.World.builtin("w" * 10**6)
    shown = str(caught.value)
    assert len(shown) <= MOST_MESSAGE + 40, len(shown)
    assert shown.startswith("unknown world") and "characters ...]" in shown
    io_error = str(MazesimIOError("x" * 10**5))
    assert io_error.endswith("x") and len(io_error) <= MOST_MESSAGE + 40
    assert str(mazesim.MazesimError("short")) == "short"
