"""Webots' ``controller.camera`` module: ``Camera`` and ``CameraRecognitionObject``."""

from __future__ import annotations

from mazesim.webots.camera import Camera, CameraRecognitionObject

__all__ = ["Camera", "CameraRecognitionObject"]
