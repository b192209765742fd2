"""The registry of mazesim's public surface and the hostile values fed to it (see registry.py)."""
