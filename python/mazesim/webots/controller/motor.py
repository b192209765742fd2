"""Webots' ``controller.motor`` module: ``Motor``."""

from __future__ import annotations

from mazesim.webots.devices import Motor

__all__ = ["Motor"]
