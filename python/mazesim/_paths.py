"""Guards on the files a command reads and writes: inputs are regular files read within a bound
(:func:`open_input`, :func:`read_input`), and no command writes over one of its inputs."""

from __future__ import annotations

import argparse
import contextlib
import errno
import fcntl
import io
import os
import re
import shlex
import stat
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path
from typing import BinaryIO

from mazesim.errors import (
    InvalidArgumentError,
    MazesimError,
    MazesimIOError,
    UnknownNameError,
    _argument,
    _closest_name,
    _shown,
)
from mazesim.errors import _path_of as fs_path

__all__ = [
    "MAX_TEXT_CHARACTERS",
    "another_output_folder",
    "cache_folder",
    "file_name_of",
    "file_described",
    "found_kind",
    "fs_path",
    "make_output_folder",
    "open_input",
    "output_file",
    "output_files",
    "output_path",
    "read_input",
    "read_text",
    "refuse_overwriting_inputs",
    "refuse_replacing_world_file",
    "same_file",
    "shell_command",
    "unknown_name_or_file",
    "unknown_robot_profile",
    "utf8_text",
    "windows_separators",
    "world_files_beside",
    "writing_alone",
]


#: The most characters of a text file a command reads (a sweep file, a key script, a
#: randomisation file): far beyond any real one, and refused before an endless file such as
#: ``/dev/zero`` fills the memory.
MAX_TEXT_CHARACTERS = 64 * 1024 * 1024


def _kind_of(mode: int) -> str:
    """What a file that is not a regular file is, in words."""
    kinds = (
        (stat.S_ISDIR, "a folder"),
        (stat.S_ISFIFO, "a FIFO (named pipe)"),
        (stat.S_ISCHR, "a character device"),
        (stat.S_ISBLK, "a block device"),
        (stat.S_ISSOCK, "a socket"),
    )
    return next((word for test, word in kinds if test(mode)), "not a regular file")


def found_kind(data: bytes | str, expected: tuple[str, ...] = ()) -> str | None:
    """What kind of mazesim file ``data`` (a file's first bytes) is, with where such a file is
    taken ("a mazesim world file: pass it as a world (...)"), as the compiled core tells a
    file given for another kind; None when it is none of mazesim's kinds, or one of
    ``expected`` (the kinds the caller reads: a damaged one is refused for its damage)."""
    from mazesim._core import file_kind

    text = data if isinstance(data, str) else data[: 64 * 1024].decode("utf-8", "replace")
    kind = file_kind(text)
    return None if kind is None or kind[0] in expected else f"{kind[0]}: {kind[1]}"


def file_described(path: str | os.PathLike[str]) -> str:
    """What ``path`` is, in words, for a message saying it is not what was expected: "a folder",
    "a FIFO (named pipe)"..., a regular file by its kind ("a mazesim world file: pass it as a
    world (...)", :func:`found_kind`) or "a file"."""
    try:
        mode = os.stat(path).st_mode
    except (OSError, ValueError) as unreadable:
        return getattr(unreadable, "strerror", None) or str(unreadable)
    if not stat.S_ISREG(mode):
        return _kind_of(mode)
    try:
        with open_input(path, "the file") as handle:
            head = handle.read(64 * 1024)
    except MazesimIOError:
        return "a file"
    return found_kind(head) or "a file"


#: The most entries of a folder :func:`world_files_beside` looks at (a typo's suggestion is not
#: worth reading a huge folder for).
MAX_FOLDER_ENTRIES = 1000


def world_files_beside(path: str, suffixes: tuple[str, ...] = (".toml", ".wbt")) -> list[str]:
    """The world files (``.toml``, ``.wbt``, or the files of ``suffixes``) in the folder of
    ``path``, written as ``path`` would name them: the names a mistyped file may have meant.
    Empty when the folder cannot be read."""
    folder = os.path.dirname(path)
    names = []
    try:
        with os.scandir(folder or ".") as entries:
            for count, entry in enumerate(entries):
                if count >= MAX_FOLDER_ENTRIES:
                    break
                if entry.name.lower().endswith(suffixes):
                    names.append(os.path.join(folder, entry.name))
    except (OSError, ValueError):  # ValueError: a NUL character, which no folder's name holds
        return []
    return sorted(names)


