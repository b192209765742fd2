"""``mazesim.hrl``, the former name of ``mazesim.learn``: it still imports, with a warning, and
nothing inside the package uses it."""

from __future__ import annotations

import importlib
import sys

import pytest

import mazesim.learn
from test_layers import ROOT, _package_of, imported_modules


def test_the_former_name_warns_and_gives_every_public_name() -> None:
    sys.modules.pop("mazesim.hrl", None)
    with pytest.warns(DeprecationWarning, match="import mazesim.learn instead"):
        hrl = importlib.import_module("mazesim.hrl")
    assert hrl.__all__ == mazesim.learn.__all__
    assert all(getattr(hrl, name) is getattr(mazesim.learn, name) for name in hrl.__all__)
    assert hrl.load_policy().lower_q is not None


def test_nothing_inside_the_package_imports_the_former_name() -> None:
    users = [
        f"{path.relative_to(ROOT)}:{line}"
        for path in ROOT.rglob("*.py")
        if path.parent.name != "hrl"
        for line, module in imported_modules(path, _package_of(path))
        if module == "mazesim.hrl" or module.startswith("mazesim.hrl.")
    ]
    assert not users
