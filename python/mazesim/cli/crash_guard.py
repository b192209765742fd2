"""A watch for the one command that runs a user's code in its own process: ``mazesim webots run
CONTROLLER.py`` runs the Python controller in the command's process (a world run, ``mazesim webots
run WORLD.wbt``, gives each controller a process of its own, and says when one crashes). Native
code the controller calls (``ctypes``, a broken extension) can kill that process with a signal,
which no ``except`` catches: the command then ended without a word of its own.

From the command line (:func:`mazesim.cli.main` without ``argv``) that command first forks a
watcher, which does nothing but wait on a pipe. The command says it ended by writing to that pipe
as it returns; should the pipe close without that word (the process died), the watcher says so
on stderr, as a world run says it of a controller ("the Python controller crashed"). The command
keeps its process, its signals and its exit status (a shell shows 139 for a segmentation fault);
the outputs it wrote before are whole (each file is written atomically), those it would write
at its end are not written.
"""

from __future__ import annotations

import atexit
import os
import signal
from collections.abc import Sequence

__all__ = ["CrashWatch", "runs_a_controller_here"]

#: What the command writes to the watcher's pipe as it ends by itself.
ENDED = b"ended"
#: What the watcher says when the command's process died without that word.
CRASH_MESSAGE = (
    "mazesim: error: the Python controller crashed the run's process (native code it called "
    "failed, as in a C extension or ctypes, or a signal killed it); the files the run wrote "
    "before are whole, those of its end were not written\n"
)


def runs_a_controller_here(arguments: Sequence[str]) -> bool:
    """Whether the command line ``arguments`` (after the program name) runs a controller in
    this process: ``webots run`` with a controller rather than a ``.wbt`` world, not asking for
    help."""
    if list(arguments[:2]) != ["webots", "run"]:
        return False
    rest = list(arguments[2:])
    if any(a in ("-h", "--help") for a in rest):
        return False
    return not any(
        a.lower().endswith(".wbt") and not a.startswith("-") and rest[i - 1 : i] != ["--world"]
        for i, a in enumerate(rest)
    )


class CrashWatch:
    """The watcher of one command (see the module): made before the command runs,
    :meth:`ended` called however it ends by itself. A process that ends normally without
    calling it (a watch made outside the command) says it ended at its exit; a process forked
    from the command's (a controller's ``os.fork``) never speaks for it."""

    def __init__(self) -> None:
        self._pipe: int | None = None
        self._owner = os.getpid()
        if not hasattr(os, "fork"):  # a system without fork (Windows): the command runs unwatched
            return
        try:
            read_end, write_end = os.pipe()
            pid = os.fork()
        except OSError:  # no process or descriptor to spare: the command runs unwatched
            return
        if pid == 0:
            os.close(write_end)
            _watch(read_end)
        os.close(read_end)
        self._pipe = write_end
        atexit.register(self.ended)

    def ended(self) -> None:
        """Tells the watcher that the command ended by itself (its exit status is its own); in a
        process forked from the command's, only lets go of that process's end of the pipe."""
        if self._pipe is None:
            return
        try:
            if os.getpid() == self._owner:
                os.write(self._pipe, ENDED)
            os.close(self._pipe)
        except OSError:
            pass
        self._pipe = None
        atexit.unregister(self.ended)


def _watch(pipe: int) -> None:
    """The watcher's whole life: waits for the pipe to close, says a crash if the command did
    not say it ended, and exits. It holds no terminal input or output but stderr, so that a
    reader of the command's output sees its end when the command ends."""
    status = 0
    try:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the command's to handle
        for descriptor in (0, 1):
            try:
                os.close(descriptor)
            except OSError:
                pass
        said = b""
        while True:
            chunk = os.read(pipe, 64)
            if not chunk:
                break
            said += chunk
        if said != ENDED:
            os.write(2, CRASH_MESSAGE.encode())
    except BaseException:  # noqa: BLE001 - the watcher never runs the command's code
        status = 1
    os._exit(status)
