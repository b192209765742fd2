"""The fields of settings dataclasses: command-line options are generated from them, and their
declared choices and ranges are checked when a dataclass is made.

A field made by :func:`setting` carries its option's help text, ``metavar``, ``choices``, shown
default and range in its metadata; ``mazesim train``, ``mazesim eval`` and ``mazesim bench`` add
one option per such field (``mazesim.cli._args.add_setting_options``), so the dataclass holds the
only default, the only help text and the only range. A field made by :func:`bounded` is no option
but has a range all the same. :func:`check_settings`, called by each dataclass when it is made,
refuses a value out of its field's choices or range as the option would: a range is declared once
and holds for a dataclass made in Python too (``TrainSettings(envs=-1)`` was taken, and failed
later inside numpy).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import field, fields
from typing import Any

__all__ = ["MAX_COUNT", "MAX_SEED", "RANGE_KEYS", "bounded", "check_settings", "setting"]

#: The largest count a setting or a command's option takes (envs, episodes, readings...).
MAX_COUNT = 2**31 - 1
#: The largest seed: seeds are 64-bit.
MAX_SEED = 2**64 - 1


def _range(least: float | None, most: float | None, above: float | None) -> dict[str, float]:
    return {
        key: value
        for key, value in (("least", least), ("most", most), ("above", above))
        if value is not None
    }


#: The metadata keys of a range; ``finite`` alone: any finite number.
RANGE_KEYS = ("least", "most", "above", "finite")


def setting(
    default: Any,
    help: str,  # noqa: A002 - the name argparse and the metadata use
    metavar: str | None = None,
    *,
    choices: tuple[str, ...] | None = None,
    default_text: str | None = None,
    least: float | None = None,
    most: float | None = None,
) -> Any:
    """A dataclass field of ``default`` offered as a command-line option: ``help`` its text,
    ``metavar`` its value's name (or ``choices`` its values), ``default_text`` the default shown
    in place of the value, ``least`` and ``most`` its range (a whole-number field's option takes
    it too)."""
    metadata: dict[str, Any] = {"help": help, **_range(least, most, None)}
    for key, value in (("metavar", metavar), ("choices", choices), ("default_text", default_text)):
        if value is not None:
            metadata[key] = value
    return field(default=default, metadata=metadata)


def bounded(
    default: Any,
    *,
    least: float | None = None,
    most: float | None = None,
    above: float | None = None,
) -> Any:
    """A dataclass field of ``default`` with a range (no command-line option): at least
    ``least``, at most ``most``, above ``above`` (none of them: any finite number); a whole
    number when ``default`` is one."""
    return field(default=default, metadata=_range(least, most, above) or {"finite": True})


def _range_text(whole: bool, meta: dict[str, Any]) -> str:
    def bound(value: float) -> str:
        return f"{value:,}" if whole else f"{value:g}"

    kind = "a whole number" if whole else "a finite number"
    least, most, above = meta.get("least"), meta.get("most"), meta.get("above")
    if least is not None and most is not None:
        return f"{kind} from {bound(least)} to {bound(most)}"
    parts = [
        f"{words} {bound(value)}"
        for words, value in (("above", above), ("at least", least), ("at most", most))
        if value is not None
    ]
    if not parts:
        return kind
    return f"{kind} {'of ' if parts[0].startswith('at') else ''}{' and '.join(parts)}"


def check_settings(settings: Any) -> None:
    """Refuses a field's value that is not one of its ``choices`` (an ``UnknownNameError``
    listing them) or not in its range (an ``InvalidArgumentError`` naming the field, the range
    and the value), as its command-line option would."""
    from mazesim.errors import InvalidArgumentError, WrongTypeError, _a_type, _known_name, _shown

    for each in fields(settings):
        meta = each.metadata
        value = getattr(settings, each.name)
        if meta.get("choices") is not None:
            _known_name(value, each.name, meta["choices"])
        if not any(key in meta for key in RANGE_KEYS):
            continue
        name = f"{type(settings).__name__}.{each.name}"
        whole = isinstance(each.default, int) and not isinstance(each.default, bool)
        kind = numbers.Integral if whole else numbers.Real
        if isinstance(value, bool) or not isinstance(value, kind):
            expected = "a whole number" if whole else "a number"
            raise WrongTypeError(f"expected {name} to be {expected}, found {_a_type(value)}")
        fits = (
            (whole or math.isfinite(value))
            and value >= meta.get("least", -math.inf)
            and value <= meta.get("most", math.inf)
            and ("above" not in meta or value > meta["above"])
        )
        if not fits:
            raise InvalidArgumentError(
                f"expected {name} to be {_range_text(whole, dict(meta))}, found {_shown(value)}"
            )
