"""Webots' ``controller.receiver`` module: ``Receiver``."""

from __future__ import annotations

from mazesim.webots.inert import Receiver

__all__ = ["Receiver"]