def unknown_name_or_file(
    path: str,
    kind: str,
    available: list[str],
    files: str,
    suffixes: tuple[str, ...],
    context: str = "",
    folder_of_names: str | None = None,
) -> UnknownNameError:
    """The error for ``path`` that is neither the name of a built-in ``kind`` (one of
    ``available``) nor a file: it says what the path is or where it was looked for, lists the
    built-in names and ``files`` (what else is taken), and ends with the closest built-in name or
    file of ``suffixes`` beside it (a typo's likely fix). A relative path
    is looked for in ``folder_of_names`` (a sweep file's folder), else in the current folder.

    A name with a folder or a suffix (``maps/maze.toml``, ``maze.toml``) is a path: the message
    says which folder does not exist, or which folder lacks the file; a path with a folder is
    compared with the files beside it only, not with the built-in names. ``context`` opens the
    message (``"sweep.toml: grid.world: "``: where the name was given)."""
    folder, file = os.path.split(path)
    is_path = bool(folder) or bool(os.path.splitext(file)[1])
    base = folder_of_names or os.getcwd()
    where = "" if os.path.isabs(path) else f" in {base}"
    looked = os.path.join(folder_of_names, path) if folder_of_names else path
    try:
        found = f"it is {_kind_of(os.stat(looked).st_mode)}, not a {kind} file"
    except ValueError:  # a NUL character, which the system refuses before looking
        found = "no path holds a NUL character"
    except OSError as unreadable:
        found = unreadable.strerror.lower() if unreadable.strerror else "no such file"
        if unreadable.errno == errno.ENOENT and is_path:
            found = (
                f"there is no folder {_shown(folder)}{where}"
                if folder and not os.path.isdir(os.path.join(base, folder))
                else f"there is no file {_shown(file)} in "
                + (f"the folder {_shown(folder)}{where}" if folder else base)
            )
        elif not os.path.isabs(path):  # a relative path: say where it was looked for
            found = f"{found}{where}"
        found += windows_separators(path, base)
    opening = (
        f"no {kind} file {_shown(path)}: "
        if is_path
        else f"no built-in {kind} named {_shown(path)} and "
    )
    opening = context + opening
    unknown = UnknownNameError(
        f"{opening}{found}; built-in {kind}s: {', '.join(available)} (or a path to {files})",
        name=path,
        nearby=[
            os.path.relpath(beside, folder_of_names) if folder_of_names else beside
            for beside in world_files_beside(looked, suffixes)
        ]
        + ([] if folder else available),
    )
    unknown.available = available
    return unknown


def unknown_robot_profile(path: str) -> UnknownNameError:
    """The error for a ``robot`` that is neither a built-in profile's name nor a profile file."""
    from mazesim._core import robot_profile_names

    return unknown_name_or_file(
        path,
        "robot profile",
        sorted(robot_profile_names()),
        "a robot profile .toml file, such as RobotProfile.builtin('e-puck').to_toml() saved "
        "to a file and edited",
        (".toml",),
    )


def _read_failure(file: str, what: str, reason: str, number: int | None) -> MazesimIOError:
    where = _where_missing(file) if number == errno.ENOENT else ""
    failure = MazesimIOError(f"{file}: cannot read {what}: {reason}{where}")
    failure.errno = number
    failure.strerror = reason
    failure.filename = file
    return failure


def _where_missing(path: str) -> str:
    """What to add to "No such file or directory" for ``path``: the folder that does not exist,
    or the folder the file was looked for in, and the closest name of a file there (a typo's
    likely fix: ``boxs.wbt`` -> ``boxes.wbt``, ``avoid_collision`` -> ``avoid_collision.py``)."""
    folder, file = os.path.split(path)
    where = "" if os.path.isabs(path) else f" in {os.getcwd()}"
    if folder and not os.path.isdir(folder):
        return f": there is no folder {_shown(folder)}{where}"
    suffix = os.path.splitext(file)[1].lower()
    names = world_files_beside(path, (suffix,))  # "" (no suffix): every file
    meant = _closest_name(path, names)
    looked = f"the folder {_shown(folder)}{where}" if folder else os.getcwd()
    windows = windows_separators(path, os.getcwd())
    if windows:
        return f": there is no {_shown(file)} in {looked}{windows}"
    return f": there is no {_shown(file)} in {looked}" + (
        f"; did you mean {_shown(meant)}?" if meant else ""
    )


