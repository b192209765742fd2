"""Webots' ``controller.distance_sensor`` module: ``DistanceSensor``."""

from __future__ import annotations

from mazesim.webots.devices import DistanceSensor

__all__ = ["DistanceSensor"]
