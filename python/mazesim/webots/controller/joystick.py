"""Webots' ``controller.joystick`` module: ``Joystick``."""

from __future__ import annotations

from mazesim.webots.keyboard import Joystick

__all__ = ["Joystick"]
