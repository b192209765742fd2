"""The four output buffers of a batch simulator, for tests that step one."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

import mazesim

#: Observations, poses, contact flags and crossings, one row per environment.
Buffers = tuple[
    npt.NDArray[np.float32], npt.NDArray[np.float32], npt.NDArray[np.bool_], npt.NDArray[np.int32]
]


def buffers(batch: mazesim.BatchSimulator) -> Buffers:
    """Zeroed output buffers of the shapes ``batch`` writes, as the binding makes them."""
    return batch.output_buffers()
