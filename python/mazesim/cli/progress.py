"""The one progress display of the ``mazesim`` commands.

A :class:`ProgressDisplay` is called as ``display(stage, done, total)`` by whatever runs long (the
demo's steps, the barcode study's readings, training and evaluation stages, video frames...). On
a terminal it draws one bar per stage on stderr, with the rate and the time left (ETA); elsewhere
(a log file, CI) it stays silent for short runs and writes a plain line now and then for long
ones, so logs stay readable::

    mazesim: simulating: 1500/3000 steps (50%), 812 steps/s, ETA 0:02
    mazesim: simulating: 3000/3000 steps (100%) in 0:04, 790 steps/s

It is also a context manager that closes its bars, whatever ends the run. Commands that show
progress take ``--no-progress`` (:func:`add_progress_option`) and build their display with
:func:`progress_display`.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable, Mapping
from typing import Any, TextIO

from mazesim._closing import Closing
from mazesim.errors import MaybeInfinite

__all__ = [
    "BAR_DELAY_S",
    "PLAIN_EVERY_S",
    "ProgressDisplay",
    "add_progress_option",
    "clock_time",
    "draws_in_place",
    "progress_display",
]

#: Seconds a stage runs before its bar appears on a terminal (short runs show none).
BAR_DELAY_S = 1.0
#: Seconds between two plain lines when stderr is not a terminal; a stage that ran at least this
#: long also ends with a final line.
PLAIN_EVERY_S = 30.0
#: The bar of a stage on a terminal: stage, share, bar, counts, elapsed time, ETA and rate.
BAR_FORMAT = (
    "{desc}: {percentage:3.0f}%|{bar}| {n_fmt}/{total_fmt} {unit} "
    "[{elapsed} elapsed, ETA {remaining}, {rate_fmt}{postfix}]"
)


def clock_time(seconds: MaybeInfinite) -> str:
    """A duration as ``M:SS`` or ``H:MM:SS`` (``?`` when unknown)."""
    if not seconds >= 0.0 or seconds == float("inf"):
        return "?"
    whole = int(round(seconds))
    hours, rest = divmod(whole, 3600)
    minutes, secs = divmod(rest, 60)
    return f"{hours}:{minutes:02d}:{secs:02d}" if hours else f"{minutes}:{secs:02d}"


def _rate(count: float, unit: str) -> str:
    """A rate in ``unit`` per second with a sensible number of digits."""
    if count >= 100:
        return f"{count:,.0f} {unit}/s"
    if count >= 10:
        return f"{count:.1f} {unit}/s"
    return f"{count:.2f} {unit}/s"


class _Stage:
    """What the display knows of the stage it is showing."""

    def __init__(self, name: str, done: int, now: float) -> None:
        self.name = name
        self.first_done = done
        self.started = now
        self.last_line = now
        self.lines = 0
        self.note = ""
        self.bar: Any = None


def draws_in_place(stream: Any) -> bool:
    """Whether ``stream`` shows a line redrawn in place (``\\r``): a terminal, or the output of
    a Jupyter (IPython kernel) cell, whose streams are not terminals (``isatty()`` is False)
    but redraw a carriage-returned line as one."""
    if type(stream).__module__.split(".")[0] == "ipykernel":
        return True
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):
        return False


class ProgressDisplay(Closing):
    """Progress of a long run on stderr: ``display(stage, done, total)``.

    Args:
        stream: Where to draw; by default ``sys.stderr`` at the time of each call.
        enabled: False makes every call do nothing (``--no-progress``).
        unit: What is counted (``"steps"``, ``"readings"``...), unless ``units`` names the
            stage's.
        units: The unit of each stage, by stage name.
        terminal: Whether ``stream`` draws bars; by default :func:`draws_in_place` (a terminal
            or a Jupyter cell's output).
        bar_delay_s: Seconds a stage runs before its bar appears on a terminal (by default
            :data:`BAR_DELAY_S`).
        plain_every_s: Seconds between plain lines when ``stream`` is not a terminal (by
            default :data:`PLAIN_EVERY_S`).
        clock: The clock of the plain lines (seconds, monotonic).

    Example:
        >>> from mazesim.cli.progress import ProgressDisplay
        >>> with ProgressDisplay(unit="steps", enabled=False) as display:
        ...     for step in range(1, 101):
        ...         display("simulating", step, 100)
    """

    def __init__(
        self,
        stream: TextIO | None = None,
        *,
        enabled: bool = True,
        unit: str = "it",
        units: Mapping[str, str] | None = None,
        terminal: bool | None = None,
        bar_delay_s: float | None = None,
        plain_every_s: float | None = None,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self._stream = stream
        self.enabled = enabled
        self.unit = unit
        self.units = dict(units or {})
        self._terminal = terminal
        self.bar_delay_s = BAR_DELAY_S if bar_delay_s is None else bar_delay_s
        self.plain_every_s = PLAIN_EVERY_S if plain_every_s is None else plain_every_s
        self._clock = clock
        self._stage: _Stage | None = None

    @property
    def stream(self) -> TextIO:
        """The stream the display writes to."""
        return self._stream if self._stream is not None else sys.stderr

    @property
    def terminal(self) -> bool:
        """Whether the display draws bars (a terminal, or a Jupyter notebook's output, which
        redraws a line as a terminal does) or plain lines."""
        if self._terminal is None:
            self._terminal = draws_in_place(self.stream)
        return self._terminal

    def unit_of(self, stage: str) -> str:
        """The unit counted in ``stage``."""
        return self.units.get(stage, self.unit)

    def __call__(self, stage: str, done: int, total: int) -> None:
        """Shows that ``done`` of ``total`` of ``stage`` are done; ``done >= total`` ends it."""
        if not self.enabled:
            return
        total = max(int(total), 0)
        done = min(max(int(done), 0), total) if total else max(int(done), 0)
        now = self._clock()
        current = self._stage
        if current is None or current.name != stage:
            self._end_stage()
            current = self._stage = _Stage(stage, done, now)
            if self.terminal:
                current.bar = self._open_bar(stage, done, total)
        if current.bar is not None:
            if current.bar.total != total:
                current.bar.total = total
            current.bar.update(done - current.bar.n)
        elif current.first_done < done < total and now - current.last_line >= self.plain_every_s:
            self._plain_line(current, done, total, now)
        if total and done >= total:
            if current.bar is None and (
                current.lines or now - current.started >= self.plain_every_s
            ):
                self._plain_line(current, done, total, now)
            self._end_stage()

    def note(self, text: str) -> None:
        """Shows ``text`` (a live figure such as ``"success 42%"``) beside the current stage's
        count, until the stage ends or another note replaces it."""
        stage = self._stage
        if not self.enabled or stage is None:
            return
        stage.note = text
        if stage.bar is not None:
            stage.bar.set_postfix_str(text, refresh=False)

    def _open_bar(self, stage: str, done: int, total: int) -> Any:
        from tqdm import tqdm

        return tqdm(
            total=total,
            initial=done,
            desc=stage,
            unit=self.unit_of(stage),
            file=self.stream,
            leave=True,
            delay=self.bar_delay_s,
            mininterval=0.2,
            smoothing=0.1,
            dynamic_ncols=True,
            bar_format=BAR_FORMAT,
        )

    def _plain_line(self, stage: _Stage, done: int, total: int, now: float) -> None:
        unit = self.unit_of(stage.name)
        elapsed = now - stage.started
        rate = (done - stage.first_done) / elapsed if elapsed > 0 else 0.0
        share = f"{100.0 * done / total:.0f}%" if total else "?"
        line = f"mazesim: {stage.name}: {done}/{total} {unit} ({share})"
        if total and done >= total:
            line += f" in {clock_time(elapsed)}, {_rate(rate, unit)}"
        else:
            left = (total - done) / rate if rate > 0 else float("inf")
            line += f", {_rate(rate, unit)}, ETA {clock_time(left)}"
        if stage.note:
            line += f", {stage.note}"
        self.stream.write(line + "\n")
        self.stream.flush()
        stage.lines += 1
        stage.last_line = now

    def _end_stage(self) -> None:
        stage, self._stage = self._stage, None
        if stage is not None and stage.bar is not None:
            stage.bar.close()

    def close(self) -> None:
        """Closes the bar of the current stage, if any."""
        self._end_stage()


def add_progress_option(parser: argparse.ArgumentParser) -> None:
    """Adds ``--no-progress`` to the parser of a command that shows progress."""
    parser.add_argument(
        "--no-progress",
        action="store_true",
        help="show no progress on stderr (by default: a bar with the ETA on a terminal, else a "
        f"plain line every {PLAIN_EVERY_S:.0f} s of a long run)",
    )


def progress_display(
    args: argparse.Namespace, unit: str = "it", units: Mapping[str, str] | None = None
) -> ProgressDisplay:
    """The progress display of a command, off when ``--no-progress`` was given."""
    return ProgressDisplay(enabled=not getattr(args, "no_progress", False), unit=unit, units=units)
