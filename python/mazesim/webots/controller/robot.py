"""Webots' ``controller.robot`` module: ``Robot``."""

from __future__ import annotations

from mazesim.webots.robot import Robot

__all__ = ["Robot"]
