"""The errors of the gymnasium environments, and the checks of ``reset``'s arguments that the single
and the vector env share, so that both refuse the same misuse with the same error.

Each error is a :class:`mazesim.MazesimError` and also the error gymnasium defines for the case
(``except gymnasium.error.ClosedEnvironmentError`` keeps working):

- :class:`EnvClosedError`: ``reset``, ``step`` or ``render`` after ``close()``;
- :class:`ResetNeededError`: ``step`` before the first ``reset``;
- :class:`~mazesim.errors.InvalidArgumentError`: a seed that is not an int in ``0..=2**64-1``
  (or, for the vector env, a list of them), options that are not a dict, or a misspelling of
  an option the env reads (it was ignored without a word).
"""

from __future__ import annotations

import numbers
from collections.abc import Mapping
from typing import Any

from gymnasium.error import ClosedEnvironmentError, ResetNeeded

from mazesim.errors import (
    InvalidArgumentError,
    MazesimError,
    WrongTypeError,
    _a_type,
    _closest_name,
    _shown,
)

__all__ = [
    "MAX_SEED",
    "EnvClosedError",
    "ResetNeededError",
    "check_options",
    "check_seed",
    "is_seed",
]

#: The largest seed an env takes: the simulators' seeds are 64-bit.
MAX_SEED = 2**64 - 1


class EnvClosedError(MazesimError, ClosedEnvironmentError):
    """The env was closed: make a new one."""


class ResetNeededError(MazesimError, ResetNeeded):
    """``step`` was called before ``reset``."""


def is_seed(seed: Any) -> bool:
    """Whether ``seed`` is one seed: a Python or numpy integer in ``0..=MAX_SEED``, not a bool."""
    return (
        isinstance(seed, numbers.Integral)
        and not isinstance(seed, bool)
        and 0 <= int(seed) <= MAX_SEED
    )


def check_seed(seed: Any) -> int | None:
    """``seed`` as an int, or None.

    Raises:
        InvalidArgumentError: Not None and not a seed (:func:`is_seed`).
    """
    if seed is None:
        return None
    if not is_seed(seed):
        raise InvalidArgumentError(
            f"expected seed to be None or an int in 0..={MAX_SEED}, found {_shown(seed)}"
        )
    return int(seed)


def check_options(options: Any, known: tuple[str, ...] = ()) -> Mapping[str, Any]:
    """``reset``'s options as a mapping (empty for None).

    An option close to one of ``known`` but not it (``reset_mak`` for ``reset_mask``) is refused
    as the misspelling it is; any other key is left alone, as Gymnasium and PettingZoo expect of
    an env (wrappers pass options of their own, and PettingZoo's API test resets with
    ``{"options": 1}``).

    Raises:
        InvalidArgumentError: Neither None nor a dict (a ``WrongTypeError``), or an option that
            is a misspelling of one of ``known``.
    """
    if options is None:
        return {}
    if not isinstance(options, Mapping):
        raise WrongTypeError(f"expected options to be None or a dict, found {_a_type(options)}")
    for key in options:
        meant = None if key in known else _closest_name(str(key), list(known))
        if meant is not None:
            raise InvalidArgumentError(
                f"expected reset options among {', '.join(map(repr, known))}, found {_shown(key)}; "
                f"did you mean {_shown(meant)}?"
            )
    return options
