"""Webots' ``controller.altimeter`` module: ``Altimeter``."""

from __future__ import annotations

from mazesim.webots.inert import Altimeter

__all__ = ["Altimeter"]
