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


def test_a_failure_no_check_names_says_what_was_expected_and_what_was_found() -> None:
    from mazesim.learn.discretise import format_levels

    with pytest.raises(InvalidArgumentError) as caught:
        format_levels([float("nan")] * 6)
    message = str(caught.value)
    assert message.startswith("format_levels: the arguments do not fit: ValueError")
    assert message.endswith(
        "; expected levels: an array of numbers; found levels=[nan, nan, nan, nan, nan, nan]"
    )


def test_a_long_value_is_shortened_in_what_was_found() -> None:
    from mazesim.odometry import advance

    with pytest.raises(InvalidArgumentError) as caught:
        advance(np.zeros(0), [1.0] * 1000, [1.0], 0.05)
    message = str(caught.value)
    assert "expected pose: a numpy array of float64, left: an array of numbers" in message
    assert "found pose=array([], dtype=float64), left=[1.0, 1.0" in message
    assert "characters ...]" in message and len(message) < 600


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


def test_a_value_whose_repr_fails_is_quoted_as_what_it_is() -> None:
    """A list nested 100,000 deep (its repr runs out of recursion) given where a camera's
    width goes, and an object whose __repr__ raises, are refused with the package's own error,
    the value described, not with the RecursionError of quoting it."""
    from mazesim.webots.camera import Camera

    nested: list[object] = []
    for _ in range(100_000):
        nested = [nested]
    with pytest.raises(mazesim.errors.WrongTypeError, match="nested too deep to show"):
        Camera.imageGetBlue(b"", nested, 0, 0)  # type: ignore[arg-type]

    class Opaque:
        def __repr__(self) -> str:
            raise ValueError("no")

    with pytest.raises(mazesim.errors.WrongTypeError, match="Opaque whose repr raised ValueError"):
        Camera.imageGetBlue(b"", Opaque(), 0, 0)  # type: ignore[arg-type]


def _typed_at(prompt: str, module: str) -> BaseException:
    """The exception of a callback defined by code that has no file of its own (typed at the
    prompt, given to ``python -c``), whose globals name ``module``."""
    namespace: dict[str, object] = {"__name__": module}
    code = "def callback():\n    raise ZeroDivisionError('the caller s')\n"
    exec(compile(code, prompt, "exec"), namespace)  # noqa: S102 - the code under test's origin
    return _raised(namespace["callback"])


@pytest.mark.parametrize("prompt", ["<stdin>", "<string>", "<console>"])
def test_a_callback_typed_at_the_prompt_is_the_callers_not_an_internal_error(prompt: str) -> None:
    """A world sampler typed at Python's prompt (or given to ``python -c``) that raised was
    reported as mazesim's "internal error, please report": code of no file counted as a
    library's. Code the package generates in its own modules stays the package's."""
    own = _typed_at(prompt, "__console__")
    assert in_the_tree("f", own, False) is own
    generated = _typed_at("<string>", "mazesim.errors")
    assert isinstance(in_the_tree("f", generated, False), InternalError)


def test_an_env_s_world_sampler_typed_at_the_prompt_raises_its_own_exception() -> None:
    gymnasium = pytest.importorskip("gymnasium")
    import mazesim.envs  # noqa: F401 - registers the envs

    namespace: dict[str, object] = {"__name__": "__console__"}
    code = "def sampler(rng):\n    raise ZeroDivisionError('the caller s')\n"
    exec(compile(code, "<stdin>", "exec"), namespace)  # noqa: S102 - the code under test's origin
    with pytest.raises(ZeroDivisionError, match="the caller s") as caught:
        gymnasium.make("mazesim/EPuckMaze-v0", world=namespace["sampler"])
    assert not isinstance(caught.value, mazesim.MazesimError)


def test_every_message_of_the_package_quotes_a_repr_through_shown() -> None:
    """A message of the package quotes a value's repr with ``_shown`` (about 200 characters),
    never with ``{value!r}``, which quoted a text of a million characters whole, up to the
    4,000 characters every message is cut to. Not only in a ``raise``: a helper that builds a
    message for a raise elsewhere (a missing file's "did you mean"), a warning printed, an
    assertion's text. A ``__repr__`` is no message; a text that must read back (a spec written
    inline) calls ``repr()`` by name."""
    import ast

    package = Path(mazesim.__file__).parent
    found = []
    for file in sorted(package.rglob("*.py")):
        tree = ast.parse(file.read_text(encoding="utf-8"))
        representations = {
            id(sub)
            for node in ast.walk(tree)
            if isinstance(node, ast.FunctionDef) and node.name == "__repr__"
            for sub in ast.walk(node)
        }
        found += [
            f"{file.relative_to(package)}:{node.lineno}"
            for node in ast.walk(tree)
            if isinstance(node, ast.FormattedValue)
            and node.conversion == ord("r")
            and id(node) not in representations
        ]
    assert found == [], found


