"""Webots' ``controller.position_sensor`` module: ``PositionSensor``."""

from __future__ import annotations

from mazesim.webots.devices import PositionSensor

__all__ = ["PositionSensor"]
