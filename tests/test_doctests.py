"""The ``>>>`` examples of the package's docstrings run and show what they say (those of a
module whose optional extra is not installed are skipped, saying which; ``make test`` installs
every extra). The core's Rust examples run as ``cargo test``'s doc tests."""

from __future__ import annotations

import doctest
import importlib
from pathlib import Path

import pytest

import mazesim
from mazesim.errors import MissingDependencyError

ROOT = Path(mazesim.__file__).parent
WITH_EXAMPLES = sorted(
    ".".join(("mazesim", *path.relative_to(ROOT).with_suffix("").parts)).removesuffix(".__init__")
    for path in ROOT.rglob("*.py")
    if ">>> " in path.read_text(encoding="utf-8")
)


def test_the_examples_are_found() -> None:
    assert "mazesim.actions" in WITH_EXAMPLES and len(WITH_EXAMPLES) >= 16


@pytest.mark.parametrize("name", WITH_EXAMPLES)
def test_the_examples_of_a_module_run(name: str) -> None:
    try:
        module = importlib.import_module(name)
    except MissingDependencyError as missing:  # an optional extra (make test installs them all)
        pytest.skip(str(missing))
    results = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert results.attempted > 0, f"{name} has no example doctest finds"
    assert results.failed == 0, f"{results.failed} of the examples of {name} fail"
