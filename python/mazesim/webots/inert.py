"""Devices of Webots' ``controller`` module that the e-puck's simulation keeps inert.

The e-puck's ``speaker`` exists and accepts every call; no sound is played (its ``emitter`` and
``receiver`` are in :mod:`mazesim.webots.radio_devices`).
The other classes (Display, Pen, Lidar, RangeFinder, Radar, Connector, Brake, Altimeter,
VacuumGripper, Skin, Motion) can be imported and constructed as in Webots, but the e-puck has no
such device: their readings are Webots' values for a missing device.

A method of Webots' API that mazesim does not simulate prints Webots-style
``Error: <call>() is not available in mazesim`` on stderr and returns None; a name Webots' API
does not have raises ``AttributeError``, as in Webots (see :mod:`mazesim.webots.webots_api`).
"""

from __future__ import annotations

import math
import sys
import wave
from types import SimpleNamespace
from typing import TYPE_CHECKING, Any

from mazesim.errors import _shown
from mazesim.webots.devices import Device, _ScalarSensor, _Sensor
from mazesim.webots.node_types import node_type
from mazesim.webots.webots_api import NotSimulated

if TYPE_CHECKING:
    from mazesim.webots.simulation import RobotSimulation

__all__ = [
    "Altimeter",
    "AnsiCodes",
    "Brake",
    "Connector",
    "ContactPoint",
    "Display",
    "Lidar",
    "LidarPoint",
    "Motion",
    "Pen",
    "RadarTarget",
    "Radar",
    "RangeFinder",
    "Skin",
    "Speaker",
    "VacuumGripper",
]


class _Inert(_Sensor):
    """A sensor the e-puck does not carry: enable/disable work, readings are NaN. Its getters
    are its Webots class's own (a Lidar has no ``getValue``, as in Webots)."""

    def _read(self) -> float:
        return math.nan


class Speaker(Device):
    """The e-puck's speaker: nothing is heard, but a sound plays for as long as its file
    lasts (``isSoundPlaying``), as Webots' speaker plays it; speech is accepted, not said."""

    _node_type = node_type("SPEAKER")

    def __init__(self, name: str, simulation: RobotSimulation) -> None:
        super().__init__(name, simulation)
        self._engine = "pico"
        self._language = "en-US"
        #: The sounds playing, by file name: the simulated time each ends (inf: looped).
        self._playing: dict[str, float] = {}

    @staticmethod
    def playSound(
        left: Any,
        right: Any,
        sound: str,
        volume: float,
        pitch: float,
        balance: float,
        loop: bool,
    ) -> None:
        """Plays the WAV file ``sound`` (relative to the controller's folder) on ``left`` and
        ``right``: it plays for its duration divided by ``pitch``, or until :meth:`stop` when
        ``loop`` is true (reference manual, Speaker); nothing is heard. A file that is not a
        readable WAV plays for no time, with an error."""
        speakers = {id(s): s for s in (left, right) if isinstance(s, Speaker)}
        if not speakers:
            return
        try:
            with wave.open(str(sound), "rb") as clip:
                seconds = clip.getnframes() / float(clip.getframerate())
        except (OSError, EOFError, wave.Error) as error:
            print(
                f"Error: wb_speaker_play_sound(): cannot play {_shown(sound)}: {_shown(error)}",
                file=sys.stderr,
            )
            return
        rate = float(pitch) if float(pitch) > 0.0 else 1.0
        for speaker in speakers.values():
            end = math.inf if loop else speaker._simulation.clock + seconds / rate
            speaker._playing[str(sound)] = end

    def stop(self, sound: str | None = None) -> None:
        """Stops ``sound``, or every sound without one."""
        if sound:
            self._playing.pop(str(sound), None)
        else:
            self._playing.clear()

    def isSoundPlaying(self, sound: str | None = None) -> bool:
        """Whether ``sound`` (any sound, without one) is still playing."""
        now = self._simulation.clock
        if sound:
            return self._playing.get(str(sound), -math.inf) > now + 1e-9
        return any(end > now + 1e-9 for end in self._playing.values())

    def speak(self, text: str, volume: float = 1.0) -> None:
        """Accepted; nothing is said."""

    def isSpeaking(self) -> bool:
        """False."""
        return False

    def setEngine(self, engine: str) -> bool:
        """Sets the speech engine's name; True."""
        self._engine = str(engine)
        return True

    def setLanguage(self, language: str) -> bool:
        """Sets the speech language; True."""
        self._language = str(language)
        return True

    def getEngine(self) -> str:
        """The speech engine's name."""
        return self._engine

    def getLanguage(self) -> str:
        """The speech language."""
        return self._language


