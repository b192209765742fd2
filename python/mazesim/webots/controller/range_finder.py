"""Webots' ``controller.range_finder`` module: ``RangeFinder``."""

from __future__ import annotations

from mazesim.webots.inert import RangeFinder

__all__ = ["RangeFinder"]
