"""A display for a controller's windows where there is none: Tk's on a virtual X display, Qt's
drawn off screen.

A Webots controller that draws with ``tkinter`` or ``turtle`` (a maze map, a plot) opens its
windows beside Webots' own. Where ``$DISPLAY`` is not set (a server, CI) and Xvfb, the X
server that draws into memory, is installed (Debian: ``apt-get install xvfb``),
:func:`virtual_display` starts one on a free display number and sets ``$DISPLAY`` for the
controller (and the processes it starts) while it runs; the windows are drawn there and not
shown. The server serves every later run of the process too and stops when the process ends:
Tk keeps its connection to a display once made, so a second server on the same display number
would meet a stale connection. Without Xvfb such a controller is not started (the run says
why). Qt needs no server: its ``offscreen`` platform (``QT_QPA_PLATFORM=offscreen``, which
:func:`window_environment` sets for the run) draws a Qt controller's windows into memory, where
Qt would otherwise stop the whole process for want of a display.
"""

from __future__ import annotations

import atexit
import os
import shutil
import subprocess
from collections.abc import Iterator
from contextlib import contextmanager

from mazesim.errors import MissingDependencyError

__all__ = ["QT_OFFSCREEN", "XVFB", "virtual_display", "window_environment", "xvfb_program"]

#: The environment that draws Qt's windows into memory.
QT_OFFSCREEN = {"QT_QPA_PLATFORM": "offscreen"}
#: The X server that draws into memory.
XVFB = "Xvfb"
#: Seconds Xvfb may take to say which display it took.
START_TIMEOUT_S = 20.0
#: The screen it offers: larger than the windows controllers open.
SCREEN = "1280x1024x24"


def xvfb_program() -> str | None:
    """The Xvfb program on ``PATH``, or None."""
    return shutil.which(XVFB)


def _display_number(reader: int, server: subprocess.Popen[bytes]) -> str:
    """The display number Xvfb writes to ``reader`` once it is ready (``-displayfd``): read up
    to its line end, since Xvfb stops if the pipe closes before it has written it whole."""
    import select
    import time

    deadline = time.monotonic() + START_TIMEOUT_S
    text = b""
    ready = True
    while b"\n" not in text and ready:
        ready = bool(select.select([reader], [], [], max(0.0, deadline - time.monotonic()))[0])
        chunk = os.read(reader, 64) if ready else b""
        ready = ready and bool(chunk)
        text += chunk
    number = text.decode("ascii", "replace").strip()
    if not number.isdigit():
        server.kill()
        server.wait()
        raise MissingDependencyError(
            f"expected Xvfb to start a virtual display for the controller's Tk windows within "
            f"{START_TIMEOUT_S:g} s, found {'no answer' if not ready else repr(number)}"
        )
    return number


#: The process's Xvfb server and its display's name, once started.
_server: tuple[subprocess.Popen[bytes], str] | None = None


def _stop() -> None:
    """Stops the process's Xvfb server, if any."""
    global _server
    if _server is None:
        return
    server, _ = _server
    _server = None
    server.terminate()
    try:
        server.wait(timeout=5)
    except subprocess.TimeoutExpired:
        server.kill()
        server.wait()


def _start(program: str) -> str:
    """Starts Xvfb on a free display and returns the display's name (``:N``)."""
    global _server
    reader, writer = os.pipe()
    try:
        server = subprocess.Popen(
            [program, "-displayfd", str(writer), "-nolisten", "tcp", "-screen", "0", SCREEN],
            pass_fds=(writer,),
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        os.close(writer)
        writer = -1
        name = f":{_display_number(reader, server)}"
    finally:
        os.close(reader)
        if writer >= 0:
            os.close(writer)
    _server = (server, name)
    atexit.register(_stop)
    return name


@contextmanager
def virtual_display() -> Iterator[str]:
    """Sets ``$DISPLAY`` to the process's virtual display for the ``with`` block, starting
    Xvfb the first time (or again if it has stopped).

    Yields:
        The display's name (``:N``).

    Raises:
        MissingDependencyError: Xvfb is not installed, or did not start.
    """
    program = xvfb_program()
    if program is None:
        raise MissingDependencyError(
            "expected Xvfb on PATH to draw the controller's Tk windows on a virtual display, "
            "found none: install it (Debian: apt-get install xvfb) or set $DISPLAY"
        )
    if _server is not None and _server[0].poll() is not None:
        _stop()
    name = _server[1] if _server is not None else _start(program)
    saved = os.environ.get("DISPLAY")
    os.environ["DISPLAY"] = name
    try:
        yield name
    finally:
        if saved is None:
            os.environ.pop("DISPLAY", None)
        else:
            os.environ["DISPLAY"] = saved


@contextmanager
def window_environment(values: dict[str, str]) -> Iterator[None]:
    """Sets the environment variables ``values`` for the ``with`` block (for the controller and
    the processes it starts), and puts back what was there."""
    saved = {name: os.environ.get(name) for name in values}
    os.environ.update(values)
    try:
        yield
    finally:
        for name, value in saved.items():
            if value is None:
                os.environ.pop(name, None)
            else:
                os.environ[name] = value