def test_a_long_word_of_any_message_is_shortened_to_about_200_characters() -> None:
    """The compiled core's messages quote a name or a path as it was given, and a deep .wbt
    file's field path is one long word: each word past MOST_QUOTED characters is shortened."""
    from mazesim.errors import MOST_QUOTED, UnknownNameError

    with pytest.raises(UnknownNameError) as caught:
        mazesim.World.builtin("w" * 10**5)
    assert len(str(caught.value)) < 3 * MOST_QUOTED + 300, len(str(caught.value))
    with pytest.raises(MazesimIOError) as missing:
        mazesim.World.load("/tmp/" + "a" * 5000)
    assert len(str(missing.value)) < 2 * MOST_QUOTED + 200, str(missing.value)
    assert str(mazesim.MazesimError("short words " * 100)) == "short words " * 100


def test_any_failure_with_an_argument_its_annotation_does_not_take_names_that_argument() -> None:
    # Not only the built-in argument failures: a library's own exception (zipfile's BadZipFile,
    # an Exception) or an arithmetic one, met because an argument was of the wrong kind, is
    # refused naming that argument; the same failure with fitting arguments is not.
    from mazesim._checks import checked

    def opened(archive: bytes, parts: list[int]) -> int:
        zipfile.ZipFile(io.BytesIO(archive))
        return 1 // parts[0]

    call = checked(opened)
    with pytest.raises(mazesim.WrongTypeError, match="parts") as caught:
        call(b"not a zip", [1.5])
    assert "parts" in str(caught.value) and "1.5" in str(caught.value)
    with pytest.raises(InternalError, match="BadZipFile"):
        call(b"not a zip", [1])

    def divided(parts: list[int]) -> int:
        return 1 // parts[0]

    with pytest.raises(mazesim.WrongTypeError, match="parts"):
        checked(divided)([0.0])
    with pytest.raises(ZeroDivisionError):  # the caller's own code, fitting arguments
        checked(divided)([0])


def test_an_abstract_class_made_as_it_is_names_what_to_define_and_is_still_a_type_error() -> None:
    from mazesim.barcode import Alg7Decoder, CodeBook, Decoder

    with pytest.raises(TypeError) as caught:
        Decoder(CodeBook.default())  # type: ignore[abstract]
    assert isinstance(caught.value, InvalidArgumentError)
    assert str(caught.value) == (
        "Decoder: expected a subclass that defines _decode (such as Alg7Decoder, "
        "RobustDecoder), found the abstract Decoder itself"
    )

    class Own(Decoder):
        def _decode(self, samples: object) -> None:
            return None

    assert isinstance(Own(CodeBook.default()), Decoder)  # a subclass of the user's is made
    decoder = Alg7Decoder(CodeBook.default())
    assert type(pickle.loads(pickle.dumps(decoder))) is Alg7Decoder


def test_running_out_of_memory_is_said_so_not_blamed_on_the_arguments_kinds() -> None:
    # Raised in a library's frame (the standard library's collections), as numpy's or a
    # parser's allocation would.
    code = compile("raise MemoryError()", collections.__file__ or "collections.py", "exec")
    error = _raised(lambda: exec(code))
    made = in_the_tree("load_world", error, True, "expected name_or_path: str; found 'x.wbt'")
    assert isinstance(made, InternalError) and isinstance(made, MemoryError)
    assert not isinstance(made, InvalidArgumentError)
    assert str(made).startswith("load_world: ran out of memory (MemoryError): expected an input")
    assert "arguments do not fit" not in str(made)


def test_a_public_function_out_of_memory_says_so_without_checking_its_arguments_again(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    from mazesim import _checks
    from mazesim.learn.discretise import encode_state

    def no_check(*_: object) -> None:
        raise AssertionError("the arguments were checked again after a MemoryError")

    code = compile("raise MemoryError()", collections.__file__ or "collections.py", "exec")
    monkeypatch.setattr(_checks._Parameters, "check", no_check)
    monkeypatch.setattr("mazesim.learn.discretise.np.asarray", lambda *_, **__: exec(code))
    with pytest.raises(MemoryError) as caught:
        encode_state([0] * 6)
    assert isinstance(caught.value, InternalError)
    assert "encode_state: ran out of memory" in str(caught.value)