def windows_separators(path: str, base: str, *, written: bool = False) -> str:
    """What to add to a message about a path written with Windows' backslashes
    (``maps\\maze.toml``), which name no folder here: that folders are separated by '/', and
    the path so written when that file exists (``written``: when the folder it would be
    written into exists). Empty for any other path."""
    if "\\" not in path or os.sep == "\\":
        return ""
    meant = path.replace("\\", "/")
    there = os.path.exists(
        os.path.join(base, (os.path.dirname(meant) or ".") if written else meant)
    )
    return "; folders are separated by '/' here, not by '\\' as on Windows" + (
        f": did you mean {_shown(meant)}?" if there else ""
    )


def open_input(path: str | os.PathLike[str], what: str) -> BinaryIO:
    """Opens a file mazesim reads, for reading in binary: a regular file only.

    The file is opened without waiting (a FIFO no process writes to would otherwise block the
    open for ever, deaf to Ctrl-C), then looked at through the open descriptor: a folder, FIFO,
    device or socket is refused before a byte is read.

    Args:
        path: The file.
        what: What the file is, for messages (``"the run"``).

    Raises:
        MazesimIOError: The file cannot be opened, or is not a regular file (``filename`` is the
            path, ``strerror`` the reason).
    """
    file = fs_path(path, "path")  # as every path argument: bytes refused
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0)
    try:
        descriptor = os.open(file, flags | getattr(os, "O_BINARY", 0))
    except OSError as error:
        raise _read_failure(file, what, error.strerror or str(error), error.errno) from None
    except ValueError as error:  # a NUL in the path
        raise _read_failure(file, what, str(error), None) from None
    try:
        mode = os.fstat(descriptor).st_mode
        if not stat.S_ISREG(mode):
            raise _read_failure(
                file, what, f"expected a regular file, found {_kind_of(mode)}", errno.EINVAL
            )
        if hasattr(os, "O_NONBLOCK"):
            status = fcntl.fcntl(descriptor, fcntl.F_GETFL)
            fcntl.fcntl(descriptor, fcntl.F_SETFL, status & ~os.O_NONBLOCK)
        return os.fdopen(descriptor, "rb")
    except BaseException:
        os.close(descriptor)
        raise


#: Bytes read at a time by :func:`read_input`.
_READ_PIECE = 1024 * 1024


def read_input(path: str | os.PathLike[str], limit: int, what: str) -> bytes:
    """The bytes of a regular file mazesim reads (:func:`open_input`), at most ``limit + 1`` of
    them: a caller refuses a file whose result is longer than ``limit``.

    Raises:
        MazesimIOError: The file cannot be opened or read, or is not a regular file.
    """
    with open_input(path, what) as handle:
        try:
            # In pieces: one read of ``limit + 1`` bytes would reserve that much for any file.
            pieces: list[bytes] = []
            left = limit + 1
            while left > 0:
                piece = handle.read(min(left, _READ_PIECE))
                if not piece:
                    break
                pieces.append(piece)
                left -= len(piece)
            return b"".join(pieces)
        except OSError as error:
            file = os.fspath(path)
            raise _read_failure(file, what, error.strerror or str(error), error.errno) from None


