"""Barcode readers: a decoder wired to a simulator's ground sensor and wheel encoders.

:class:`BarcodeReader` reads for one :class:`mazesim.Simulator`; :class:`BatchBarcodeReader`
for the N robots of a :class:`mazesim.BatchSimulator` (one decoder per robot), touching in Python
only the robots whose sensor is on a code, so a large batch costs little more than a small one.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from mazesim._core import RobotProfile, Simulator
from mazesim._sizes import number_array
from mazesim.barcode.decoders import Decoder, Reading
from mazesim.barcode.odometry import Odometry, _as_mask, barcode_sensor_index
from mazesim.errors import InvalidArgumentError, WrongTypeError, _a_type, _shown

__all__ = ["BarcodeReader", "BatchBarcodeReader"]


class BarcodeReader:
    """Feeds one simulator's barcode sensor and encoders to a decoder, one step at a time.

    Args:
        decoder: The decoder (its state is this reader's).
        robot: The robot profile, to find the barcode sensor and for odometry.

    Example:
        >>> import mazesim
        >>> from mazesim.barcode import BarcodeReader, CodeBook, RobustDecoder
        >>> world = mazesim.load_world("seed-maze")
        >>> sim = mazesim.Simulator(world, robot="seed", seed=0)
        >>> reader = BarcodeReader(RobustDecoder(CodeBook.from_world(world)), sim.robot)
        >>> reader.update(sim)  # call after each sim.step(...); None until a code ends
    """

    def __init__(self, decoder: Decoder, robot: RobotProfile) -> None:
        if not isinstance(decoder, Decoder):
            raise WrongTypeError(f"expected a Decoder, found {_a_type(decoder)}")
        self.decoder = decoder
        self.robot = robot
        #: The simulator whose robot was found to be ``robot`` (checked once, not every step).
        self._checked: Simulator | None = None
        self.sensor_index = barcode_sensor_index(robot)
        self.odometry = Odometry(robot, 1, self.sensor_index)

    def reset(self) -> None:
        """Forgets the stream; call it after resetting or teleporting the simulator."""
        self.decoder.reset()
        self.odometry.reset()

    def update(self, simulator: Simulator) -> Reading | None:
        """Reads the simulator's barcode sensor and encoders after a step.

        Returns:
            The reading of a code the sensor just left, or None.

        Raises:
            InvalidArgumentError: The simulator's robot is not the one the reader was made for
                (another sensor, another wheel geometry for its odometry).
        """
        if simulator is not self._checked and simulator.robot != self.robot:
            raise InvalidArgumentError(
                f"expected a simulator of the robot {_shown(self.robot.name)} the reader was made "
                f"for, found one of {_shown(simulator.robot.name)}; make the reader with the "
                "simulator's robot: BarcodeReader(decoder, simulator.robot)"
            )
        self._checked = simulator
        ground = float(simulator.ground_sensors()[self.sensor_index])
        position = self.odometry.update(simulator.encoders)[0]
        return self.decoder.update(ground, (float(position[0]), float(position[1])))


class BatchBarcodeReader:
    """One decoder per robot of a batch, fed from the batch's arrays.

    Args:
        decoders: One decoder per robot (N of them, all with the same floor band).
        robot: The robot profile of the batch.

    Raises:
        InvalidArgumentError: No decoders, one decoder given for two robots, or decoders with
            different floor bands.
    """

    def __init__(self, decoders: Sequence[Decoder], robot: RobotProfile) -> None:
        self.decoders = list(decoders)
        if not self.decoders:
            raise InvalidArgumentError("expected at least one decoder, found none")
        first_of: dict[int, int] = {}
        for index, decoder in enumerate(self.decoders):
            earlier = first_of.setdefault(id(decoder), index)
            if earlier != index:
                # A decoder holds its robot's samples: shared, two robots' readings mix.
                raise InvalidArgumentError(
                    f"expected a decoder of its own for each robot, found decoders[{earlier}] "
                    f"given again as decoders[{index}] (`[decoder] * n` repeats one object: "
                    "make each, e.g. `[make_decoder(...) for _ in range(n)]`)"
                )
        bands = {(d.floor_low, d.floor_high) for d in self.decoders}
        if len(bands) != 1:
            raise InvalidArgumentError(
                f"expected one floor band for all decoders of a batch, found {sorted(bands)}"
            )
        ((self.floor_low, self.floor_high),) = bands
        self.num_envs = len(self.decoders)
        self.sensor_index = barcode_sensor_index(robot)
        self.needs_position = any(d.needs_position for d in self.decoders)
        self.odometry = Odometry(robot, self.num_envs, self.sensor_index)
        self._on_code = np.zeros(self.num_envs, dtype=bool)
        self._previous: npt.NDArray[np.float64] | None = None

    def reset(self, mask: npt.ArrayLike | None = None) -> None:
        """Forgets the streams of the robots in ``mask`` (all by default)."""
        flags = _as_mask(mask, self.num_envs)
        for index in np.flatnonzero(flags):
            self.decoders[index].reset()
        self._on_code[flags] = False
        self.odometry.reset(flags)
        if self._previous is not None:
            self._previous[flags] = np.nan

    def update(
        self,
        ground: npt.ArrayLike,
        encoders: npt.ArrayLike | None = None,
        mask: npt.ArrayLike | None = None,
    ) -> list[tuple[int, Reading]]:
        """Feeds one step of every robot, or of the robots in ``mask``.

        Args:
            ground: (N,) barcode sensor readings (the batch's observation column of the sensor).
            encoders: (N, 2) wheel angles in radians; needed when a decoder uses positions.
                Odometry follows every robot whatever the mask.
            mask: (N,) robots whose decoders get this sample (all by default); the others'
                decoders do not see it, as if it were lost.

        Returns:
            (robot index, reading) for every robot whose sensor just left a code, in index order.
        """
        values = number_array(ground, "ground").reshape(-1)
        if values.shape != (self.num_envs,):
            raise InvalidArgumentError(
                f"expected ground readings of shape ({self.num_envs},), found {values.shape}"
            )
        positions: npt.NDArray[np.float64] | None = None
        if encoders is not None:
            positions = self.odometry.update(encoders)
        elif self.needs_position:
            raise InvalidArgumentError("the decoders need the wheel encoders each step")
        fed = _as_mask(mask, self.num_envs)
        off_floor = (values < self.floor_low) | (values > self.floor_high)
        busy = np.flatnonzero((off_floor | self._on_code) & fed)
        readings: list[tuple[int, Reading]] = []
        for index in busy:
            decoder = self.decoders[index]
            position = None if positions is None else (positions[index, 0], positions[index, 1])
            if not self._on_code[index] and self._previous is not None:
                before = self._previous[index]
                decoder.note_floor(None if np.isnan(before[0]) else (before[0], before[1]))
            reading = decoder.update(values[index], position)
            self._on_code[index] = decoder.on_code
            if reading is not None:
                readings.append((int(index), reading))
        if positions is not None:
            if self._previous is None or mask is None:
                self._previous = positions
            else:
                self._previous[fed] = positions[fed]
        return readings
