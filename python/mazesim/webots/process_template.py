"""The template process a world's controller processes are forked from.

A world of many robots starts one controller process per robot (:mod:`mazesim.webots.lockstep`).
A fresh Python process spends about 0.4 s of processor time importing mazesim, numpy and the
controller API before the controller's first line runs; forty of them took 17 s of it on a
2-core machine (``benches/webots_startup.py``, docs/performance.md). Instead, a run of a world
starts one template process, which imports all that once and then forks one child per
controller: each child starts with everything imported, and behaves as a fresh process started
for that controller would:

- its import path (``sys.path``), working folder and environment are the world's process's at the
  run's start (the controller's own folder, ``sys.argv`` and ``WEBOTS_HOME`` are then set by
  :func:`~mazesim.webots.runner.run_controller`, as in a fresh process);
- its standard output and error are the world's process's, unprefixed, each written a whole line
  at a time (as Webots reads each controller's output line by line, the lines of controllers
  printing at once never mix, even where ``PYTHONUNBUFFERED`` is set), and its standard input
  is empty;
- it ignores Ctrl-C (and so do the programs it starts, a compiled controller): the world's
  process ends every controller's run on Ctrl-C, at a step, as a supervisor's quit does, so that
  no controller stops in the middle of a call to the world's process; ``random`` and numpy's
  global generator are seeded anew (each child draws its own numbers, as fresh processes
  would);
- it ends as a Python program ends (its threads joined, its ``atexit`` functions run).

The template holds a copy of each child's end of its pipe until the child has ended, then writes
on it ``("exit", status, words)``: the child's exit status as :func:`os.waitstatus_to_exitcode`
gives it (minus the signal's number for a child killed by a signal) and what the child left in its
:class:`LastWords` (why it could not report its end, or ""). A child that ends without its report
(``os._exit``, killed, crashed in native code, its pipe closed) is so reported by how it really
ended; the world's process reads the message after whatever the child wrote, and stops reading a
child's pipe once the child has reported its end.

The template itself never runs a controller. It ignores Ctrl-C (the world's process tells it when
the run is over), waits for its children at the end and kills those still running
``exit_wait_seconds`` later, then exits.

The protocol, over a pipe from the world's process (``multiprocessing.connection``):
``("start", job)`` followed by the controller's end of its own pipe (passed as a file descriptor)
forks a child that runs :func:`~mazesim.webots.controller_process.controller_main` on them;
``("finish", exit_wait_seconds)`` (or the pipe's end) ends the template.
"""

from __future__ import annotations

import contextlib
import gc
import io
import json
import mmap
import os
import signal
import socket
import subprocess
import sys
import time
import warnings
from multiprocessing import reduction
from multiprocessing.connection import Connection, wait
from typing import Any

__all__ = ["ControllerProcesses", "LastWords", "serve"]

#: The template's program: the world's process's import path, then :func:`serve`; in a child it
#: goes on to run the controller and ends as a Python program ends.
_PROGRAM = (
    "import json, sys\n"
    "sys.path[:] = json.loads(sys.argv[2])\n"
    "from mazesim.webots.process_template import serve\n"
    "from mazesim.webots.controller_process import controller_main\n"
    "controller_main(*serve(int(sys.argv[1])))\n"
)
#: Real seconds the world's process waits for the template to end beyond its children's wait.
_TEMPLATE_EXIT_MARGIN_SECONDS = 5.0


class ControllerProcesses:
    """The world's side: starts the template, then a controller process per :meth:`start`.

    Example::

        processes = ControllerProcesses()
        connection = processes.start(job)  # the world's end of the controller's pipe
        ...
        processes.finish(5.0)
    """

    def __init__(self) -> None:
        ours, template_end = socket.socketpair()
        flags = subprocess._args_from_interpreter_flags()  # type: ignore[attr-defined]
        with template_end:
            self._process = subprocess.Popen(
                [
                    sys.executable,
                    *flags,
                    "-c",
                    _PROGRAM,
                    str(template_end.fileno()),
                    json.dumps(sys.path),
                ],
                pass_fds=[template_end.fileno()],
                stdin=subprocess.DEVNULL,
            )
        self._control = Connection(ours.detach())

    @property
    def pid(self) -> int:
        """The template's process id (the parent of every controller process)."""
        return self._process.pid

    def start(self, job: Any) -> Connection:
        """Forks a controller process for ``job``; returns the world's end of its pipe.

        If the template has ended (it could not import mazesim), the pipe's other end is closed
        at once: the controller counts as a process that ended without a report.
        """
        ours, theirs = socket.socketpair()
        with theirs:
            try:
                self._control.send(("start", job))
                reduction.send_handle(self._control, theirs.fileno(), self._process.pid)
            except OSError:
                pass
        return Connection(ours.detach())

    def finish(self, exit_wait_seconds: float) -> None:
        """Tells the template that the run is over; it waits ``exit_wait_seconds`` for its
        children, kills those still running and ends."""
        try:
            self._control.send(("finish", exit_wait_seconds))
        except OSError:
            pass
        self._control.close()
        try:
            self._process.wait(exit_wait_seconds + _TEMPLATE_EXIT_MARGIN_SECONDS)
        except subprocess.TimeoutExpired:
            self._process.kill()
            self._process.wait()