def read_text(
    path: str | os.PathLike[str],
    what: str,
    not_text: Callable[[str], MazesimError] = InvalidArgumentError,
    most: int = MAX_TEXT_CHARACTERS,
) -> str:
    """The text of a UTF-8 file a command reads, of at most ``most`` characters
    (:data:`MAX_TEXT_CHARACTERS` unless its kind is smaller).

    A byte-order mark at its start (Windows editors write one) is not part of the text, as the
    world and robot profile readers leave it out too; a file in another encoding (UTF-16, as
    Windows Notepad's "Unicode" saves, or Latin-1) is refused saying which and to save it as
    UTF-8.

    Args:
        path: The file.
        what: What the file is, for messages (``"the key script"``).
        not_text: Builds the error for a file that is not UTF-8 text, or too long, from its
            message (:class:`~mazesim.errors.InvalidArgumentError` unless a format has its own).

    Raises:
        MazesimIOError: The file cannot be read, or is not a regular file (its ``filename`` is
            the path).
        MazesimError: What ``not_text`` builds, when the file is not UTF-8 text or too long.
    """
    file = os.fspath(path)
    try:
        with io.TextIOWrapper(open_input(file, what), encoding="utf-8-sig") as handle:
            text = handle.read(most + 1)
    except UnicodeDecodeError as error:
        raise not_text(_not_utf8(file, what, error)) from None
    except MazesimIOError:
        raise
    except OSError as error:
        raise _read_failure(file, what, error.strerror or str(error), error.errno) from None
    if len(text) > most:
        raise not_text(f"{file}: expected {what} of at most {most} characters, found more")
    return text


def utf8_text(data: bytes, file: str, what: str, not_text: Callable[[str], MazesimError]) -> str:
    """The text of a file's ``data`` read whole, as :func:`read_text` reads a file: a byte-order
    mark at its start left out, and a file in another encoding refused by ``not_text`` saying
    which (the one rule of every reader of text files, those that read the bytes first too)."""
    try:
        return data.removeprefix(b"\xef\xbb\xbf").decode("utf-8")
    except UnicodeDecodeError as error:
        raise not_text(_not_utf8(file, what, error)) from None


def _not_utf8(file: str, what: str, error: UnicodeDecodeError) -> str:
    return (
        f"{file}: expected {what} in UTF-8 text, found {_other_encoding(error)}: save it as "
        'UTF-8 (an editor\'s "Save as", encoding UTF-8) and give it again'
    )


def _other_encoding(error: UnicodeDecodeError) -> str:
    """What a text that is not UTF-8 looks like, from where its decoding failed."""
    start = bytes(error.object[:2])
    if error.start < 2 and start in (b"\xff\xfe", b"\xfe\xff"):
        return f"UTF-16 text (it starts with the byte-order mark {start.hex(' ').upper()})"
    byte = error.object[error.start]
    return (
        f"a byte 0x{byte:02X} that is not UTF-8 (text in another encoding, such as Latin-1 or "
        "Windows-1252?)"
    )


def shell_command(*words: str | os.PathLike[str]) -> str:
    """A command as a person copies it into a shell: each word quoted as a POSIX shell needs
    (``mazesim eval --policy 'my navigator'``), so that a path holding spaces, quotes or
    non-ASCII letters stays one word; plain words are written as they are."""
    return shlex.join(os.fspath(word) for word in words)


def same_file(first: str | os.PathLike[str], second: str | os.PathLike[str]) -> bool:
    """Whether two paths name one existing file, whatever their spelling (relative or absolute,
    ``..``, symbolic or hard links, case on case-insensitive disks)."""
    try:
        return os.path.samefile(first, second)
    except (OSError, ValueError):
        return False


def _same_target(first: str | os.PathLike[str], second: str | os.PathLike[str]) -> bool:
    """Whether two paths would write one file, whether it exists yet or not: the same file, or
    the same path once ``..``, symbolic links and case (where the disk ignores it) are
    resolved."""
    if same_file(first, second):
        return True
    try:
        return os.path.normcase(os.path.realpath(first)) == os.path.normcase(
            os.path.realpath(second)
        )
    except (OSError, ValueError):
        return False


def refuse_overwriting_inputs(
    outputs: Iterable[tuple[str, str | os.PathLike[str] | None]],
    inputs: Iterable[tuple[str, str | os.PathLike[str] | None]],
) -> None:
    """Raises when a file a command would write is one of the files it reads, or another of the
    files it writes.

    Args:
        outputs: (what it is, path) of each file the command writes, e.g.
            ``("--out", "x.toml")``; None paths are skipped.
        inputs: (what it is, path) of each file or folder the command reads.

    Raises:
        InvalidArgumentError: An output is an input, or two outputs are one file (the message
            names both and what to do), or an output file is a folder.
    """
    read = [(label, path) for label, path in inputs if path is not None]
    written: list[tuple[str, str | os.PathLike[str]]] = []
    for out_label, out_path in outputs:
        if out_path is None:
            continue
        if os.path.isdir(out_path):
            raise InvalidArgumentError(
                f"{out_label} {_shown(os.fspath(out_path))} is a folder; expected the path of "
                "a file"
            )
        clashes = [
            (label, path, "; mazesim does not write over its own input:")
            for label, path in read
            if same_file(out_path, path)
        ]
        clashes += [
            (label, path, ", which this command writes too:")
            for label, path in written
            if _same_target(out_path, path)
        ]
        if clashes:
            label, path, why = clashes[0]
            raise InvalidArgumentError(
                f"{out_label} {_shown(os.fspath(out_path))} is the same file as {label} "
                f"{_shown(os.fspath(path))}{why} choose another {out_label}"
            )
        written.append((out_label, out_path))


