"""The one command-line parser class of the package, below every layer that parses arguments.

:class:`BoundedParser` is argparse's parser with two habits every ``mazesim`` entry point
needs: an option is taken by its whole name only (argparse's abbreviations made a prefix of
one option another's), and the usage error is bounded (argparse quotes the word typed whole, and
a word of a million characters made a message as long). The commands' parser
(``cli._help.CommandParser``) adds its help formatting and hints to it; a module run with
``python -m`` below the CLI layer (``replay.screenshot``) uses it as it is. A test checks that
no other parser class is made in the package.
"""

from __future__ import annotations

import argparse
from typing import Any, NoReturn

from mazesim.errors import MOST_MESSAGE, _shortened

__all__ = ["BoundedParser"]


class BoundedParser(argparse.ArgumentParser):
    """argparse's parser, taking each option by its whole name and with a bounded usage error."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("allow_abbrev", False)
        super().__init__(*args, **kwargs)

    def error(self, message: str) -> NoReturn:
        """argparse's usage error (exit status 2), a word typed too long shortened in it."""
        super().error(_shortened(message, MOST_MESSAGE))
