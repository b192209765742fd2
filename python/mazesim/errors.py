"""The exceptions raised by mazesim.

Every error that mazesim raises on purpose is a :class:`MazesimError`. Each subclass also derives
from the built-in exception a Python user would expect (``ValueError``, ``LookupError``,
``OSError``), so ``except ValueError`` keeps working.

The compiled core raises these classes too: it calls a class with one message string (and, for
:class:`UnknownNameError`, the keywords ``name`` and ``available``) and then sets the extra
attributes, so every constructor takes a single positional message and every attribute defaults
to ``None``.
"""

from __future__ import annotations

import contextlib
import difflib
import math
import numbers
import os
import re
from collections.abc import Collection, Iterator
from typing import Annotated, Any

__all__ = [
    "ClusterConnectionError",
    "ControllerBuildError",
    "InternalError",
    "InvalidActionError",
    "InvalidArgumentError",
    "MazesimError",
    "MazesimIOError",
    "MissingDependencyError",
    "PolicyFormatError",
    "RunFormatError",
    "SimulatorBusyError",
    "SnapshotError",
    "UnknownNameError",
    "WorldFormatError",
    "WrongTypeError",
]


#: Most characters of a user's value that a message quotes: a longer value (a name of a
#: million characters) is quoted by its start and its end (:func:`_shortened`).
MOST_QUOTED = 200
#: Most characters of a message: a longer one (a value quoted at length, below the package's
#: own helpers) is shown shortened the same way.
MOST_MESSAGE = 4000


def _shortened(text: str, most: int = MOST_QUOTED) -> str:
    """``text`` as a message quotes it: whole if it has at most ``most`` characters, else its
    start and its end around a note of how many characters were left out (the one helper of
    every message that quotes a user's value)."""
    if len(text) <= most:
        return text
    head, tail = most * 2 // 3, most // 3
    return f"{text[:head]}[... {len(text) - head - tail} characters ...]{text[len(text) - tail :]}"


#: A run of more than :data:`MOST_QUOTED` characters without a space: no word of the package's
#: own, but a value quoted in it (a path, a name, a dotted field of a deep file).
_LONG_WORD = re.compile(rf"\S{{{MOST_QUOTED + 1},}}")


def _words_shortened(message: str) -> str:
    """``message`` with each of its words longer than :data:`MOST_QUOTED` characters
    :func:`_shortened`: a message of the compiled core, or one that quotes a value with ``str``,
    quotes a path or a name of a million characters as a line."""
    return _LONG_WORD.sub(lambda word: _shortened(word.group()), message)


#: Whether a ``mazesim`` command is running: :func:`mazesim.cli.main` sets it while the command
#: runs (:func:`_command_line`), so that a message names what the user can change as the user
#: gave it (:func:`_argument`): the command's option (``--out``), else the Python parameter.
_ON_COMMAND_LINE = [False]


def _argument(option: str, parameter: str) -> str:
    """How a message names an argument the user may change: its command-line ``option``
    (``"--out"``, ``"--resume"``) while a ``mazesim`` command runs, else the Python ``parameter``
    of the function called (``"monitor_dir"``, ``"resume=True"``): the one source of the words
    "choose another --out" on the command line and "choose another monitor_dir" in Python."""
    return option if _ON_COMMAND_LINE[0] else parameter


@contextlib.contextmanager
def _command_line() -> Iterator[None]:
    """Makes :func:`_argument` name command-line options while the block runs (a command's
    run, in :func:`mazesim.cli.main`); the former naming after it, however it ends."""
    before = _ON_COMMAND_LINE[0]
    _ON_COMMAND_LINE[0] = True
    try:
        yield
    finally:
        _ON_COMMAND_LINE[0] = before


def _shown(value: object) -> str:
    """``repr(value)`` as a message quotes it, :func:`_shortened`: every ``{value!r}`` of a
    message the package raises is written ``{_shown(value)}`` (a test of the package's source
    keeps it so), so that a value of a million characters shows as a line, and a value whose
    ``repr`` fails (a list nested 100,000 deep, whose ``repr`` runs out of recursion; an object
    whose ``__repr__`` raises) as what it is, not as the message's own exception."""
    try:
        text = repr(value)
    except RecursionError:
        text = f"<a {type(value).__name__} nested too deep to show>"
    except Exception as failure:  # noqa: BLE001 - any __repr__ of the caller's may raise
        text = f"<a {type(value).__name__} whose repr raised {type(failure).__name__}>"
    return _shortened(text)