def _preload() -> None:
    """Imports what every controller process runs on: the controller API, the world import with
    its PROTO engine (which it imports when first called) and the runner (and, through them,
    mazesim and numpy)."""
    from mazesim.webots import controller, importer, proto, runner, scene  # noqa: F401


class LastWords:
    """A few bytes of memory a child shares with the template (not a file descriptor, which the
    controller may close): where the child's process says why it could not report its end over
    its pipe. The first words said are kept."""

    #: Bytes of the region (a length, then the words in UTF-8).
    SIZE = 4096

    def __init__(self) -> None:
        self._region = mmap.mmap(-1, self.SIZE)

    def say(self, words: str) -> None:
        """Leaves ``words`` (cut to what the region holds), unless words were left already."""
        if self.read():
            return
        data = words.encode("utf-8", "replace")[: self.SIZE - 4]
        self._region[4 : 4 + len(data)] = data
        self._region[:4] = len(data).to_bytes(4, "little")

    def read(self) -> str:
        """The words left, or ""."""
        size = min(int.from_bytes(self._region[:4], "little"), self.SIZE - 4)
        return self._region[4 : 4 + size].decode("utf-8", "replace")

    def close(self) -> None:
        """Unmaps the region (in this process)."""
        self._region.close()


def serve(fd: int) -> tuple[Connection, Any, LastWords]:
    """The template's loop on the pipe of file descriptor ``fd``; returns only in a child, with
    the controller's pipe, job and :class:`LastWords` (the template exits when the run is
    over)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    control = Connection(fd)
    _preload()
    # A child's end wakes the loop (the signal's handler does nothing: the byte Python writes
    # for it on the wake-up pipe does).
    awake, waking = os.pipe()
    os.set_blocking(awake, False)
    os.set_blocking(waking, False)
    signal.set_wakeup_fd(waking)
    signal.signal(signal.SIGCHLD, lambda signum, frame: None)
    children: dict[int, tuple[Connection, LastWords]] = {}
    exit_wait_seconds = 0.0
    while True:
        ready = wait([control, awake])
        if awake in ready:
            with contextlib.suppress(OSError):
                os.read(awake, 512)
        _reap(children, block=False)
        if control not in ready:
            continue
        try:
            message = control.recv()
        except (EOFError, OSError):
            break
        if message[0] == "finish":
            exit_wait_seconds = float(message[1])
            break
        job = message[1]
        handle = reduction.recv_handle(control)
        words = LastWords()
        # What the template holds is never collected by the child's garbage collector, so the
        # child does not copy the memory it shares with the template to mark it (the child's
        # own objects are collected as ever).
        gc.freeze()
        with warnings.catch_warnings():
            # Python 3.12 and later warn about forking a process that has threads: the template's
            # only other threads are numpy's BLAS workers, which OpenBLAS stops before a fork
            # (its pthread_atfork handler) and starts again in the child when it needs them.
            warnings.simplefilter("ignore", DeprecationWarning)
            child = os.fork()
        if child == 0:
            control.close()
            # The other children's pipes and words are not this child's.
            for link, said in children.values():
                link.close()
                said.close()
            signal.set_wakeup_fd(-1)
            signal.signal(signal.SIGCHLD, signal.SIG_DFL)
            os.close(awake)
            os.close(waking)
            _become_fresh()
            return Connection(handle), job, words
        children[child] = (Connection(handle), words)
    control.close()
    deadline = time.monotonic() + exit_wait_seconds
    while children and time.monotonic() < deadline:
        _reap(children, block=False)
        time.sleep(0.01)
    for child in children:
        os.kill(child, signal.SIGKILL)
    _reap(children, block=True)
    sys.exit(0)


def _become_fresh() -> None:
    """What a fresh process would have that a forked one does not: random streams of its own
    (``random`` reseeds itself after a fork; numpy does not), and standard output and error
    that write whole lines. Ctrl-C stays ignored, as in the template: the world's process ends
    the run (:class:`~mazesim.webots.lockstep.Interruption`)."""
    numpy_random = sys.modules.get("numpy.random")
    if numpy_random is not None:
        numpy_random.seed()
    sys.stdout = _whole_lines(sys.stdout, 1)
    sys.stderr = _whole_lines(sys.stderr, 2)


def _whole_lines(stream: Any, fd: int) -> Any:
    """``stream`` (of file descriptor ``fd``) rewritten to hand each line to the system in one
    write, so that the lines of controllers printing at once do not mix: unbuffered
    (``PYTHONUNBUFFERED``), a ``print`` of several values writes each piece apart."""
    stream.flush()
    return io.TextIOWrapper(
        io.BufferedWriter(io.FileIO(fd, "w", closefd=False)),
        encoding=stream.encoding,
        errors=stream.errors,
        line_buffering=True,
    )


def _reap(children: dict[int, tuple[Connection, LastWords]], *, block: bool) -> None:
    """Collects the children that have ended (all of them, waiting, when ``block``), and writes
    on each one's pipe how it ended: ``("exit", status, words)``."""
    for child, (link, words) in list(children.items()):
        try:
            done, status = os.waitpid(child, 0 if block else os.WNOHANG)
        except ChildProcessError:
            done, status = child, 0
        if not done:
            continue
        del children[child]
        # Never waits on a world's process that does not read (it has stopped listening to a
        # child that reported its end).
        os.set_blocking(link.fileno(), False)
        with contextlib.suppress(OSError):
            link.send(("exit", os.waitstatus_to_exitcode(status), words.read()))
        link.close()
        words.close()
