"""Webots' ``controller.compass`` module: ``Compass``."""

from __future__ import annotations

from mazesim.webots.sensors import Compass

__all__ = ["Compass"]
