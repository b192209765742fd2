"""Webots' ``controller.skin`` module: ``Skin``."""

from __future__ import annotations

from mazesim.webots.inert import Skin

__all__ = ["Skin"]
