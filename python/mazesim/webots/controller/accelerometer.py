"""Webots' ``controller.accelerometer`` module: ``Accelerometer``."""

from __future__ import annotations

from mazesim.webots.sensors import Accelerometer

__all__ = ["Accelerometer"]
