"""The fields of settings dataclasses that command-line options are generated from.

A field made by :func:`setting` carries its option's help text, ``metavar``, ``choices`` and
shown default in its metadata; ``mazesim train``, ``mazesim eval`` and ``mazesim bench`` add one
option per such field (``mazesim.cli._args.add_setting_options``), so the dataclass holds the only
default and the only help text.
"""

from __future__ import annotations

from dataclasses import field, fields
from typing import Any

__all__ = ["check_choices", "setting"]


def setting(
    default: Any,
    help: str,  # noqa: A002 - the name argparse and the metadata use
    metavar: str | None = None,
    *,
    choices: tuple[str, ...] | None = None,
    default_text: str | None = None,
) -> Any:
    """A dataclass field of ``default`` offered as a command-line option: ``help`` its text,
    ``metavar`` its value's name (or ``choices`` its values), ``default_text`` the default shown
    in place of the value."""
    metadata: dict[str, Any] = {"help": help}
    for key, value in (("metavar", metavar), ("choices", choices), ("default_text", default_text)):
        if value is not None:
            metadata[key] = value
    return field(default=default, metadata=metadata)


def check_choices(settings: Any) -> None:
    """Refuses a value of a field made by :func:`setting` with ``choices`` that is not one of
    them, as its command-line option would (an ``UnknownNameError`` listing them): the choices
    are declared once and hold for the dataclass made in Python too."""
    from mazesim.errors import _known_name

    for each in fields(settings):
        choices = each.metadata.get("choices")
        if choices is not None:
            _known_name(getattr(settings, each.name), each.name, choices)