class MazesimError(Exception):
    """The root of every exception that mazesim raises on purpose.

    Its message is shown at most :data:`MOST_MESSAGE` characters long (:func:`_shortened`), so
    that no value quoted in it floods a terminal or a log.
    """

    def __str__(self) -> str:
        return _shortened(_words_shortened(super().__str__()), MOST_MESSAGE)


class WorldFormatError(MazesimError, ValueError):
    """A world description is malformed.

    The message names the file, the line and the field, and says what was expected.

    Attributes:
        source: The file name or ``"<string>"`` the text came from, if known.
        line: The 1-based line of the error, if known.
        column: The 1-based column of the error, if known.
        field: The dotted name of the offending field (e.g. ``"walls[2].size"``), if known.
    """

    def __init__(
        self,
        message: str = "",
        *,
        source: str | None = None,
        line: int | None = None,
        column: int | None = None,
        field: str | None = None,
    ) -> None:
        super().__init__(message)
        self.source = source
        self.line = line
        self.column = column
        self.field = field


class UnknownNameError(MazesimError, LookupError, ValueError):
    """A name (a built-in world, a robot profile, a sensor) is not known.

    It is a ``LookupError`` (a name looked up) and a ``ValueError`` (an argument's value out of
    its choices), so code that caught ``ValueError`` for an unknown reward or action mode, which
    once raised ``InvalidArgumentError``, still catches it.

    Given the name asked for and the names that exist, the message ends with the closest of
    them, as a typo's likely fix: ``...; did you mean 'seed-maze'?``.

    Attributes:
        available: The names that would have been accepted, if known.
        suggestion: The accepted name closest to the one asked for (of ``available`` and
            ``nearby``: the world files beside a path that does not exist), or None when none is
            close.
    """

    def __init__(
        self,
        message: str = "",
        *,
        available: list[str] | None = None,
        name: str | None = None,
        nearby: list[str] | None = None,
    ) -> None:
        self.suggestion = _closest_name(name, [*(available or []), *(nearby or [])])
        if self.suggestion is not None:
            message = f"{message}; did you mean {_shown(self.suggestion)}?"
        super().__init__(message)
        self.available = available


class _Registered:
    """The mark of :data:`RegisteredName`."""

    def __repr__(self) -> str:
        return "a name a registry of mazesim holds"


#: The annotation of every parameter whose value names a registered thing (an env id, a
#: controller, a source of events, a render, action or reward mode, a shipped navigator's
#: world): a ``str`` to type checkers, checked by :func:`_known_name`. The hostile walk of the
#: package's surface finds these parameters by it, whatever they are called, and gives each a
#: name no registry holds, which must be refused listing the known names.
RegisteredName = Annotated[str, _Registered()]


class _Unbounded:
    """The mark of :data:`MaybeInfinite`."""

    def __repr__(self) -> str:
        return "a number, or an infinity"


#: The annotation of a number parameter that may be infinite (a bound of no limit, a distance
#: of "nothing in range"): a ``float`` to type checkers. A parameter annotated plain ``float`` is
#: given a finite number or refused before the call (``mazesim._checks``); NaN is refused for
#: both. The hostile walk gives every ``float`` parameter an infinity, found by its annotation.
MaybeInfinite = Annotated[float, _Unbounded()]


def _known_name(value: object, what: str, known: Collection[str], hint: str = "") -> str:
    """``value`` when it is one of the ``known`` names of ``what``; else the one refusal of a
    name no registry of mazesim holds: an :class:`UnknownNameError` listing the known names
    (``available``), then ``hint`` (what to do instead, if anything), and the closest as a "did
    you mean". A value of any type is refused so, never hashed: a list or a dict where a name
    goes is refused as an unknown name, not as Python's unhashable ``TypeError``."""
    if isinstance(value, str) and value in known:
        return value
    names = [str(each) for each in known]
    raise UnknownNameError(
        f"expected {what} to be one of {', '.join(names)}; found {_shown(value)}{hint}",
        available=names,
        name=value if isinstance(value, str) else None,
    )


