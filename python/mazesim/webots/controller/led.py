"""Webots' ``controller.led`` module: ``LED``."""

from __future__ import annotations

from mazesim.webots.devices import LED

__all__ = ["LED"]
