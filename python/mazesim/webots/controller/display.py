"""Webots' ``controller.display`` module: ``Display``."""

from __future__ import annotations

from mazesim.webots.inert import Display

__all__ = ["Display"]
