"""``mazesim demo`` runs recorded once for the tests that read their outputs."""

from __future__ import annotations

from pathlib import Path

__all__ = ["record_demo"]

#: The option of ``mazesim demo`` that writes each output.
OUTPUT_OPTIONS = {"out": "--out", "run": "--record", "html": "--html", "gif": "--video"}


def record_demo(options: list[str], paths: dict[str, Path]) -> dict[str, Path]:
    """Runs ``mazesim demo`` with ``options`` and an output option for each of ``paths`` (keys
    ``out``, ``run``, ``html`` and ``gif``, as :data:`OUTPUT_OPTIONS` names them); ``paths``."""
    from mazesim.cli import main

    outputs = [part for key, path in paths.items() for part in (OUTPUT_OPTIONS[key], str(path))]
    assert main(["demo", *options, *outputs]) == 0
    return paths