class Display(Device):
    """A display: one the world puts in an extension slot has its node's width and height,
    and its drawings are accepted and dropped (mazesim has no view to show it on), as the C
    library's ``wb_display_*`` functions do; without one (the e-puck has none) its size is 0.
    An image (``imageNew``, ``imageCopy``, ``imageLoad``) keeps its size only."""

    _node_type = node_type("DISPLAY")

    RGB = 3
    RGBA = 4
    ARGB = 5
    BGRA = 6
    ABGR = 7

    def __init__(
        self, name: str, simulation: RobotSimulation, width: int = 0, height: int = 0
    ) -> None:
        super().__init__(name, simulation)
        self._size = (max(0, int(width)), max(0, int(height)))

    def getWidth(self) -> int:
        """The display's width in pixels (its node's ``width``)."""
        return self._size[0]

    def getHeight(self) -> int:
        """The display's height in pixels (its node's ``height``)."""
        return self._size[1]

    def setColor(self, color: int) -> None:
        """Accepted; nothing is drawn."""

    def setAlpha(self, alpha: float) -> None:
        """Accepted; nothing is drawn."""

    def setOpacity(self, opacity: float) -> None:
        """Accepted; nothing is drawn."""

    def setFont(self, font: str, size: int, antiAliasing: bool) -> None:
        """Accepted; nothing is drawn."""

    def attachCamera(self, camera: Any) -> None:
        """Accepted; nothing is drawn."""

    def detachCamera(self) -> None:
        """Accepted."""

    def drawPixel(self, x: int, y: int) -> None:
        """Accepted; nothing is drawn."""

    def drawLine(self, x1: int, y1: int, x2: int, y2: int) -> None:
        """Accepted; nothing is drawn."""

    def drawRectangle(self, x: int, y: int, width: int, height: int) -> None:
        """Accepted; nothing is drawn."""

    def drawOval(self, cx: int, cy: int, a: int, b: int) -> None:
        """Accepted; nothing is drawn."""

    def drawPolygon(self, x: Any, y: Any) -> None:
        """Accepted; nothing is drawn."""

    def drawText(self, text: str, x: int, y: int) -> None:
        """Accepted; nothing is drawn."""

    def fillRectangle(self, x: int, y: int, width: int, height: int) -> None:
        """Accepted; nothing is drawn."""

    def fillOval(self, cx: int, cy: int, a: int, b: int) -> None:
        """Accepted; nothing is drawn."""

    def fillPolygon(self, x: Any, y: Any) -> None:
        """Accepted; nothing is drawn."""

    def imageNew(
        self, data: Any, format: int, width: int | None = None, height: int | None = None
    ) -> SimpleNamespace:
        """An image of ``width`` x ``height`` (its size only)."""
        return SimpleNamespace(width=max(0, int(width or 0)), height=max(0, int(height or 0)))

    def imageLoad(self, filename: str) -> SimpleNamespace:
        """An image of size 0: the file is not read."""
        return SimpleNamespace(width=0, height=0)

    def imageCopy(self, x: int, y: int, width: int, height: int) -> SimpleNamespace:
        """An image of ``width`` x ``height`` (its size only)."""
        return SimpleNamespace(width=max(0, int(width)), height=max(0, int(height)))

    def imagePaste(self, ir: Any, x: int, y: int, blend: bool = False) -> None:
        """Accepted; nothing is drawn."""

    def imageSave(self, ir: Any, filename: str) -> None:
        """Accepted; no file is written."""

    def imageDelete(self, ir: Any) -> None:
        """Accepted."""


class Pen(Device):
    """A pen (the e-puck has none)."""

    _node_type = node_type("PEN")

    def write(self, write: bool) -> None:
        """Accepted; nothing is drawn."""

    def setInkColor(self, color: int, density: float) -> None:
        """Accepted; nothing is drawn."""


class Lidar(_Inert):
    """A lidar (the e-puck has none)."""

    _node_type = node_type("LIDAR")

    def getRangeImage(self) -> None:
        """None: no lidar."""
        return None

    def getHorizontalResolution(self) -> int:
        """0: no lidar."""
        return 0

    def getNumberOfLayers(self) -> int:
        """0: no lidar."""
        return 0

    def getLayerRangeImage(self, layer: int) -> None:
        """None: no lidar."""
        return None

    def enablePointCloud(self) -> None:
        """Accepted; there is no point cloud."""

    def disablePointCloud(self) -> None:
        """Accepted."""

    def isPointCloudEnabled(self) -> bool:
        """False: no lidar."""
        return False

    def getPointCloud(self, data_type: str = "list") -> None:
        """None: no lidar."""
        return None

    def getLayerPointCloud(self, layer: int, data_type: str = "list") -> None:
        """None: no lidar."""
        return None

    def getNumberOfPoints(self) -> int:
        """0: no lidar."""
        return 0

    def getFov(self) -> float:
        """NaN: no lidar."""
        return math.nan

    getVerticalFov = getMinRange = getMaxRange = getFov
    getFrequency = getMinFrequency = getMaxFrequency = getFov

    def setFrequency(self, frequency: float) -> None:
        """Accepted; there is no lidar."""


