"""Ending a controller that goes on after its run has ended, as Webots does.

In Webots, once ``Robot.step`` has returned -1 the controller has one second of real time to save
its data before Webots kills its process (Webots User Guide, "Controller Programming",
"Controller Termination"). mazesim runs the controller inside its own process, so it cannot kill
it; instead, a call to ``Robot.step`` after the end raises
:class:`~mazesim.webots.robot.ControllerStopped`, and one made more than
:data:`GRACE_SECONDS` after the end also makes every frame of the controller's code raise it at
its next line. A controller that catches everything (``while True: try: robot.step(32)
except: pass``), at any number of function levels, is unwound all the same: the exception raised
in an ``except`` block is not caught by that block.
:func:`~mazesim.webots.runner.run_controller` ends the unwinding when the controller's code has
been left.

A controller that never calls the API again (``while True: pass`` after the end, or before its
first step) is ended by a :class:`Watchdog`: a thread that watches the run's clock and, when the
grace after the end has passed or no step was taken for :data:`STALL_SECONDS` of real time, raises
the same exception in the controller's thread (CPython's asynchronous exceptions, delivered
between two bytecodes) and starts the same unwinding there. A thread rather than a child process
keeps the controller in the caller's process (its modules, its ``sys.path``, the simulation it
steps) and rather than a signal leaves the caller's signal handlers alone and works on any thread.
Code blocked inside one C call (a ``sleep`` of an hour, a read of a pipe) is ended when that call
returns.
"""

from __future__ import annotations

import ctypes
import os
import sys
import threading
import time
from types import FrameType
from typing import Any, Protocol

__all__ = ["GRACE_SECONDS", "STALL_SECONDS", "Watchdog"]

#: Real seconds a controller may go on after ``Robot.step`` returned -1, as in Webots.
GRACE_SECONDS = 1.0
#: Real seconds a controller may run without taking a step before the end (its set-up before the
#: first step included) before it is stopped.
STALL_SECONDS = 60.0
#: How often the watchdog looks at the run (seconds).
_POLL_SECONDS = 0.05

#: mazesim's own code, which is not unwound (it raises the exception itself).
_PACKAGE = os.path.dirname(os.path.dirname(os.path.abspath(__file__))) + os.sep
#: The trace and profile functions set before the unwinding, restored after it (a coverage
#: tool's, a debugger's).
_previous: list[tuple[Any, Any]] = []


def is_controllers(frame: FrameType) -> bool:
    """Whether ``frame`` runs the controller's code (any code but mazesim's own)."""
    return not os.path.abspath(frame.f_code.co_filename).startswith(_PACKAGE)


def unwind_controller(stop: type[BaseException], message: str) -> None:
    """Makes each frame of the controller's code on this thread, and each it calls from now on,
    raise ``stop(message)`` at its next line, until :func:`end_unwinding`.

    Python stops tracing a thread whose trace function raised; a profile function, which never
    raises, sets the tracing again at the next call or return (the frame that caught the
    exception is then unwound too, however many levels catch everything).
    """

    def at_each_line(frame: FrameType, event: str, arg: Any) -> Any:
        if event == "line" and is_controllers(frame):
            raise stop(message)
        return at_each_line

    def at_each_call(frame: FrameType, event: str, arg: Any) -> Any:
        return at_each_line if is_controllers(frame) else None

    def trace_again(frame: FrameType, event: str, arg: Any) -> None:
        if sys.gettrace() is not at_each_call:
            _trace_controller_frames(frame, at_each_line)
            sys.settrace(at_each_call)

    if not _previous:
        _previous.append((sys.gettrace(), sys.getprofile()))
    _trace_controller_frames(sys._getframe(1), at_each_line)
    sys.settrace(at_each_call)
    sys.setprofile(trace_again)


def _trace_controller_frames(frame: FrameType | None, trace: Any) -> None:
    """Sets ``trace`` on the controller's frames from ``frame`` out to the runner's."""
    while frame is not None and not frame.f_code.co_filename.endswith(
        os.path.join("webots", "runner.py")
    ):
        if is_controllers(frame):
            frame.f_trace = trace
        frame = frame.f_back


