"""Webots' ``controller.gps`` module: ``GPS``."""

from __future__ import annotations

from mazesim.webots.sensors import GPS

__all__ = ["GPS"]
