"""Webots' ``controller.vacuum_gripper`` module: ``VacuumGripper``."""

from __future__ import annotations

from mazesim.webots.inert import VacuumGripper

__all__ = ["VacuumGripper"]
