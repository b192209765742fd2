"""The former name of :mod:`mazesim.learn`, kept so that ``mazesim.hrl`` still imports.

Every public name of :mod:`mazesim.learn` is here as well; new code imports :mod:`mazesim.learn`.
"""

from __future__ import annotations

from mazesim.learn import *  # noqa: F403
from mazesim.learn import __all__  # noqa: F401
