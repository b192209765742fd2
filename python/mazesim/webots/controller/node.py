"""Webots' ``controller.node`` module: ``ContactPoint`` and ``Node``."""

from __future__ import annotations

from mazesim.webots.inert import ContactPoint
from mazesim.webots.supervisor import Node

__all__ = ["ContactPoint", "Node"]
