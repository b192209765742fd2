"""Webots' ``controller.touch_sensor`` module: ``TouchSensor``."""

from __future__ import annotations

from mazesim.webots.sensors import TouchSensor

__all__ = ["TouchSensor"]
