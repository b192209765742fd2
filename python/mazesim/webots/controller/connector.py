"""Webots' ``controller.connector`` module: ``Connector``."""

from __future__ import annotations

from mazesim.webots.inert import Connector

__all__ = ["Connector"]
