"""Webots' ``controller.mouse`` module: ``Mouse`` and ``MouseState``."""

from __future__ import annotations

from mazesim.webots.keyboard import Mouse, MouseState

__all__ = ["Mouse", "MouseState"]
