"""Bridges from mazesim's environments to other RL libraries (each an optional extra).

- :mod:`mazesim.integrations.sb3`: Stable-Baselines3 (``pip install "mazesim[sb3]"``).
"""