def _closest_name(name: str | None, available: list[str] | None, cutoff: float = 0.6) -> str | None:
    """The name of ``available`` closest to ``name`` (difflib's ratio of at least ``cutoff``), or
    else the one name that starts with what was typed, a shortened name (``avoid`` for
    ``avoid-collision``), or None: the one "did you mean" of the package. File names are
    compared by their stems (``my-maz.toml`` to ``my-maze``), so that a shared folder or suffix
    makes no name close."""
    if name is None or not available:
        return None
    typed = _spelling(str(name))
    # A name spelt in another case or with other separators ("next_step" for "NextStep").
    alike = {str(each) for each in available if _plain(_spelling(str(each))) == _plain(typed)}
    if len(alike) == 1:
        return alike.pop()
    scored = [
        (difflib.SequenceMatcher(None, _spelling(str(each)), typed).ratio(), str(each))
        for each in available
    ]
    score, closest = max(scored)
    if score >= cutoff:
        return closest
    # A name cut short: the first word or words of exactly one name (case aside).
    longer = {
        str(each)
        for each in available
        if len(typed) >= 2 and _spelling(str(each)).lower().startswith(typed.lower())
    }
    return longer.pop() if len(longer) == 1 else None


def _plain(name: str) -> str:
    """``name`` as compared for a name spelt otherwise: lower case, without ``_`` and ``-``."""
    return name.replace("_", "").replace("-", "").lower()


def _spelling(name: str) -> str:
    """What of ``name`` is compared for a "did you mean": a path's file name without its suffix
    (``maps/my-maze.toml`` is ``my-maze``), any other name whole."""
    file = name.replace("\\", "/").rsplit("/", 1)[-1]
    stem, dot, suffix = file.rpartition(".")
    return stem if dot and stem and suffix.isalpha() else file


#: Starts of names whose "u" is spoken "you" (uint8, UUID), which take "a".
_SPOKEN_YOU = ("uint", "uni", "uu", "use", "usu", "uti")


def _with_article(name: str) -> str:
    """``name`` with "a" or "an" as it is spoken: "an int", "an ndarray", "a uint8", "a float"
    (the binding's ``with_article`` says the same)."""
    lower = name.lower()
    # An "nd" is spoken "en-dee" (ndarray).
    vowel = lower[:1] in tuple("aeiou") and not lower.startswith(_SPOKEN_YOU)
    vowel = vowel or lower.startswith("nd")
    return f"{'an' if vowel else 'a'} {name}"


def _a_type(value: object) -> str:
    """What was found, for a refusal "expected ..., found {_a_type(value)}": the name of the
    value's type with its article ("an int", "a str", "an ndarray"), or "None"; the one wording
    of the package's refusals of a type, the binding's (``type_name``) included."""
    return "None" if value is None else _with_article(type(value).__name__)


class InvalidActionError(MazesimError, ValueError):
    """An action is not valid: NaN or infinite wheel speeds, or an unknown action code."""


class InvalidArgumentError(MazesimError, ValueError):
    """An argument is out of range or of the wrong shape or dtype."""


class WrongTypeError(InvalidArgumentError, TypeError):
    """An argument is of a type the parameter does not take (text for a number, None for a
    sensor's sampling period, a list for a world): an :class:`InvalidArgumentError` that is also
    a ``TypeError``, as Python's own refusal of a wrong type is, so ``except TypeError`` and
    ``except InvalidArgumentError`` both catch it. A value of the right type that is out of range
    stays an :class:`InvalidArgumentError` (a ``ValueError``)."""


class MazesimIOError(MazesimError, OSError):
    """Reading or writing a file failed (the message names the file and gives the OS's reason).

    The compiled core also sets ``errno``, ``strerror`` (the OS's reason) and ``filename``.
    """

    def __str__(self) -> str:
        """The message as given (shortened as every message is), whatever attributes are set
        after construction."""
        if len(self.args) == 1:
            return _shortened(_words_shortened(str(self.args[0])), MOST_MESSAGE)
        return super().__str__()


