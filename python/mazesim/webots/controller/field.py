"""Webots' ``controller.field`` module: ``Field``."""

from __future__ import annotations

from mazesim.webots.supervisor import Field

__all__ = ["Field"]
