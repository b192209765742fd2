"""Keyboard, mouse and joystick of Webots' ``controller`` module, played from a key script.

A run has no window to type into, so the keyboard plays a script: ``mazesim webots run ...
--keys FILE`` reads lines of ``time_s key [duration_s]``. From ``time_s`` on, ``key`` is held
down until the next line's time (or for ``duration_s`` seconds when given). ``key`` is one
character (``a`` and ``A`` both give 65, as Webots reports letters), a Webots key name (``UP``,
``DOWN``, ``LEFT``, ``RIGHT``, ``HOME``, ``END``, ``PAGEUP``, ``PAGEDOWN``, ``SPACE``,
``NUMPAD_UP``...), with modifiers joined by ``+`` (``SHIFT+A``, ``CONTROL+UP``), or ``-`` to
release every key. Blank lines and ``#`` comments are skipped. Without a script ``getKey()``
returns -1, as Webots does when nobody types.
"""

from __future__ import annotations

import bisect
import math
import os
from dataclasses import dataclass
from typing import TYPE_CHECKING, NamedTuple

from mazesim._paths import read_text
from mazesim.errors import InvalidArgumentError, _shown
from mazesim.webots.devices import Sampled
from mazesim.webots.webots_api import NotSimulated, webots_property

if TYPE_CHECKING:
    from mazesim.webots.simulation import RobotSimulation

__all__ = ["Joystick", "KeyPress", "KeyScript", "Keyboard", "Mouse", "MouseState", "read_keys"]

#: Webots' key codes for the named keys (``Keyboard.UP`` etc.).
KEY_CODES = {
    "END": 312,
    "HOME": 313,
    "LEFT": 314,
    "UP": 315,
    "RIGHT": 316,
    "DOWN": 317,
    "PAGEUP": 366,
    "PAGEDOWN": 367,
    "NUMPAD_HOME": 375,
    "NUMPAD_LEFT": 376,
    "NUMPAD_UP": 377,
    "NUMPAD_RIGHT": 378,
    "NUMPAD_DOWN": 379,
    "NUMPAD_END": 382,
    "SPACE": 32,
}
#: Webots' modifier bits, added to the key code.
MODIFIERS = {"SHIFT": 0x10000, "CONTROL": 0x20000, "CTRL": 0x20000, "ALT": 0x40000}
#: The words that release every key.
RELEASE = {"-", "NONE", "RELEASE"}


@dataclass(frozen=True)
class KeyPress:
    """One line of a key script: ``key`` (a Webots key code, or None to release) from ``start``
    (s) until ``end`` (s; ``inf`` until the next line)."""

    start: float
    key: int | None
    end: float


def key_code(text: str) -> int:
    """The Webots key code of a key as a script writes it (``A``, ``UP``, ``SHIFT+A``).

    Raises:
        InvalidArgumentError: The text names no key.
    """
    *modifiers, key = text.split("+") if text != "+" else ["+"]
    code = 0
    for modifier in modifiers:
        bit = MODIFIERS.get(modifier.upper())
        if bit is None:
            raise InvalidArgumentError(
                f"expected a modifier SHIFT, CONTROL or ALT before '+', found {_shown(modifier)}"
            )
        code |= bit
    if len(key) == 1:
        return code | ord(key.upper())
    named = KEY_CODES.get(key.upper())
    if named is None:
        raise InvalidArgumentError(
            f"expected one character or a key name ({', '.join(sorted(KEY_CODES))}), found "
            f"{_shown(key)}"
        )
    return code | named


