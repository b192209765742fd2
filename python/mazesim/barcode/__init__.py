"""Floor barcodes: code books, decoders, readers and the reading study (report section 4.2).

A checkpoint is a code of five bars of 1.7 cm (white = 1, black = 0) across a corridor on a grey
floor; the robot reads it with the ground sensor nearest its centre line. Crossing it along the
checkpoint's yaw (arriving) reads the code as written, crossing it the other way (departing)
reads it backwards, so one reading tells the checkpoint and the direction.

- :class:`CodeBook`: which code each checkpoint carries, looked up both ways.
- :class:`Alg7Decoder` (the report's Alg. 7) and :class:`RobustDecoder` (wheel odometry places
  each sample along the code): streaming decoders fed one ground-sensor sample per step.
- :class:`BarcodeReader` / :class:`BatchBarcodeReader`: decoders wired to a
  :class:`mazesim.Simulator` or to the arrays of a :class:`mazesim.BatchSimulator`, with
  :class:`Odometry` and :class:`WheelEncoders`.
- :mod:`mazesim.barcode.study`: the reading study of the report's Fig. 4.3 and 4.5
  (``mazesim barcode-study``).

Example:
    >>> import mazesim
    >>> from mazesim.barcode import BarcodeReader, CodeBook, RobustDecoder
    >>> world = mazesim.load_world("seed-maze")
    >>> sim = mazesim.Simulator(world, robot="seed", seed=0)
    >>> reader = BarcodeReader(RobustDecoder(CodeBook.from_world(world)), sim.robot)
    >>> readings = []
    >>> for _ in range(200):
    ...     sim.step(3.14, 3.14)
    ...     reading = reader.update(sim)
    ...     if reading is not None:
    ...         readings.append((reading.checkpoint, reading.direction))
    >>> readings, [(c["checkpoint"], c["direction"]) for c in sim.crossings()]
    ([(1, 'arrival')], [(1, 'arrival')])
"""

from __future__ import annotations

from mazesim.barcode.codebook import ARRIVAL, DEPARTURE, CodeBook
from mazesim.barcode.decoders import (
    BAR_LENGTH,
    BIT_THRESHOLD,
    DECODERS,
    FLOOR_HIGH,
    FLOOR_LOW,
    Alg7Decoder,
    Decoder,
    Reading,
    RobustDecoder,
    make_decoder,
)
from mazesim.barcode.odometry import Odometry, WheelEncoders, barcode_sensor_index
from mazesim.barcode.reader import BarcodeReader, BatchBarcodeReader

__all__ = [
    "ARRIVAL",
    "BAR_LENGTH",
    "BIT_THRESHOLD",
    "DECODERS",
    "DEPARTURE",
    "FLOOR_HIGH",
    "FLOOR_LOW",
    "Alg7Decoder",
    "BarcodeReader",
    "BatchBarcodeReader",
    "CodeBook",
    "Decoder",
    "Odometry",
    "Reading",
    "RobustDecoder",
    "WheelEncoders",
    "barcode_sensor_index",
    "make_decoder",
]
