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
"""

from __future__ import annotations

import os
import sys
from types import FrameType
from typing import Any

__all__ = ["GRACE_SECONDS", "end_unwinding", "unwind_controller"]

#: Real seconds a controller may go on after ``Robot.step`` returned -1, as in Webots.
GRACE_SECONDS = 1.0

#: mazesim's own code, which is not unwound (it raises the exception itself).
_PACKAGE = os.path.dirname(os.path.dirname(os.path.abspath(__file__))) + os.sep
#: The trace and profile functions set before the unwinding, restored after it (a coverage
#: tool's, a debugger's).
_previous: list[tuple[Any, Any]] = []


def _is_controllers(frame: FrameType) -> bool:
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
        if event == "line" and _is_controllers(frame):
            raise stop(message)
        return at_each_line

    def at_each_call(frame: FrameType, event: str, arg: Any) -> Any:
        return at_each_line if _is_controllers(frame) else None

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
        if _is_controllers(frame):
            frame.f_trace = trace
        frame = frame.f_back


def end_unwinding() -> None:
    """Ends what :func:`unwind_controller` started (nothing when it did not run)."""
    if _previous:
        trace, profile = _previous.pop()
        sys.setprofile(profile)
        sys.settrace(trace)
