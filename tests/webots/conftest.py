"""Fixtures of the Webots tests."""

from __future__ import annotations

from pathlib import Path

import pytest


@pytest.fixture(scope="session")
def native_build_cache(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The build cache of the tests' compiled controllers (each build is keyed by its files'
    paths and contents, so the tests share it without seeing each other's builds)."""
    return tmp_path_factory.mktemp("native-cache")


@pytest.fixture
def own_cache(native_build_cache: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """Builds go to the tests' cache, not the user's."""
    monkeypatch.setenv("MAZESIM_CACHE", str(native_build_cache))
    return native_build_cache
