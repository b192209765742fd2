"""The optional packages of :mod:`mazesim.ros2`, checked without importing them.

:func:`require_ros2` turns a missing ``cyclonedds`` or ``rosbags`` into a
:class:`~mazesim.errors.MissingDependencyError` that says what to install, at once.
"""

from __future__ import annotations

import importlib.util
import sys

from mazesim.errors import MissingDependencyError

__all__ = ["ROS2_PACKAGES", "require_ros2"]

#: The import name of each package the ROS 2 bridge needs, with its PyPI name.
ROS2_PACKAGES = {"cyclonedds": "cyclonedds", "rosbags": "rosbags"}


def require_ros2() -> None:
    """Checks that ``cyclonedds`` and ``rosbags`` are importable.

    Raises:
        MissingDependencyError: One is missing; the message names it and how to install it.
    """
    missing = [
        pypi for module, pypi in ROS2_PACKAGES.items() if importlib.util.find_spec(module) is None
    ]
    if missing:
        raise MissingDependencyError(
            f"mazesim ros2 needs {' and '.join(missing)}, which {sys.executable} cannot import: "
            f"run 'pip install \"mazesim[ros2]\"' (in a checkout: 'make ros2-deps'); no ROS 2 "
            f"installation is needed"
        )