class LidarPoint:
    """A point of a lidar's point cloud."""

    def __init__(self, x: float = 0.0, y: float = 0.0, z: float = 0.0, layer: int = 0) -> None:
        self.x, self.y, self.z = x, y, z
        self.layer_id = layer
        self.time = 0.0


class RangeFinder(_Inert):
    """A range finder (the e-puck has none)."""

    _node_type = node_type("RANGE_FINDER")

    def getRangeImage(self, data_type: str = "list") -> None:
        """None: no range finder."""
        return None

    @staticmethod
    def rangeImageGetDepth(image: Any, width: int, x: int, y: int) -> float:
        """The depth at pixel (x, y) of a range image."""
        return float(image[y * width + x])


class Radar(_Inert):
    """A radar (the e-puck has none)."""

    _node_type = node_type("RADAR")

    def getNumberOfTargets(self) -> int:
        """0: no radar."""
        return 0

    def getTargets(self) -> list[RadarTarget]:
        """The empty list: no radar."""
        return []


class RadarTarget:
    """A target seen by a radar."""

    def __init__(self) -> None:
        self.distance = math.nan
        self.received_power = math.nan
        self.speed = math.nan
        self.azimuth = math.nan


class Connector(Device):
    """A connector (the e-puck has none)."""

    _node_type = node_type("CONNECTOR")

    def isLocked(self) -> bool:
        """False."""
        return False

    def getPresence(self) -> int:
        """-1: no connector."""
        return -1


class Brake(Device):
    """A brake (the e-puck's wheels have none)."""

    _node_type = node_type("BRAKE")

    ROTATIONAL = 0
    LINEAR = 1


class Altimeter(_Inert, _ScalarSensor):
    """An altimeter (the e-puck has none)."""

    _node_type = node_type("ALTIMETER")


class VacuumGripper(Device):
    """A vacuum gripper (the e-puck has none)."""

    _node_type = node_type("VACUUM_GRIPPER")

    def isOn(self) -> bool:
        """False."""
        return False


class Skin(Device):
    """A skin (the e-puck has none)."""

    _node_type = node_type("SKIN")


class Motion(NotSimulated):
    """A motion file player (for humanoids; the e-puck has no joints to play it on)."""

    def __init__(self, fileName: str = "") -> None:
        self._file = fileName

    def isValid(self) -> bool:
        """False: no motion can be played."""
        return False

    def isOver(self) -> bool:
        """True: nothing plays."""
        return True

    def play(self) -> None:
        """Accepted; nothing plays."""

    def stop(self) -> None:
        """Accepted."""


class ContactPoint:
    """A contact point of a solid (``Node.getContactPoints``)."""

    def __init__(self, point: list[float] | None = None, node_id: int = -1) -> None:
        self.point = point or [0.0, 0.0, 0.0]
        self.node_id = node_id

    def getPoint(self) -> list[float]:
        """The point in the world frame (m)."""
        return self.point

    def getNodeId(self) -> int:
        """The id of the node in contact."""
        return self.node_id


class AnsiCodes:
    """ANSI escape codes for coloured console output, as Webots' module has them."""

    RESET = "\u001b[0m"
    BOLD = "\u001b[1m"
    UNDERLINE = "\u001b[4m"
    BLACK_BACKGROUND = "\u001b[40m"
    RED_BACKGROUND = "\u001b[41m"
    GREEN_BACKGROUND = "\u001b[42m"
    YELLOW_BACKGROUND = "\u001b[43m"
    BLUE_BACKGROUND = "\u001b[44m"
    MAGENTA_BACKGROUND = "\u001b[45m"
    CYAN_BACKGROUND = "\u001b[46m"
    WHITE_BACKGROUND = "\u001b[47m"
    BLACK_FOREGROUND = "\u001b[30m"
    RED_FOREGROUND = "\u001b[31m"
    GREEN_FOREGROUND = "\u001b[32m"
    YELLOW_FOREGROUND = "\u001b[33m"
    BLUE_FOREGROUND = "\u001b[34m"
    MAGENTA_FOREGROUND = "\u001b[35m"
    CYAN_FOREGROUND = "\u001b[36m"
    WHITE_FOREGROUND = "\u001b[37m"
    CLEAR_SCREEN = "\u001b[2J"
