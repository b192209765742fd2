"""Webots' ``controller.radar`` module: ``Radar`` and ``RadarTarget``."""

from __future__ import annotations

from mazesim.webots.inert import Radar, RadarTarget

__all__ = ["Radar", "RadarTarget"]
