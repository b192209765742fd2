"""Deprecated: the former name of :mod:`mazesim.learn`, whose every public name it gives; importing
it warns (:class:`DeprecationWarning`). Import :mod:`mazesim.learn` instead."""

from __future__ import annotations

import warnings

from mazesim.learn import *  # noqa: F403
from mazesim.learn import __all__  # noqa: F401

warnings.warn(
    "mazesim.hrl is deprecated and will be removed: import mazesim.learn instead",
    DeprecationWarning,
    stacklevel=2,
)
