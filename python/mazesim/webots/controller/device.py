"""Webots' ``controller.device`` module: ``Device``."""

from __future__ import annotations

from mazesim.webots.devices import Device

__all__ = ["Device"]
