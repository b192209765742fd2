"""Whether the running code is the package's own or its user's.

The argument check at the public surface (:mod:`mazesim._checks`) checks a call from outside
once, not the calls the package then makes to itself; user code that the package runs from inside
one of its calls (a Webots controller) calls from outside again (:func:`users_code`).
"""

from __future__ import annotations

import contextlib
import threading
from collections.abc import Iterator

__all__ = ["STATE", "thread_flag", "users_code"]

#: Per thread, whether a checked call is running (``STATE.inside``): the calls it makes to other
#: public functions are the package's own and are not checked again (the check costs once per
#: call from outside, not once per helper in a step).
STATE = threading.local()


@contextlib.contextmanager
def thread_flag(state: threading.local, name: str, value: bool) -> Iterator[None]:
    """Within it, this thread's flag ``name`` of ``state`` is ``value``; as it was after (False
    where it was never set)."""
    before = getattr(state, name, False)
    setattr(state, name, value)
    try:
        yield
    finally:
        setattr(state, name, before)


def users_code() -> contextlib.AbstractContextManager[None]:
    """Runs the user's own code (a controller the package executes) as a caller from outside:
    its calls to public functions are checked, as they would be from a script of its own,
    instead of passing as the package's calls to itself (a controller's
    ``motor.setVelocity("fast")`` raised the ``ValueError`` of a line deep in the package)."""
    return thread_flag(STATE, "inside", False)