class KeyScript:
    """The keys held down over time, from a key script."""

    def __init__(self, presses: list[KeyPress]) -> None:
        self.presses = sorted(presses, key=lambda press: press.start)
        self._starts = [press.start for press in self.presses]

    @classmethod
    def parse(cls, text: str, source: str = "<keys>") -> KeyScript:
        """Reads a key script.

        Raises:
            InvalidArgumentError: A line is not ``time_s key [duration_s]``; the message gives
                ``source:line``.
        """
        lines: list[tuple[int, float, int | None, float | None]] = []
        for number, line in enumerate(text.splitlines(), start=1):
            words = line.split("#", 1)[0].split()
            if not words:
                continue
            where = f"{source}:{number}"
            if len(words) not in (2, 3):
                raise InvalidArgumentError(
                    f"{where}: expected 'time_s key [duration_s]', found {_shown(line.strip())}"
                )
            start = _seconds(words[0], where, "time")
            try:
                key = None if words[1].upper() in RELEASE else key_code(words[1])
            except InvalidArgumentError as error:
                raise InvalidArgumentError(f"{where}: {error}") from None
            duration = _seconds(words[2], where, "duration") if len(words) == 3 else None
            lines.append((number, start, key, duration))
        lines.sort(key=lambda entry: (entry[1], entry[0]))
        presses = []
        for i, (_, start, key, duration) in enumerate(lines):
            following = lines[i + 1][1] if i + 1 < len(lines) else math.inf
            end = following if duration is None else min(following, start + duration)
            presses.append(KeyPress(start, key, end))
        return cls(presses)

    def key_at(self, time: float) -> int | None:
        """The key held down at ``time`` seconds, or None."""
        index = bisect.bisect_right(self._starts, time + 1e-9) - 1
        if index < 0:
            return None
        press = self.presses[index]
        return press.key if time < press.end - 1e-9 else None


def _seconds(word: str, where: str, what: str) -> float:
    try:
        value = float(word)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and value >= 0.0):
        raise InvalidArgumentError(
            f"{where}: expected a {what} in seconds >= 0, found {_shown(word)}"
        )
    return value


#: The longest key script (characters): some 100,000 lines of keys, where a script of 64 MiB
#: took 3.7 GB and more than ten minutes to read.
MAX_KEY_SCRIPT_CHARACTERS = 4 * 1024 * 1024


def read_keys(path: str | os.PathLike[str]) -> KeyScript:
    """Reads a key script file.

    Raises:
        MazesimIOError: The file cannot be read.
        InvalidArgumentError: A line is malformed, or the file is longer than
            :data:`MAX_KEY_SCRIPT_CHARACTERS`.
    """
    file = os.fspath(path)
    what = "the key script (lines of 'time_s key [duration_s]')"
    text = read_text(file, what, most=MAX_KEY_SCRIPT_CHARACTERS)
    return KeyScript.parse(text, file)


class _Polled(Sampled, NotSimulated):
    """An input device sampled every period: enable, disable, getSamplingPeriod."""

    _api = "wb_keyboard"

    def __init__(self, simulation: RobotSimulation | None = None) -> None:
        self._simulation = simulation
        self._period_ms = 0

    def enable(self, samplingPeriod: int) -> None:
        """Reads the device every ``samplingPeriod`` ms."""
        period = self._checked_period(samplingPeriod)
        if period is not None:
            self._period_ms = period

    def disable(self) -> None:
        """Stops reading the device."""
        self._period_ms = 0


