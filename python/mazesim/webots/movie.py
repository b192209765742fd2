"""A supervisor's movie: ``movieStartRecording`` to ``movieStopRecording`` written as an MP4.

Webots records "the simulation" into a movie file from ``wb_supervisor_movie_start_recording``
to ``wb_supervisor_movie_stop_recording``; ``wb_supervisor_movie_is_ready`` is true before a
recording starts and again once the file is written, false while it is recorded, and
``wb_supervisor_movie_failed`` tells whether the last one failed (reference manual, Supervisor;
Webots' own test ``supervisor_movie`` checks these states). Its C library refuses a second
start, an empty file name, a size or quality out of range and an acceleration below 1, printing
an error and recording nothing. A headless run has no 3D window: its movie is the top-down view
``exportImage`` and ``--video`` draw (:func:`mazesim.webots.view_export.view_image`), one frame
per simulated step, played ``acceleration`` times as fast as the simulation ran (at most 60
frames per second: a faster one keeps every few steps), whatever the size, codec and caption
asked. The frames go to a private temporary file as they are drawn; stopping writes the movie
to its file whole (or fails, with an error, when imageio and imageio-ffmpeg are missing or the
file cannot be written), and the movie is ready as soon as the stop returns.
"""

from __future__ import annotations

import math
import os
import shutil
import tempfile
from typing import Any

from mazesim._atomic import atomic_file
from mazesim.errors import MazesimError
from mazesim.webots.devices import _print_error

__all__ = ["MAX_FPS", "MovieRecorder"]

#: The most frames per second a movie is written with (a faster one keeps every few steps).
MAX_FPS = 60.0
_START = "wb_supervisor_movie_start_recording"


class MovieRecorder:
    """The movie of one supervisor: idle (ready), recording, or written (ready, or failed)."""

    def __init__(self, simulation: Any) -> None:
        self._simulation = simulation
        self._target: str | None = None
        self._folder: tempfile.TemporaryDirectory[str] | None = None
        self._writer: Any = None
        self._stride = 1
        self._steps = 0
        self._missing = ""
        self.failed = False

    @property
    def ready(self) -> bool:
        """Whether no movie is being recorded."""
        return self._target is None

    def start(
        self, filename: Any, width: int, height: int, quality: int, acceleration: int
    ) -> None:
        """Starts recording into ``filename``, or prints Webots' error and records nothing."""
        refused = self._refusal(filename, width, height, quality, acceleration)
        if not self.ready:
            refused = f"{_START}(): movie recording has already been started."
        if refused is not None:
            _print_error(f"Error: {refused}")
            return
        step_ms = float(self._simulation.basic_time_step_ms)
        fps = 1000.0 / step_ms * int(acceleration)
        self._stride = max(1, math.ceil(fps / MAX_FPS - 1e-9))
        self.failed = False
        self._target = os.fspath(filename)
        self._steps = 0
        try:
            import imageio.v2 as imageio
            import imageio_ffmpeg  # noqa: F401
        except ImportError as error:
            self._writer = None
            self._missing = f"writing a movie needs imageio and imageio-ffmpeg ({error})"
            return
        self._folder = tempfile.TemporaryDirectory(prefix="mazesim-movie-")
        self._writer = imageio.get_writer(
            os.path.join(self._folder.name, "movie.mp4"),
            format="FFMPEG",
            mode="I",
            fps=fps / self._stride,
            codec="libx264",
            quality=max(0.0, min(10.0, int(quality) / 10.0)),
            macro_block_size=16,
        )
        self.frame()

    @staticmethod
    def _refusal(
        filename: Any, width: int, height: int, quality: int, acceleration: int
    ) -> str | None:
        """Webots' C library's error for these arguments, or None."""
        if not isinstance(filename, (str, os.PathLike)) or not os.fspath(filename):
            return f"{_START}() called with NULL or empty 'filename' argument."
        if int(width) <= 0 or int(height) <= 0:
            return f"{_START}(): 'width' and 'height' arguments must be postitive."
        if not 1 <= int(quality) <= 100:
            return f"{_START}(): 'quality' argument ({int(quality)}) must be between 1 and 100."
        if int(acceleration) < 1:
            return f"{_START}(): 'acceleration' argument must be greater than or equal to 1."
        return None

    def frame(self) -> None:
        """Adds the view of the world now (every ``stride``-th step) while recording."""
        if self._target is None or self._writer is None:
            return
        if self._steps % self._stride == 0:
            from mazesim.webots.view_export import view_image

            self._writer.append_data(view_image(self._simulation))
        self._steps += 1

    def stop(self) -> None:
        """Writes the movie to its file: ready then, failed when it could not be written."""
        target, self._target = self._target, None
        if target is None:
            return
        writer, self._writer = self._writer, None
        if writer is None:
            self.failed = True
            _print_error(f"Error: wb_supervisor_movie_stop_recording(): {self._missing}.")
            return
        folder, self._folder = self._folder, None
        try:
            writer.close()
            assert folder is not None
            with open(os.path.join(folder.name, "movie.mp4"), "rb") as movie:
                with atomic_file(target) as out:
                    shutil.copyfileobj(movie, out)
        except (OSError, MazesimError) as error:
            self.failed = True
            reason = getattr(error, "strerror", None) or error
            _print_error(
                f"Error: wb_supervisor_movie_stop_recording(): cannot write {target}: {reason}."
            )
        finally:
            if folder is not None:
                folder.cleanup()
