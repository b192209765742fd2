"""Webots' ``controller.lidar`` module: ``Lidar`` and ``LidarPoint``."""

from __future__ import annotations

from mazesim.webots.inert import Lidar, LidarPoint

__all__ = ["Lidar", "LidarPoint"]
