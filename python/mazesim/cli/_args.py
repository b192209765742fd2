"""Argument types of the ``mazesim`` command line.

Each type takes the text of one argument and returns its value, or raises
:class:`argparse.ArgumentTypeError` with a message that says what was expected and what was
found (argparse prints it as ``mazesim COMMAND: error: argument --X: <message>``, exit code 2).
This module imports nothing heavy: every command's parser uses it.
"""

from __future__ import annotations

import argparse
import dataclasses
import decimal
import functools
import math
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from mazesim._paths import output_path
from mazesim._settings import MAX_COUNT
from mazesim.errors import _closest_name, _shown

__all__ = [
    "MAX_COUNT",
    "add_out_folder",
    "add_seed_option",
    "add_setting_options",
    "MAX_NUMBER",
    "MAX_SECONDS",
    "name_list",
    "non_negative_int",
    "non_negative_seconds",
    "output_path",
    "positive_int",
    "positive_number",
    "positive_seconds",
    "seed_argument",
    "whole_number",
]

#: The most simulated seconds a command runs for (11.6 days).
MAX_SECONDS = 1e6
#: The largest number a positive-number option takes.
MAX_NUMBER = 1e9


def _positive_float(text: str, what: str, largest: float) -> float:
    """A finite number in (0, largest]; ``what`` names it in the message ("number of seconds")."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a {what}, found {_shown(text)}") from None
    if not math.isfinite(value) or not 0.0 < value <= largest:
        raise argparse.ArgumentTypeError(
            f"expected a positive {what} of at most {largest:g}, found {_shown(text)}"
        )
    return value


def positive_seconds(text: str) -> float:
    """A positive number of seconds, at most :data:`MAX_SECONDS`."""
    return _positive_float(text, "number of seconds", MAX_SECONDS)


def non_negative_seconds(text: str) -> float:
    """A number of seconds of at least 0 (0 often means "until stopped")."""
    if text.strip() in ("0", "0.0"):
        return 0.0
    return positive_seconds(text)


def positive_number(text: str) -> float:
    """A finite number above 0, at most :data:`MAX_NUMBER`."""
    return _positive_float(text, "number", MAX_NUMBER)


#: The suffixes a count may end with (``500k``, ``36M``), and what they multiply by.
COUNT_SUFFIXES = {"k": 1_000, "K": 1_000, "m": 1_000_000, "M": 1_000_000}


def whole_number(text: str, smallest: int, largest: int = MAX_COUNT) -> int:
    """A whole number in ``[smallest, largest]``, written as a person would: ``1000``,
    ``1_000``, ``1k``, ``1.5M`` (the one reader of every count the commands take). A value that
    is not whole once its suffix is applied (``1.5555k``) is refused, naming the value understood,
    never rounded.

    Raises:
        argparse.ArgumentTypeError: ``text`` is not such a number (argparse prints the message).
    """
    cleaned = text.strip().replace("_", "")
    scale = COUNT_SUFFIXES.get(cleaned[-1:], 1)
    digits = cleaned[:-1] if scale > 1 else cleaned
    try:
        exact = decimal.Decimal(digits)
    except decimal.DecimalException:
        exact = decimal.Decimal("NaN")
    if not exact.is_finite():
        raise argparse.ArgumentTypeError(
            f"expected a whole number such as 1000, 1_000, 500k or 2M, found {_shown(text)}"
        )
    # A count has a few digits: '1e999999999' is refused, never written out or made an int.
    if exact.adjusted() > 24:
        raise argparse.ArgumentTypeError(
            f"expected a whole number of at most {largest:,}, found {_shown(text)}"
        )
    if exact.adjusted() < -24:
        raise argparse.ArgumentTypeError(f"expected a whole number, found {_shown(text)}")
    exact *= scale
    understood = "" if str(exact) == cleaned else f" (understood as {exact.normalize():,f})"
    # Compared as decimals first: '1e999999999' never becomes a Python int.
    if exact < smallest:
        raise argparse.ArgumentTypeError(
            f"expected a whole number of at least {smallest}, found {_shown(text)}{understood}"
        )
    if exact > largest:
        raise argparse.ArgumentTypeError(
            f"expected a whole number of at most {largest:,}, found {_shown(text)}{understood}"
        )
    if exact != exact.to_integral_value():
        raise argparse.ArgumentTypeError(
            f"expected a whole number, found {_shown(text)}{understood}: give a whole count"
        )
    return int(exact)


def positive_int(text: str) -> int:
    """A whole number of at least 1 and at most :data:`MAX_COUNT` (a count of readings,
    episodes, envs, CPUs...)."""
    return whole_number(text, 1)


def non_negative_int(text: str) -> int:
    """A whole number of at least 0 and at most :data:`MAX_COUNT` (0 often means "automatic")."""
    return whole_number(text, 0)


def name_list(text: str, names: Sequence[str], what: str) -> list[str]:
    """Comma-separated names among ``names`` (``what`` they are, for the message), each once, in
    the order given.

    Raises:
        argparse.ArgumentTypeError: An unknown name, or none at all.
    """
    chosen = [part.strip() for part in text.split(",") if part.strip()]
    if not chosen or any(name not in names for name in chosen):
        meant = [
            f"{_shown(closest)} for {_shown(name)}"
            for name in chosen
            if name not in names and (closest := _closest_name(name, list(names))) is not None
        ]
        raise argparse.ArgumentTypeError(
            f"expected {what} among {', '.join(names)}, found {_shown(text)}"
            + (f"; did you mean {', '.join(meant)}?" if meant else "")
        )
    return list(dict.fromkeys(chosen))


def seed_argument(text: str) -> int:
    """A seed: a whole number in ``[0, 2^64)``."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number, found {_shown(text)}") from None
    if value < 0 or value >= 2**64:
        raise argparse.ArgumentTypeError(f"expected a seed in [0, 2^64), found {_shown(text)}")
    return value