def refuse_replacing_world_file(file: str | os.PathLike[str], force: bool) -> None:
    """Raises when a command would replace a world file that exists and ``force`` (``--force``)
    is False. The one rule of every command that writes a world file (``worlds --export``,
    ``import-wbt --out``): a world file is one its user edits, so an existing one is kept unless
    asked; what a command makes again from its inputs (pictures, replays, videos, the files of a
    run folder) is replaced. A device or a pipe (``/dev/stdout``) holds nothing to lose.

    Raises:
        MazesimIOError: ``file`` is an existing file (or a link to one) and ``force`` is False.
    """
    if not force and os.path.isfile(file):
        raise MazesimIOError(
            f"{os.fspath(file)} exists: name another file, or add --force to overwrite it (a "
            "world file is one you edit: mazesim never replaces one unasked)"
        )


def file_name_of(name: str, suffix: str) -> str:
    """A plain file name made from a name the user's files chose (a world's ``name``): no folder
    parts, no leading dot, only letters, digits, ``-``, ``_`` and ``.``; ``"world"`` if nothing
    is left. ``file_name_of("../x y", ".png")`` is ``"x-y.png"``."""
    plain = re.sub(r"[^A-Za-z0-9._-]+", "-", os.path.basename(name.replace("\\", "/")))
    return (plain.lstrip(".-") or "world") + suffix


def output_files(
    folder: str | os.PathLike[str], names: Iterable[str]
) -> list[tuple[str, str | os.PathLike[str] | None]]:
    """(what it is, path) of the files a command writes into its output folder."""
    return [(f"the output {name}", os.path.join(folder, name)) for name in names]


def output_path(text: str) -> str:
    """A path to write to, as a command-line argument type: not empty (an empty path would
    quietly mean the current folder), without NUL characters, and without Windows' backslashes
    between folders (``-o out\\maze.png`` would write a file of that name beside ``out/``)."""
    if not text or "\0" in text:
        raise argparse.ArgumentTypeError(f"expected a path to write to, found {_shown(text)}")
    windows = windows_separators(text, os.getcwd(), written=True)
    if windows:
        raise argparse.ArgumentTypeError(
            f"expected a path to write to, found {_shown(text)}{windows}"
        )
    return text


def output_file(text: str) -> str:
    """The path of a file to write, as a command-line argument type: :func:`output_path`, not a
    folder, and not below a file (its missing folders are made when it is written)."""
    output_path(text)
    if os.path.isdir(text):
        raise argparse.ArgumentTypeError(
            f"expected the path of a file to write, found the folder {_shown(text)}"
        )
    parent = os.path.dirname(os.path.abspath(text))
    while not os.path.exists(parent) and os.path.dirname(parent) != parent:
        parent = os.path.dirname(parent)
    if not os.path.isdir(parent):
        raise argparse.ArgumentTypeError(
            f"expected a path to write to, found {_shown(text)}, below {_shown(parent)}, which "
            "is a file"
        )
    return text


