"""Measuring mazesim: steady-state throughput, contact share and memory per env of a batch
under a named workload (what ``mazesim bench`` runs; docs/performance.md)."""

from __future__ import annotations

from .steady import MAZE_KINDS, MIN_WARMUP_STEPS, BenchSettings, Block, SteadyState, measure
from .workloads import WORKLOADS, Workload, braitenberg, make_workload

__all__ = [
    "MAZE_KINDS",
    "MIN_WARMUP_STEPS",
    "WORKLOADS",
    "BenchSettings",
    "Block",
    "SteadyState",
    "Workload",
    "braitenberg",
    "make_workload",
    "measure",
]
