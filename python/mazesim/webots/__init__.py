"""Webots interoperability: import ``.wbt`` worlds, run Webots-style e-puck controllers.

- :func:`import_wbt` reads a Webots world (V8.5 to R2025a, NUE or ENU) into a mazesim
  :class:`~mazesim.World` and a report of what was imported and what was not.
- :mod:`mazesim.webots.controller` is Webots' Python ``controller`` module for the e-puck (every
  class, the e-puck's devices, extension-slot devices, keyboard script, supervisor);
  :func:`run_controller` runs an unmodified controller file on it, as
  ``mazesim webots run CONTROLLER.py`` does, and keeps the run whatever the controller does.

Examples:
    >>> import mazesim.webots
    >>> world, report = mazesim.webots.import_wbt("tests/data/webots-worlds/e-puck.R2023b.wbt")
    >>> len(report["obstacles"]), report["robot"]["yaw"]
    (9, 1.57)
"""

from __future__ import annotations

from mazesim.webots.importer import ImportReport, import_wbt, import_wbt_text
from mazesim.webots.runner import ControllerRun, run_controller
from mazesim.webots.simulation import RobotSimulation, prepare

__all__ = [
    "ControllerRun",
    "ImportReport",
    "RobotSimulation",
    "import_wbt",
    "import_wbt_text",
    "prepare",
    "run_controller",
]