def make_output_folder(folder: str | os.PathLike[str], parameter: str = "folder") -> None:
    """Makes the output folder ``folder`` and its parents, unless it is a folder already.

    Every command and function that writes into a folder makes it here, so that a path that is
    something else (a file, ``/dev/full``, a FIFO) or cannot be made is refused saying what was
    expected and what was found, not with the system's bare "File exists", and what to change:
    ``--out`` on the command line, else ``parameter``, the caller's parameter that named the
    folder (:func:`mazesim.errors._argument`).

    Raises:
        MazesimIOError: ``folder`` is not a folder, or it cannot be made.
    """
    path = os.fspath(folder)
    try:
        os.makedirs(path, exist_ok=True)
    except FileExistsError as error:
        if not os.path.exists(path):
            kind = "a symbolic link to nothing"
        else:
            mode = os.stat(path).st_mode
            kind = "a file" if stat.S_ISREG(mode) else _kind_of(mode)
        found = f"expected an output folder, found {kind}"
        raise _folder_failure(path, found, error, parameter) from None
    except OSError as error:
        reason = f"cannot make the output folder: {error.strerror or error}"
        raise _folder_failure(path, reason, error, parameter) from None


def cache_folder(variable: str, name: str, *, under_variable: bool = False) -> Path:
    """The folder mazesim caches ``name`` in (built controllers, downloaded PROTOs):
    ``$variable`` if set (``$variable/name`` when ``under_variable``: a variable naming
    mazesim's whole cache), else ``$XDG_CACHE_HOME/mazesim/name``, else
    ``~/.cache/mazesim/name``.

    Raises:
        MazesimIOError: The folder, or one above it, is a file or another thing that is not a
            folder: the message names the variable that set it, what is there and what to do.
    """
    configured = os.environ.get(variable)
    if configured:
        folder = Path(configured) / name if under_variable else Path(configured)
        setting = f"${variable}"
    else:
        xdg = os.environ.get("XDG_CACHE_HOME")
        base = Path(xdg) if xdg else Path(os.path.expanduser("~")) / ".cache"
        folder = base / "mazesim" / name
        setting = "$XDG_CACHE_HOME" if xdg else "the default cache"
    for above in (folder, *folder.parents):
        try:
            mode = os.stat(above).st_mode
        except OSError:
            continue
        if stat.S_ISDIR(mode):
            return folder
        kind = "a file" if stat.S_ISREG(mode) else _kind_of(mode)
        what = "it" if above == folder else f"above it, {above},"
        raise MazesimIOError(
            f"{setting} names {folder} as the folder of cached {name}, but {what} is {kind}, "
            f"not a folder: set {variable} to a folder (or unset it)"
        )
    return folder


def _folder_failure(path: str, reason: str, error: OSError, parameter: str) -> MazesimIOError:
    failure = MazesimIOError(f"{path}: {reason}; {another_output_folder(parameter)}")
    failure.errno, failure.strerror, failure.filename = error.errno, error.strerror, path
    return failure


def another_output_folder(parameter: str) -> str:
    """What to do about an output folder that cannot be used: choose another ``--out`` (on the
    command line), or another ``parameter`` (in Python)."""
    return f"choose another {_argument('--out', parameter)}"


@contextlib.contextmanager
def writing_alone(
    folder: str | os.PathLike[str], command: str, create: bool = True
) -> Iterator[None]:
    """Holds an exclusive lock on ``folder`` while ``command`` writes into it.

    A second command into the same folder (a run started twice by mistake) is refused at once
    instead of interleaving its checkpoints and tables with the first's. The lock is the
    operating system's advisory lock on the folder itself (``flock``): no file is left behind,
    and it is released when the command ends, however it ends (a crash or a kill too).

    Args:
        folder: The output folder; made if missing and ``create``.
        command: The command, for the message (e.g. ``"mazesim train"``).
        create: Make the folder when it does not exist; when False and it does not exist,
            nothing is locked (the command refuses the missing folder itself).

    Raises:
        MazesimIOError: Another process holds the folder, or it cannot be made or opened.
    """
    path = os.fspath(folder)
    if not os.path.isdir(path):
        if not create and not os.path.lexists(path):
            yield
            return
        make_output_folder(path)
    try:
        handle = os.open(path, os.O_RDONLY | os.O_DIRECTORY)
    except OSError as error:
        raise MazesimIOError(f"{path}: cannot open the output folder: {error.strerror}") from error
    try:
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            raise MazesimIOError(
                f"{path}: another process is writing into this folder (a {command} started "
                f"twice?); wait for it to end, or {another_output_folder('folder')}"
            ) from None
        yield
    finally:
        os.close(handle)