class Keyboard(_Polled):
    """The keyboard, played from the run's key script."""

    END = KEY_CODES["END"]
    HOME = KEY_CODES["HOME"]
    LEFT = KEY_CODES["LEFT"]
    UP = KEY_CODES["UP"]
    RIGHT = KEY_CODES["RIGHT"]
    DOWN = KEY_CODES["DOWN"]
    PAGEUP = KEY_CODES["PAGEUP"]
    PAGEDOWN = KEY_CODES["PAGEDOWN"]
    NUMPAD_HOME = KEY_CODES["NUMPAD_HOME"]
    NUMPAD_LEFT = KEY_CODES["NUMPAD_LEFT"]
    NUMPAD_UP = KEY_CODES["NUMPAD_UP"]
    NUMPAD_RIGHT = KEY_CODES["NUMPAD_RIGHT"]
    NUMPAD_DOWN = KEY_CODES["NUMPAD_DOWN"]
    NUMPAD_END = KEY_CODES["NUMPAD_END"]
    KEY = 0xFFFF
    SHIFT = MODIFIERS["SHIFT"]
    CONTROL = MODIFIERS["CONTROL"]
    ALT = MODIFIERS["ALT"]

    def __init__(
        self, samplingPeriod: int | None = None, simulation: RobotSimulation | None = None
    ) -> None:
        if simulation is None:
            from mazesim.webots import simulation as simulations

            simulation = simulations.current()
        super().__init__(simulation)
        self._served_sample = -1
        self._enabled_at_ms = 0.0
        if samplingPeriod:
            self.enable(samplingPeriod)

    def getKey(self) -> int:
        """The key held down now, once per time step; -1 when no (further) key is pressed."""
        simulation = self._simulation
        if simulation is None:
            return -1
        if self._period_ms == 0:
            self._warn_disabled("get_key")
            return -1
        # As in Webots, the keyboard is read once per sampling period (counted from enable):
        # a key held down is returned once per period, not at every step between.
        now_ms = round(simulation.time * 1000.0, 6)
        sample = int((now_ms - self._enabled_at_ms + 1e-6) // self._period_ms)
        if sample < 1 or sample == self._served_sample:
            return -1
        self._served_sample = sample
        sampled_at = (self._enabled_at_ms + sample * self._period_ms) / 1000.0
        key = simulation.keys.key_at(sampled_at)
        return -1 if key is None else key

    def enable(self, samplingPeriod: int) -> None:
        """Reads the keyboard every ``samplingPeriod`` ms, from now on."""
        super().enable(samplingPeriod)
        if self._simulation is not None:
            self._enabled_at_ms = round(self._simulation.time * 1000.0, 6)
        self._served_sample = -1


class MouseState(NamedTuple):
    """What ``Mouse.getState`` returns: buttons, the pointer in the view, its 3D point."""

    left: bool
    middle: bool
    right: bool
    u: float
    v: float
    x: float
    y: float
    z: float


class Mouse(_Polled):
    """The mouse of the 3D view; a headless run has none: no button is ever pressed."""

    _api = "wb_mouse"

    def __init__(self, samplingPeriod: int | None = None) -> None:
        super().__init__()
        self._three_d = False
        if samplingPeriod:
            self.enable(samplingPeriod)

    def enable3dPosition(self) -> None:
        """Asks for the 3D position under the pointer (always NaN here)."""
        self._three_d = True

    def disable3dPosition(self) -> None:
        """Stops asking for the 3D position."""
        self._three_d = False

    def is3dPositionEnabled(self) -> bool:
        """Whether the 3D position was asked for."""
        return self._three_d

    def getState(self) -> MouseState:
        """No button pressed, the pointer outside the view (NaN), as Webots without a view."""
        nan = math.nan
        return MouseState(False, False, False, nan, nan, nan, nan, nan)

    state = webots_property("getState")


class Joystick(_Polled):
    """A game controller; none is connected in a headless run."""

    _api = "wb_joystick"

    def __init__(self, samplingPeriod: int | None = None) -> None:
        super().__init__()
        if samplingPeriod:
            self.enable(samplingPeriod)

    def isConnected(self) -> bool:
        """False: no joystick is connected."""
        return False

    def getModel(self) -> str:
        """The empty string: no joystick."""
        return ""

    model = webots_property("getModel")

    def getNumberOfAxes(self) -> int:
        """0: no joystick."""
        return 0

    def getAxisValue(self, axis: int) -> int:
        """0: no joystick."""
        return 0

    def getNumberOfPovs(self) -> int:
        """0: no joystick."""
        return 0

    def getPovValue(self, pov: int) -> int:
        """0: no joystick."""
        return 0

    def getPressedButton(self) -> int:
        """-1: no button pressed."""
        return -1

    def setConstantForce(self, level: int) -> None:
        """Ignored: no force feedback."""

    def setConstantForceDuration(self, duration: float) -> None:
        """Ignored: no force feedback."""

    def setAutoCenteringGain(self, gain: float) -> None:
        """Ignored: no force feedback."""

    def setResistanceGain(self, gain: float) -> None:
        """Ignored: no force feedback."""

    def setForceAxis(self, axis: int) -> None:
        """Ignored: no force feedback."""
