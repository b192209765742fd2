"""Webots' ``controller.brake`` module: ``Brake``."""

from __future__ import annotations

from mazesim.webots.inert import Brake

__all__ = ["Brake"]
