"""Webots' ``controller.supervisor`` module: ``Supervisor``."""

from __future__ import annotations

from mazesim.webots.supervisor import Supervisor

__all__ = ["Supervisor"]
