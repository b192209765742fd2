"""Webots' ``controller.emitter`` module: ``Emitter``."""

from __future__ import annotations

from mazesim.webots.radio_devices import Emitter

__all__ = ["Emitter"]
