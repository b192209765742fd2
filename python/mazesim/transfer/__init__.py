"""The sim-to-real transfer study: a navigator on a grid of perturbations of its robot.

:func:`run_study` drives a hierarchical navigator in its world with the robot perturbed along the
axes of :mod:`mazesim.transfer.axes`, one axis at a time and in pairs, through the batch engine,
and measures success, contacts and path ratio per cell (:class:`StudyResult`, whose JSON form is
checked by :func:`check_study_json`); :mod:`mazesim.transfer.heatmap` draws the heat maps.
``mazesim transfer-study`` is its command.
"""

from mazesim.transfer.axes import AXES, AXIS_NAMES, Axis, Setting, axis_named, parse_axes
from mazesim.transfer.result import STUDY_SCHEMA, Cell, StudyResult, check_study_json
from mazesim.transfer.study import StudyOptions, run_study, study_size

__all__ = [
    "AXES",
    "AXIS_NAMES",
    "STUDY_SCHEMA",
    "Axis",
    "Cell",
    "Setting",
    "StudyOptions",
    "StudyResult",
    "axis_named",
    "check_study_json",
    "parse_axes",
    "run_study",
    "study_size",
]
