"""Webots' ``controller.gyro`` module: ``Gyro``."""

from __future__ import annotations

from mazesim.webots.sensors import Gyro

__all__ = ["Gyro"]
