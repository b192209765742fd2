"""Webots' ``controller.pen`` module: ``Pen``."""

from __future__ import annotations

from mazesim.webots.inert import Pen

__all__ = ["Pen"]
