"""Webots' ``controller.light_sensor`` module: ``LightSensor``."""

from __future__ import annotations

from mazesim.webots.sensors import LightSensor

__all__ = ["LightSensor"]
