"""Deprecated: the former name of :mod:`mazesim.learn`, kept for a deprecation period.

Importing it warns (:class:`DeprecationWarning`) and gives every public name of
:mod:`mazesim.learn`; import :mod:`mazesim.learn` instead. Nothing inside mazesim imports it.
"""

from __future__ import annotations

import warnings

from mazesim.learn import *  # noqa: F403
from mazesim.learn import __all__  # noqa: F401

warnings.warn(
    "mazesim.hrl is deprecated and will be removed: import mazesim.learn instead",
    DeprecationWarning,
    stacklevel=2,
)