class SnapshotError(InvalidArgumentError):
    """A simulator snapshot cannot be restored: the bytes are not a snapshot, are truncated or
    corrupt, are of another format version, or were taken in another world, with another robot
    profile, control step or noise setting; the message says which, with what was expected and
    what was found."""


class InternalError(MazesimError, RuntimeError):
    """A bug in mazesim: the compiled core panicked. The message starts with "internal error,
    please report" and carries the panic's message; the process goes on."""


class SimulatorBusyError(MazesimError, RuntimeError):
    """A simulator or batch is in the middle of a call that cannot be waited for: a call on the
    same thread (from a property of one of the arguments, or from a signal handler), or, in a
    child made by ``fork()``, a call of a parent's thread the child does not have. A call from
    another thread is not refused: it waits (the GIL released) until the object is free."""


class MissingDependencyError(MazesimError, ImportError):
    """An optional part of mazesim needs a package that is not installed (for example ROS 1's
    ``rospy`` for :mod:`mazesim.ros`); the message names the package and how to install it."""


class ControllerBuildError(MazesimError, RuntimeError):
    """A compiled Webots controller (C) could not be built: the message quotes the compiler."""


class ClusterConnectionError(MazesimError, ConnectionError):
    """Joining a Ray cluster failed; the message names the address and what to check or set
    (such as Ray's token authentication)."""


class PolicyFormatError(MazesimError, ValueError):
    """A saved navigator (Q-tables and their metadata, :mod:`mazesim.learn.tables`) cannot be used:
    the file is truncated or corrupt, of another format version, or made for another state or
    action encoding or another world; the message names the file and says which."""


class RunFormatError(MazesimError, ValueError):
    """A recorded run (:mod:`mazesim.replay.run`) cannot be read: it is not a run file, it is
    malformed, or it was written in a newer major version of the format than this mazesim
    reads; the message names the file and says which."""


def _path_of(value: object, name: str) -> str:
    """The path ``value`` names, as a str: a str, or an ``os.PathLike`` whose ``__fspath__``
    gives a str. Every path argument of the package takes the same, the compiled core's
    (``World.load``, ``World.save``) included: bytes, or a path object giving bytes, is refused
    (decode it with ``os.fsdecode``).

    The one path helper: ``mazesim._paths.fs_path`` for the readers, the writer of
    ``mazesim._atomic`` for every output.

    Raises:
        WrongTypeError: ``value`` is not such a path.
    """
    found = _a_type(value)
    if isinstance(value, os.PathLike) and not isinstance(value, (str, bytes)):
        # A path object's own code may fail in any way: it names no path, as the compiled
        # core's path arguments say of it (never the object's own exception escaping).
        try:
            value = type(value).__fspath__(value)  # what it gives, whatever its type
        except Exception as error:  # noqa: BLE001 - any failure of user code is the same refusal
            raise WrongTypeError(
                f"expected {name} to be a str or os.PathLike, found {found} whose __fspath__ "
                f"raised {type(error).__name__}: {_shown(str(error))}"
            ) from error
        if not isinstance(value, str):
            found += f" whose __fspath__ gives {_a_type(value)}"
    if not isinstance(value, str):
        hint = " (decode bytes with os.fsdecode)" if "bytes" in found else ""
        raise WrongTypeError(f"expected {name} to be a str or os.PathLike, found {found}{hint}")
    return value


def _bounded_number(
    name: str, value: Any, *, above: float | None = None, least: float | None = None
) -> float:
    """A number taken from a caller, as a float: finite, and above ``above`` or at least
    ``least`` when given (a step of 0 ms divides by 0; a NaN threshold compares false with
    every reading). The one check of such parameters of the Python side.

    Raises:
        WrongTypeError: Not a real number (a bool is none either).
        InvalidArgumentError: NaN, infinite, or out of its range.
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise WrongTypeError(f"expected {name} to be a number, found {_a_type(value)}")
    number = float(value)
    if math.isfinite(number) and (above is None or number > above):
        if least is None or number >= least:
            return number
    bound = (
        f" above {above:g}"
        if above is not None
        else f" of at least {least:g}"
        if least is not None
        else ""
    )
    raise InvalidArgumentError(
        f"expected {name} to be a finite number{bound}, found {_shown(value)}"
    )
