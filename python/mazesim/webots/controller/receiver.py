"""Webots' ``controller.receiver`` module: ``Receiver``."""

from __future__ import annotations

from mazesim.webots.radio_devices import Receiver

__all__ = ["Receiver"]
