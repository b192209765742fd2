"""Webots' ``controller.emitter`` module: ``Emitter``."""

from __future__ import annotations

from mazesim.webots.inert import Emitter

__all__ = ["Emitter"]
