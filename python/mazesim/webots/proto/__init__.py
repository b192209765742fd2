"""The PROTO engine: Webots PROTO instances of a world expanded into base nodes before the
core imports it (see ``docs/webots.md``, "PROTOs").

``expand_world`` finds each PROTO as Webots does (``resolver``), reads it (``definition``),
evaluates a procedural body with a JavaScript or Lua engine (``templates``, with the helper
modules of ``template_modules``), replaces ``IS`` references by the instance's fields and expands
nested PROTOs (``expander``); stock objects that cannot be read get mazesim's stand-ins
(``stand_ins``, the apartment's furniture and window in ``furniture``).
"""

from __future__ import annotations

import re

from .expander import Expander, ExpansionReport
from .resolver import ProtoUnavailableError, cache_dir, fetch_url

__all__ = ["ExpansionReport", "ProtoUnavailableError", "cache_dir", "expand_world", "fetch_url"]

_HEADER = re.compile(r"#VRML_SIM\s+(R\d{4}[a-z]|V?\d+(?:\.\d+)*)")


def _version(text: str) -> tuple[str, bool]:
    """The world's version tag for ``webots://`` URLs, and whether its PROTOs are Y-up (before
    R2022a)."""
    match = _HEADER.search(text[:200])
    if match is None:
        return "R2023b", False
    tag = match.group(1)
    if tag.startswith("R"):
        return tag, tag < "R2022a"
    return tag, True


def expand_world(text: str, world: str) -> tuple[str, ExpansionReport]:
    """The text of a world with its PROTO instances expanded.

    Args:
        text: The world's text (any line ends).
        world: Its path: relative ``EXTERNPROTO`` paths and the project's ``protos/`` folder
            are found from it.

    Returns:
        The expanded text (each expansion on its instance's line, so lines stay those of the
        file) and what was expanded, stood in for or not found.

    Raises:
        ProtoUnavailableError: An ``EXTERNPROTO`` URL cannot be downloaded and is not cached.
        WorldFormatError: A PROTO file is malformed or its template fails.
    """
    text = text.replace("\r\n", "\n").replace("\r", "\n")
    version, y_up = _version(text)
    expander = Expander(world, text, version, y_up)
    return expander.expand_world(), expander.report
