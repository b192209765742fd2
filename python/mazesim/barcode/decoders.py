"""Barcode decoders over a ground-sensor stream: the report's Alg. 7 and an odometry-based one.

Both are fed one sample per control step (:meth:`Decoder.update`) and split the stream the same
way. On the grey floor of a maze (reflectance 0.36) the e-puck ground sensor reads 599 (noise
about 2), a white bar (1.0) 856 and a black bar (0.2) 300. A sample outside the *floor band*
``[floor_low, floor_high]`` (default ``[550, 650]``) starts a code, and the floor seen again ends
it. The sensor averages a 3 mm spot (3 x 3 points), so across a bar edge it reads a mix: across a
white/black edge met square on 691 or 803, across a black/floor edge 429 or 530 (still black),
across a white/floor edge 748 or 816 (still white), all outside the band. Met at an angle, the
spot can hold 2/9 white and 7/9 black, which reads 618: like the floor. Alg. 7 ends the code
there and reads two broken halves (its main failure here; the narrower band ``[586, 612]`` would
avoid it), while the robust decoder ends a code only after two floor samples at least 2 mm apart.
At the end of a code the decoder returns a :class:`Reading`: the checkpoint and direction of a
valid read, or "no valid read" with the reason.

:class:`Alg7Decoder` is the report's Alg. 7: it takes the middle sample of each fifth of the
samples and thresholds it at 700. It assumes the samples are spread evenly over the bars, which
holds when the robot crosses at a steady speed and heading.

:class:`RobustDecoder` places every sample along the code with wheel odometry (the sensor's
position in any fixed frame, e.g. from :class:`mazesim.barcode.Odometry`), so bar widths are
known in metres; diagonal crossings, turns, speed changes and even back-and-forth motion on the
code are decoded from where each sample was taken, and a reading that does not fit the geometry
of a code is refused instead of guessed.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt

from mazesim._sizes import number_array
from mazesim.barcode.codebook import ARRIVAL, CodeBook
from mazesim.errors import InvalidArgumentError, RegisteredName, WrongTypeError, _a_type

__all__ = [
    "BAR_LENGTH",
    "BIT_THRESHOLD",
    "DECODERS",
    "FLOOR_HIGH",
    "FLOOR_LOW",
    "Alg7Decoder",
    "Decoder",
    "Reading",
    "RobustDecoder",
    "make_decoder",
]

#: Lower end of the floor band: a reading below it is black (or a bar edge), not the floor.
FLOOR_LOW = 550.0
#: Upper end of the floor band: a reading above it is white (or a bar edge), not the floor.
FLOOR_HIGH = 650.0
#: Alg. 7's threshold: a reading at or above it is a white bar (bit 1), below it a black bar (0).
BIT_THRESHOLD = 700.0
#: Width of one bar along the direction of travel, metres (the report's 1.7 cm).
BAR_LENGTH = 0.017
#: Samples on one code after which a read is abandoned (about a minute at 32 ms a step).
MAX_SAMPLES = 2000
#: Consecutive floor samples that always end a code (a robot that stopped past its end).
FLOOR_RUN_LIMIT = 10

Position = tuple[float, float]


@dataclass(frozen=True)
class Reading:
    """The outcome of one pass over a code.

    Attributes:
        checkpoint: The checkpoint read, or None for "no valid read".
        direction: "arrival" (crossed along the checkpoint's yaw) or "departure", or None.
        bits: The bits the decoder settled on, in the order met ("" if it could not tell them).
        samples: How many ground-sensor samples the pass over the code gave.
        reason: Why the read is not valid ("" for a valid read).
    """

    checkpoint: int | None
    direction: str | None
    bits: str
    samples: int
    reason: str = ""

    @property
    def valid(self) -> bool:
        """True when the read names a checkpoint and a direction."""
        return self.checkpoint is not None

    @property
    def signed_id(self) -> int:
        """The read as the simulator's ``last_crossing``: +id arrival, -id departure, 0 none."""
        if self.checkpoint is None:
            return 0
        return self.checkpoint if self.direction == ARRIVAL else -self.checkpoint


class Decoder(ABC):
    """A streaming barcode decoder for one ground sensor.

    Call :meth:`update` once per control step with the sensor's reading (and, for decoders that
    use it, the sensor's position from odometry). It returns None while nothing ends and a
    :class:`Reading` in the step the sensor is back on the floor after a code.

    Args:
        book: The code book that turns bits into a checkpoint and a direction.
        floor_low: Readings below this are not the floor (black bars).
        floor_high: Readings above this are not the floor (white bars).
        bit_threshold: Readings at or above this are a 1 (white), below it a 0 (black).
        max_samples: Samples on one code after which the read is abandoned as "no valid read".
        floor_samples: Consecutive floor samples that end a code; fewer, followed by a code
            sample, were the sensor's spot across a bar edge and belong to the code.
        floor_distance: Path in metres the sensor must also cover on the floor (from the first
            to the last of those samples, by the positions given) before the code ends; 0 for
            none. :data:`FLOOR_RUN_LIMIT` floor samples end a code whatever the distance.

    Raises:
        InvalidArgumentError: The band is empty or the threshold lies inside it.
    """

    #: The decoder's name on the command line.
    name: ClassVar[str] = ""
    #: Whether :meth:`update` needs the sensor's position.
    needs_position: ClassVar[bool] = False

    def __init__(
        self,
        book: CodeBook,
        floor_low: float = FLOOR_LOW,
        floor_high: float = FLOOR_HIGH,
        bit_threshold: float = BIT_THRESHOLD,
        max_samples: int = MAX_SAMPLES,
        floor_samples: int = 1,
        floor_distance: float = 0.0,
    ) -> None:
        if not isinstance(book, CodeBook):
            raise WrongTypeError(f"expected a CodeBook, found {_a_type(book)}")
        numbers = {
            "floor_low": floor_low,
            "floor_high": floor_high,
            "bit_threshold": bit_threshold,
            "floor_distance": floor_distance,
        }
        for name, number in numbers.items():
            if not math.isfinite(number):
                raise InvalidArgumentError(f"expected {name} a finite number, found {number}")
        if floor_distance < 0.0:
            raise InvalidArgumentError(
                f"expected floor_distance of 0 or more metres, found {floor_distance}"
            )
        if not floor_low < floor_high:
            raise InvalidArgumentError(
                f"expected floor_low < floor_high, found {floor_low} and {floor_high}"
            )
        if floor_low <= bit_threshold <= floor_high:
            raise InvalidArgumentError(
                f"expected the bit threshold outside the floor band [{floor_low}, {floor_high}], "
                f"found {bit_threshold}"
            )
        if max_samples < 1:
            raise InvalidArgumentError(f"expected max_samples >= 1, found {max_samples}")
        if floor_samples < 1:
            raise InvalidArgumentError(f"expected floor_samples >= 1, found {floor_samples}")
        self.book = book
        self.floor_low = float(floor_low)
        self.floor_high = float(floor_high)
        self.bit_threshold = float(bit_threshold)
        self.max_samples = int(max_samples)
        self.floor_samples = int(floor_samples)
        self.floor_distance = float(floor_distance)
        self.reset()

    def reset(self) -> None:
        """Forgets the stream (after a reset or a teleport of the robot)."""
        self._values: list[float] = []
        self._positions: list[Position] = []
        self._before: Position | None = None
        self._abandoned = False
        self._previous: Position | None = None
        self._floor_run: list[tuple[float, Position | None]] = []

    @property
    def on_code(self) -> bool:
        """True while the sensor is on a code (the last sample was not the floor)."""
        return bool(self._values) or self._abandoned

    def note_floor(self, position: Position | None) -> None:
        """Records a floor sample at ``position`` while off a code, without decoding anything.

        The same as :meth:`update` with a floor reading when :attr:`on_code` is False; a batch
        reader calls it lazily for robots that stayed on the floor.
        """
        self._previous = position

    def is_floor(self, value: float) -> bool:
        """True when a reading lies in the floor band."""
        return self.floor_low <= value <= self.floor_high

    def update(self, ground: float, position: Position | None = None) -> Reading | None:
        """Feeds one ground-sensor sample.

        Args:
            ground: The barcode sensor's reading.
            position: The sensor's (x, y) in metres in a fixed odometry frame, if known.

        Returns:
            The reading of a code the sensor just left, or None.

        Raises:
            InvalidArgumentError: The decoder needs positions and none was given.
        """
        if position is None and self.needs_position:
            raise InvalidArgumentError(
                f"the {self.name} decoder needs the sensor's position from odometry each step"
            )
        value = float(ground)
        if self.is_floor(value):
            if not self.on_code:
                self._previous = position
                return None
            if self._abandoned:
                self._abandoned = False
                self._previous = position
                return None
            self._floor_run.append((value, position))
            if not self._floor_run_ends():
                return None
            after = self._floor_run[0][1]
            self._previous = position
            return self._end(after)
        if self._abandoned:
            return None
        if not self._values:
            self._before = self._previous
        # Floor readings followed by a code reading were part of the code (a spot across an edge).
        for floor_value, floor_position in self._floor_run:
            self._append(floor_value, floor_position)
        self._floor_run = []
        self._append(value, position)
        self._previous = position
        if len(self._values) > self.max_samples:
            count = len(self._values)
            self._values, self._positions = [], []
            self._abandoned = True
            return Reading(None, None, "", count, f"more than {self.max_samples} samples on a code")
        return None

    def _floor_run_ends(self) -> bool:
        """Whether the floor samples seen since the last code sample end the code."""
        run = len(self._floor_run)
        if run >= FLOOR_RUN_LIMIT:
            return True
        if run < self.floor_samples:
            return False
        if self.floor_distance <= 0.0:
            return True
        first, last = self._floor_run[0][1], self._floor_run[-1][1]
        if first is None or last is None:
            return True
        return math.hypot(last[0] - first[0], last[1] - first[1]) >= self.floor_distance

    def _append(self, value: float, position: Position | None) -> None:
        self._values.append(value)
        self._positions.append(position if position is not None else (math.nan, math.nan))

    def _end(self, after: Position | None) -> Reading:
        values = np.asarray(self._values, dtype=np.float64)
        positions = np.asarray(self._positions, dtype=np.float64).reshape(-1, 2)
        before = self._before
        self._values, self._positions, self._before, self._floor_run = [], [], None, []
        return self._decode(values, positions, before, after)

    def _result(self, bits: str, samples: int) -> Reading:
        found = self.book.lookup(bits)
        if found is None:
            return Reading(None, None, bits, samples, f"{bits} is no code of the book")
        checkpoint, direction = found
        return Reading(checkpoint, direction, bits, samples)

    @abstractmethod
    def _decode(
        self,
        values: npt.NDArray[np.float64],
        positions: npt.NDArray[np.float64],
        before: Position | None,
        after: Position | None,
    ) -> Reading:
        """Decodes the samples of one pass over a code."""


class Alg7Decoder(Decoder):
    """The report's Alg. 7 barcode reader.

    Reading starts when a sample is white or black (outside the floor band) and goes on until
    the floor is seen again. With ``k`` samples and ``n = k / 5`` (a real number), bit ``i``
    (1-based) is sample ``floor(n * i - n / 2)`` (0-based), the middle of the i-th fifth, read as
    1 when it is at least 700. The bits are looked up in the book (the report converts them to a
    decimal number and compares; the look-up is the same). It ignores positions.

    Examples:
        >>> from mazesim.barcode import CodeBook
        >>> decoder = Alg7Decoder(CodeBook({1: "10110"}))
        >>> stream = [600.0] + [856.0] * 4 + [300.0] * 4 + [856.0] * 8 + [300.0] * 4 + [600.0]
        >>> [r for r in map(decoder.update, stream) if r is not None]
        [Reading(checkpoint=1, direction='arrival', bits='10110', samples=20, reason='')]
    """

    name = "alg7"

    def _decode(
        self,
        values: npt.NDArray[np.float64],
        positions: npt.NDArray[np.float64],
        before: Position | None,
        after: Position | None,
    ) -> Reading:
        count = len(values)
        bars = self.book.code_length
        n = count / bars
        bits = []
        for i in range(1, bars + 1):
            index = min(max(int(math.floor(n * i - n / 2.0)), 0), count - 1)
            bits.append("1" if values[index] >= self.bit_threshold else "0")
        return self._result("".join(bits), count)


class RobustDecoder(Decoder):
    """An odometry-based decoder: it knows where along the code each sample was taken.

    The sensor enters the code half-way between the last floor sample and the first code sample,
    and leaves it half-way between the last code sample and the first floor sample after it.
    The code's axis ``d`` must satisfy ``d . (exit - entry) = 5 * bar_length``: that leaves two
    candidate axes, at +-acos(L / |exit - entry|) from the chord (one for a crossing along the
    axis). For each candidate every sample gets its coordinate ``u`` along the code, and bar
    ``i`` is read from the samples in its middle (``margin`` of a bar clear of each edge): they
    must all agree, and every change between consecutive samples must lie at an edge between
    bars of different colour. A pass is refused ("no valid read") when the chord is shorter
    than the code (the sensor turned back), implausibly long (more than ``max_angle`` off the
    axis), a bar has no sample in its middle, the samples disagree, the two candidate axes give
    different codes, or the bits are no code of the book.

    Args:
        book: The code book.
        bar_length: Width of a bar along the code, metres.
        margin: Share of a bar next to each edge whose samples are not used to read the bar.
        length_tolerance: How much shorter than the code the chord may be (odometry and the
            half-step uncertainty at both ends), as a share of the code's length.
        max_angle: Largest angle in radians between the chord and the code's axis.
        floor_samples: Consecutive floor samples that end a code, and
        floor_distance: the path in metres they must span: a floor-like reading of the spot
            across a bar edge at an angle (2/9 white reads ~618) spans a fraction of a
            millimetre, so it does not cut a code in two; such readings are not used.
        **kwargs: The floor band and thresholds of :class:`Decoder`.
    """

    name = "robust"
    needs_position = True

    def __init__(
        self,
        book: CodeBook,
        bar_length: float = BAR_LENGTH,
        margin: float = 0.2,
        length_tolerance: float = 0.15,
        max_angle: float = math.radians(75.0),
        floor_samples: int = 2,
        floor_distance: float = 0.002,
        **kwargs: Any,
    ) -> None:
        if not (bar_length > 0.0 and math.isfinite(bar_length)):
            raise InvalidArgumentError(f"expected a positive bar length, found {bar_length}")
        if not 0.0 <= margin < 0.5:
            raise InvalidArgumentError(f"expected a margin in [0, 0.5), found {margin}")
        if not 0.0 <= length_tolerance < 1.0:
            raise InvalidArgumentError(
                f"expected a length tolerance in [0, 1), found {length_tolerance}"
            )
        if not 0.0 <= max_angle < math.pi / 2:
            raise InvalidArgumentError(f"expected max_angle in [0, pi/2), found {max_angle}")
        self.bar_length = float(bar_length)
        self.margin = float(margin)
        self.length_tolerance = float(length_tolerance)
        self.max_angle = float(max_angle)
        super().__init__(book, floor_samples=floor_samples, floor_distance=floor_distance, **kwargs)

    def _decode(
        self,
        values: npt.NDArray[np.float64],
        positions: npt.NDArray[np.float64],
        before: Position | None,
        after: Position | None,
    ) -> Reading:
        count = len(values)
        if before is None or after is None:
            return Reading(None, None, "", count, "the pass over the code has no start or end")
        entry = 0.5 * (number_array(before, "before", nan_means="no position known") + positions[0])
        exit_ = 0.5 * (positions[-1] + number_array(after, "after", nan_means="no position known"))
        chord = exit_ - entry
        chord_length = float(math.hypot(chord[0], chord[1]))
        bars = self.book.code_length
        code_length = bars * self.bar_length
        if chord_length < code_length * (1.0 - self.length_tolerance):
            return Reading(
                None,
                None,
                "",
                count,
                f"left the code {chord_length * 100:.1f} cm from where it entered, "
                f"less than its length {code_length * 100:.1f} cm",
            )
        if chord_length * math.cos(self.max_angle) > code_length:
            return Reading(
                None, None, "", count, f"crossed over {chord_length * 100:.1f} cm: too oblique"
            )
        angle = math.acos(min(1.0, code_length / chord_length))
        heading = math.atan2(chord[1], chord[0])
        offsets = (0.0,) if angle < 1e-3 else (angle, -angle)
        bits_by_axis: list[str] = []
        reasons: list[str] = []
        is_white = values >= self.bit_threshold
        known = (values < self.floor_low) | (values > self.floor_high)
        for offset in offsets:
            axis = np.array([math.cos(heading + offset), math.sin(heading + offset)])
            scale = code_length / float(chord @ axis)
            along = ((positions - entry) @ axis) * scale / self.bar_length
            bits, reason = self._bits_along(along[known], is_white[known], bars)
            if bits is None:
                reasons.append(reason)
            else:
                bits_by_axis.append(bits)
        if not bits_by_axis:
            return Reading(None, None, "", count, reasons[0])
        if len(set(bits_by_axis)) > 1:
            return Reading(
                None, None, "", count, f"two readings fit the samples: {' or '.join(bits_by_axis)}"
            )
        return self._result(bits_by_axis[0], count)

    def _bits_along(
        self, along: npt.NDArray[np.float64], is_white: npt.NDArray[np.bool_], bars: int
    ) -> tuple[str | None, str]:
        """Bits from samples at ``along`` (in bar widths from the entry edge), or a reason."""
        slack = 2.0 * self.margin
        if along.min() < -slack or along.max() > bars + slack:
            return None, "the odometry puts samples off the code"
        bar_index = np.floor(along).astype(np.int64)
        within = along - bar_index
        middle = (within >= self.margin) & (within <= 1.0 - self.margin)
        bits = []
        for bar in range(bars):
            seen = is_white[middle & (bar_index == bar)]
            if seen.size == 0:
                return None, f"no sample in the middle of bar {bar + 1}"
            if seen.all():
                bits.append(True)
            elif not seen.any():
                bits.append(False)
            else:
                return None, f"bar {bar + 1} reads both white and black"
        # Every colour change between consecutive samples must cross an edge between bars of
        # different colours, within a margin of a bar. Samples within a margin of the code's
        # ends are left out: the spot there also sees the floor.
        inner = (along >= self.margin) & (along <= bars - self.margin)
        along, is_white = along[inner], is_white[inner]
        changes = np.flatnonzero(is_white[1:] != is_white[:-1])
        for change in changes:
            low, high = sorted((along[change], along[change + 1]))
            first_edge = max(1, math.ceil(low - self.margin))
            last_edge = min(bars - 1, math.floor(high + self.margin))
            if not any(bits[edge - 1] != bits[edge] for edge in range(first_edge, last_edge + 1)):
                return None, f"a colour change at {low:.2f}-{high:.2f} bars lies at no edge"
        return "".join("1" if bit else "0" for bit in bits), ""


#: The decoders by their command-line names.
DECODERS: dict[str, type[Decoder]] = {"alg7": Alg7Decoder, "robust": RobustDecoder}


def make_decoder(name: RegisteredName, book: CodeBook, **options: Any) -> Decoder:
    """A decoder by name ("alg7" or "robust") for a code book.

    Raises:
        UnknownNameError: No decoder has this name.
    """
    from mazesim.errors import _known_name

    cls = DECODERS[_known_name(name, "decoder", sorted(DECODERS))]
    return cls(book, **options)
