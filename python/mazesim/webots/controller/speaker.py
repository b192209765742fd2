"""Webots' ``controller.speaker`` module: ``Speaker``."""

from __future__ import annotations

from mazesim.webots.inert import Speaker

__all__ = ["Speaker"]