def add_seed_option(parser: argparse.ArgumentParser, seeded: str, metavar: str = "N") -> None:
    """Adds ``--seed`` (:func:`seed_argument`, 0 by default), the seed of ``seeded``."""
    help_text = f"seed of {seeded} (default: %(default)s)"
    parser.add_argument("--seed", type=seed_argument, default=0, metavar=metavar, help=help_text)


def add_out_folder(parser: argparse.ArgumentParser, default: str, holding: str = "") -> None:
    """Adds ``--out DIR`` (:func:`output_path`), the output folder, created if missing, which
    holds ``holding`` (said in the help when given)."""
    what = f"folder for {holding}" if holding else "output folder"
    help_text = f"{what}, created if missing (default: %(default)s)"
    parser.add_argument("--out", type=output_path, default=default, metavar="DIR", help=help_text)


def _declared_range(setting: dataclasses.Field[Any]) -> Callable[[str], Any]:
    """A field's option type from its declared range (``mazesim._settings.setting``'s ``least``
    and ``most``): a whole number in it for a whole-number field; else text (a number field of
    another kind names its type in ``types``, or the dataclass's check refuses it)."""
    meta = setting.metadata
    if type(setting.default) is not int or ("least" not in meta and "most" not in meta):
        return str
    return functools.partial(
        whole_number, smallest=meta.get("least", 0), largest=meta.get("most", MAX_COUNT)
    )


def add_setting_options(
    parser: argparse.ArgumentParser,
    settings: Any,
    types: Mapping[str, Callable[[str], Any]],
) -> list[str]:
    """Adds an option ``--name`` for each field of the settings dataclass ``settings`` whose
    metadata has a ``help`` text: its default is the field's, its help the metadata's (with the
    default, or the metadata's ``default_text``), its type from ``types`` (else a whole number in
    the field's declared range, else text), its ``metavar`` and ``choices`` from the metadata.

    Returns:
        The fields' names, in order (the ``argparse`` destinations).
    """
    names = []
    for setting in dataclasses.fields(settings):
        if "help" not in setting.metadata:
            continue
        meta = setting.metadata
        shown = meta.get("default_text", "%(default)s")
        options: dict[str, Any] = {
            "default": getattr(settings, setting.name),
            "help": f"{meta['help']} (default: {shown})",
        }
        if "choices" in meta:
            options["choices"] = meta["choices"]
        else:
            options["type"] = types.get(setting.name, _declared_range(setting))
            options["metavar"] = meta["metavar"]
        parser.add_argument(f"--{setting.name.replace('_', '-')}", **options)
        names.append(setting.name)
    return names
