"""Webots' ``controller.inertial_unit`` module: ``InertialUnit``."""

from __future__ import annotations

from mazesim.webots.sensors import InertialUnit

__all__ = ["InertialUnit"]
