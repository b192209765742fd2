"""Webots' ``controller.ansi_codes`` module: ``AnsiCodes``."""

from __future__ import annotations

from mazesim.webots.inert import AnsiCodes

__all__ = ["AnsiCodes"]
