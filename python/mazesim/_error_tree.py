"""Puts an exception that reaches mazesim's public surface into the package's one error tree.

The argument check (:mod:`mazesim._checks`) calls :func:`in_the_tree` when a public function or
method ends with an exception that is not a :class:`~mazesim.errors.MazesimError`. What it gives
instead, chained to the original (``__cause__``, whose traceback a bug report needs):

- a built-in argument failure (``ValueError``, ``TypeError``, ``IndexError``, ``KeyError``...)
  whose arguments fit their annotations (those that do not were named by the check already):
  :class:`~mazesim.errors.InvalidArgumentError`, saying what the function found wrong (numpy's
  "operands could not be broadcast together with shapes (3,) (11,)" for an array of the wrong
  shape, which no annotation says);
- an ``OSError``: :class:`~mazesim.errors.MazesimIOError`, naming the file and the system's
  reason, with ``errno``, ``strerror`` and ``filename`` kept;
- anything else raised by mazesim or a library it calls (an ``AssertionError``, a
  ``NotImplementedError``, a library's own exception): :class:`~mazesim.errors.InternalError`,
  "internal error, please report".

Each is also an instance of the original exception's class when that is a built-in one and Python
allows it (``except KeyError`` around a call keeps working), and pickles as such.

Left as they are: ``KeyboardInterrupt``, ``SystemExit`` and other ``BaseException``\\ s that are
not errors, warnings turned into errors, ``StopIteration``, gymnasium's own protocol errors
(documented), and an exception raised in the caller's own code (a callback, a value's
``__len__``): that one is the caller's, not mazesim's.
"""

from __future__ import annotations

import functools
import os
import sys
import sysconfig
from typing import Any

from mazesim.errors import InternalError, InvalidArgumentError, MazesimError, MazesimIOError

__all__ = ["in_the_tree", "io_error", "made_as"]

#: The longest part of an original message quoted (a message may quote a huge value).
QUOTED_CHARACTERS = 300

#: Folders that hold installed packages, wherever they are on ``sys.path``.
_PACKAGE_FOLDERS = ("site-packages", "dist-packages")

#: Folders of code that is mazesim's or a library's: an exception raised elsewhere was raised by
#: the caller's own code.
_LIBRARY_FOLDERS = tuple(
    os.path.realpath(folder) + os.sep
    for folder in {
        os.path.dirname(os.path.abspath(__file__)),
        *(sysconfig.get_paths().get(k, "") for k in ("stdlib", "platstdlib", "purelib", "platlib")),
        # Packages outside the environment it reads too (Debian's ROS 1 in dist-packages).
        *(p for p in sys.path if os.path.basename(p.rstrip(os.sep)) in _PACKAGE_FOLDERS),
    }
    if folder
)


def _raised_by_library(error: BaseException) -> bool:
    """Whether the innermost frame of ``error``'s traceback is mazesim's or a library's (or
    compiled code's)."""
    trace = error.__traceback__
    if trace is None:
        return True
    while trace.tb_next is not None:
        trace = trace.tb_next
    frame = trace.tb_frame
    file = frame.f_code.co_filename
    if file.startswith("<") and not file.startswith("<frozen"):
        # Code without a file of its own: the caller's typed at the prompt (``<stdin>``), given
        # to ``python -c`` or exec'd (``<string>``), or code a module generated (a dataclass's
        # methods), whose globals are its module's: the module's file says whose it is.
        module = sys.modules.get(frame.f_globals.get("__name__", ""))
        origin = getattr(module, "__file__", None)
        return isinstance(origin, str) and _in_library(origin)
    if file.startswith("<") or not os.path.isabs(file):
        return True  # frozen modules, compiled extensions (numpy's .pyx)
    return _in_library(file)


def _in_library(file: str) -> bool:
    """Whether ``file`` is mazesim's or an installed library's."""
    return os.path.realpath(file).startswith(_LIBRARY_FOLDERS)


def _rebuild(tree: type, kind: type, args: tuple[Any, ...]) -> Any:
    return made_as(tree, kind, *args) if len(args) == 1 else tree(*args)


@functools.cache
def _both(tree: type, kind: type) -> type:
    """A class that is ``tree`` (of the package) and ``kind`` (the original's), or ``tree`` alone
    when Python cannot make one of both (their layouts differ)."""
    if issubclass(tree, kind) or kind.__module__ != "builtins":
        return tree  # a library's own class may need what its constructor sets
    try:
        made = type(tree.__name__, (tree, kind), {"__module__": tree.__module__})
    except TypeError:
        return tree
    made.__qualname__ = tree.__qualname__
    made.__doc__ = tree.__doc__

    def reduce(self: BaseException) -> tuple[Any, ...]:
        return (_rebuild, (tree, kind, self.args))

    made.__reduce__ = reduce  # type: ignore[method-assign,assignment]
    return made


def made_as(tree: type, kind: type, message: str) -> Any:
    """A ``tree`` error that is also a ``kind`` if it can be made with just a message."""
    try:
        return _both(tree, kind)(message)
    except Exception:  # noqa: BLE001 - the original class wants other arguments
        return tree(message)


def _quoted(error: BaseException) -> str:
    text = str(error)
    if len(text) > QUOTED_CHARACTERS:
        text = text[:QUOTED_CHARACTERS] + f"... ({len(text)} characters)"
    return f"{type(error).__name__}: {text}" if text else type(error).__name__


def io_error(error: OSError, where: str = "") -> MazesimIOError:
    """``error`` as a :class:`~mazesim.errors.MazesimIOError` whose message is the file and the
    system's reason ("/dev/null: File exists", not "[Errno 17] File exists: '/dev/null'"), or
    ``where`` and the reason when the system named no file (the reason alone without either);
    itself if it is one already."""
    if isinstance(error, MazesimIOError):
        return error
    name = error.filename if error.filename is not None else where
    reason = error.strerror or _quoted(error)
    made = made_as(MazesimIOError, type(error), f"{name}: {reason}" if name else reason)
    made.errno, made.strerror, made.filename = error.errno, reason, error.filename
    return made


def _left_alone(error: BaseException) -> bool:
    if not isinstance(error, Exception):
        return True  # KeyboardInterrupt, SystemExit, GeneratorExit
    if isinstance(error, (MazesimError, Warning, StopIteration)):
        return True
    if type(error).__module__.split(".")[0] == "gymnasium":
        return True  # gymnasium's protocol errors, documented
    return not _raised_by_library(error)


def in_the_tree(
    where: str, error: BaseException, argument_failure: bool, given: str = ""
) -> BaseException:
    """The exception to raise instead of ``error``, which ended the public function ``where``
    (its qualified name); ``error`` itself when it is left alone. ``argument_failure``: the
    error is a built-in argument failure whose arguments fit their annotations; ``given``: what
    the arguments were expected to be and were ("expected x: float; found x=nan"), said after
    the failure."""
    if _left_alone(error):
        return error
    if isinstance(error, OSError):
        return io_error(error, where)
    if isinstance(error, MemoryError):
        # Not an argument of the wrong kind, nor a fault to report: the input is too large for
        # the memory the process has.
        message = (
            f"{where}: ran out of memory ({_quoted(error)}): expected an input that fits the "
            "process's memory; give a smaller one, or run with more memory"
        )
        return made_as(InternalError, MemoryError, message)
    if argument_failure:
        message = f"{where}: the arguments do not fit: {_quoted(error)}"
        if given:
            message += f"; {given}"
        return made_as(InvalidArgumentError, type(error), message)
    message = f"{where}: internal error, please report: {_quoted(error)}"
    return made_as(InternalError, type(error), message)
