"""A live view: a matplotlib window that shows frames as a run goes, where a display exists.

:class:`LiveView` opens one window (pyplot, the user's interactive backend) and replaces its
picture with each frame it is shown, at most as fast as the simulated time passes when asked to
keep real time. Where no window can open (no ``DISPLAY`` or ``WAYLAND_DISPLAY`` on Linux, or a
non-interactive matplotlib backend such as Agg) it says so once on stderr and carries on
headless: the run goes on, the frames are kept (:attr:`LiveView.last_frame`) but not shown.
"""

from __future__ import annotations

import os
import sys
import time
from typing import Any, TextIO

import numpy as np
import numpy.typing as npt

from mazesim.errors import MOST_MESSAGE, _shortened, _shown

__all__ = [
    "LIVE_OPTION_NOTICE",
    "NON_INTERACTIVE_BACKENDS",
    "LiveView",
    "display_problem",
    "shown_in",
]

#: What a command's ``--live`` says where no window can open (``{problem}``: the reason).
LIVE_OPTION_NOTICE = "mazesim: live view off: {problem}; carrying on headless"

#: matplotlib's backends that draw into files only, never a window.
NON_INTERACTIVE_BACKENDS = frozenset({"agg", "cairo", "pdf", "pgf", "ps", "svg", "template"})


def display_problem() -> str | None:
    """Why no window can open here, or None when one can."""
    import matplotlib

    backend = str(matplotlib.get_backend()).lower()
    if backend in NON_INTERACTIVE_BACKENDS:
        return f"the matplotlib backend {_shown(backend)} cannot open windows"
    if sys.platform.startswith("linux") and not (
        os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")
    ):
        return "no display (neither DISPLAY nor WAYLAND_DISPLAY is set)"
    return None


class LiveView:
    """One window showing frames as they come.

    Args:
        title: The window's title.
        real_time_step_s: Simulated seconds per frame; when given, :meth:`show` waits so the
            window does not run ahead of real time.
        stream: Where to say that there is no display.
        headless_notice: What to say there when no window can open, with ``{problem}`` where
            the reason goes; by default the words of the commands' ``--live``.
    """

    def __init__(
        self,
        title: str = "mazesim",
        real_time_step_s: float | None = None,
        stream: TextIO | None = None,
        headless_notice: str = LIVE_OPTION_NOTICE,
    ) -> None:
        self.title = title
        self.real_time_step_s = real_time_step_s
        self.problem = display_problem()
        self.headless = self.problem is not None
        self.frames_shown = 0
        self.last_frame: npt.NDArray[np.uint8] | None = None
        self._figure: Any = None
        self._image: Any = None
        self._next_time: float | None = None
        if self.headless:
            out = stream if stream is not None else sys.stderr
            # Said shortened past MOST_MESSAGE characters, as every message quoting a value is.
            notice = _shortened(headless_notice.format(problem=self.problem), MOST_MESSAGE)
            out.write(notice + "\n")
            out.flush()

    def show(self, frame: npt.NDArray[np.uint8]) -> None:
        """Shows a frame (or only keeps it, headless)."""
        self.last_frame = frame
        self.frames_shown += 1
        if self.headless:
            return
        import matplotlib.pyplot as pyplot

        if self._figure is None or not pyplot.fignum_exists(self._figure.number):
            self._figure = pyplot.figure(self.title)
            axes = self._figure.add_subplot()
            axes.set_axis_off()
            self._image = axes.imshow(frame)
            self._figure.tight_layout()
            pyplot.show(block=False)
        else:
            self._image.set_data(frame)
        if self.real_time_step_s is not None:
            now = time.monotonic()
            if self._next_time is not None and self._next_time > now:
                time.sleep(self._next_time - now)
            self._next_time = max(now, self._next_time or now) + self.real_time_step_s
        pyplot.pause(0.001)

    def close(self) -> None:
        """Closes the window, if one is open."""
        if self._figure is not None:
            import matplotlib.pyplot as pyplot

            pyplot.close(self._figure)
            self._figure = None


def shown_in(
    live: LiveView | None,
    frame: npt.NDArray[np.uint8],
    title: str,
    frames_per_second: float,
    headless_notice: str,
) -> LiveView:
    """Shows ``frame`` in ``live``, opened first when it is None (titled ``title``, at most
    ``frames_per_second`` frames a second of real time, ``headless_notice`` said where no
    window can open), as an env of ``render_mode="human"`` renders; returns the view."""
    if live is None:
        live = LiveView(title, 1.0 / frames_per_second, headless_notice=headless_notice)
    live.show(frame)
    return live
