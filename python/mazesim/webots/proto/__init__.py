"""The PROTO engine: Webots PROTO instances of a world expanded into base nodes before the
core imports it (see ``docs/webots.md``, "PROTOs").

``expand_world`` finds each PROTO as Webots does (``resolver``), reads it (``definition``),
evaluates a procedural body with a JavaScript or Lua engine (``templates``, with the helper
modules of ``template_modules``), replaces ``IS`` references by the instance's fields and expands
nested PROTOs (``expander``); stock objects that cannot be read get mazesim's stand-ins
(``stand_ins``, the apartment's furniture and window in ``furniture``).
"""

from __future__ import annotations

from .expander import Expander, ExpansionReport
from .resolver import ProtoUnavailableError, Resolver, cache_dir, fetch_url
from .syntax import unix_line_ends, world_version

__all__ = [
    "ExpansionReport",
    "ProtoUnavailableError",
    "cache_dir",
    "expand_world",
    "fetch_url",
    "world_resolver",
]

#: The Webots release a world without a ``#VRML_SIM`` header is read as.
DEFAULT_VERSION = "R2023b"


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
    text = unix_line_ends(text)
    version, y_up = world_version(text)
    expander = Expander(world, text, version or DEFAULT_VERSION, y_up)
    return expander.expand_world(), expander.report


def world_resolver(text: str, world: str) -> Resolver:
    """The resolver of a world's ``webots://`` and http(s) URLs, at the Webots release its
    header names (for files the PROTO expansion does not read: its floor textures)."""
    version, _ = world_version(unix_line_ends(text))
    return Resolver(world, version or DEFAULT_VERSION)
