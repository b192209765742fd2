"""Webots' ``controller.keyboard`` module: ``Keyboard``."""

from __future__ import annotations

from mazesim.webots.keyboard import Keyboard

__all__ = ["Keyboard"]
