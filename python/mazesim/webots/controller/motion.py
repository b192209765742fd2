"""Webots' ``controller.motion`` module: ``Motion``."""

from __future__ import annotations

from mazesim.webots.inert import Motion

__all__ = ["Motion"]