def end_unwinding() -> None:
    """Ends what :func:`unwind_controller` started (nothing when it did not run)."""
    if _previous:
        trace, profile = _previous.pop()
        sys.setprofile(profile)
        sys.settrace(trace)


class _Run(Protocol):
    """What the watchdog reads of a run (:class:`~mazesim.webots.simulation.RobotSimulation`)."""

    steps: int
    ended: bool
    ended_at: float | None
    stopped: bool


class Watchdog:
    """Ends a controller that goes on without calling ``Robot.step``, from another thread.

    :meth:`start` it on the thread that runs the controller's code and :meth:`stop` it when that
    code is left: meanwhile it raises ``stop`` in that thread (and unwinds its frames as
    :func:`unwind_controller` does) once the run has been over for :data:`GRACE_SECONDS`
    (``run.stopped`` is set then, as when the controller calls ``step`` again), or when no step
    was taken for ``stall_seconds`` before the end (``stalled`` is set then).

    :meth:`stop` runs no Python code outside mazesim (the unwinding may still be on and would stop
    it half-way); an exception raised that has not reached the controller yet is taken there.
    """

    def __init__(self, run: _Run, stop: type[BaseException], stall_seconds: float) -> None:
        self.stalled = False
        self._run = run
        self._stop = stop
        self._stall_seconds = stall_seconds
        self._thread_id = threading.get_ident()
        self._lock = threading.Lock()
        self._done = False
        self._fired = False

    def start(self) -> None:
        """Starts watching the run."""
        threading.Thread(target=self._watch, name="mazesim-watchdog", daemon=True).start()

    def stop(self) -> None:
        """Stops watching (the thread ends at its next look)."""
        with self._lock:
            self._done = True
            fired = self._fired
        if fired:
            # An exception raised just before may not have arrived yet: it arrives at the next
            # backward jump, here. (Clearing it with PyThreadState_SetAsyncExc(id, NULL) would
            # leave CPython 3.11's eval breaker set for good.)
            try:
                for _ in range(2):
                    pass
            except self._stop:
                pass

    def _watch(self) -> None:
        run = self._run
        steps, since = run.steps, time.monotonic()
        while True:
            time.sleep(_POLL_SECONDS)
            now = time.monotonic()
            if self._done or run.stopped:
                return  # left, or already stopped by a call of Robot.step after the grace
            if run.ended:
                if run.ended_at is None or now - run.ended_at <= GRACE_SECONDS:
                    continue
                message = (
                    f"the controller went on for more than {GRACE_SECONDS:g} s of real time "
                    "after Robot.step returned -1: stopped, as Webots ends such a controller"
                )
            elif run.steps != steps:
                steps, since = run.steps, now
                continue
            elif now - since > self._stall_seconds:
                message = (
                    f"the controller took no step for {self._stall_seconds:g} s of real time "
                    "(a loop that never calls Robot.step): stopped"
                )
            else:
                continue
            with self._lock:
                if self._done:
                    return
                if run.ended:
                    run.stopped = True
                else:
                    self.stalled = True
                self._fired = True
                _SET_ASYNC_EXC(
                    ctypes.c_ulong(self._thread_id), ctypes.py_object(self._stopping(message))
                )
            return

    def _stopping(self, message: str) -> type[BaseException]:
        """A subclass of ``stop`` whose instance, made in the thread it is raised in (Python makes
        an asynchronous exception's instance there), also unwinds that thread's controller
        frames, unless the controller's code has been left by then."""
        stop, watchdog = self._stop, self

        class Stopping(stop):  # type: ignore[misc, valid-type]
            def __init__(self, *args: Any) -> None:
                super().__init__(message)
                if not watchdog._done:
                    unwind_controller(stop, message)

        Stopping.__name__ = Stopping.__qualname__ = stop.__name__
        return Stopping


#: CPython's call that raises an exception in another thread at its next bytecode (None: drops
#: a pending one), looked up once: looking it up runs ctypes' Python code.
_SET_ASYNC_EXC = ctypes.pythonapi.PyThreadState_SetAsyncExc
