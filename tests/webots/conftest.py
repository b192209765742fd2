"""Fixtures of the Webots tests."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from mazesim.webots import controller
from mazesim.webots import simulation as simulations


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


@pytest.fixture
def fresh_robot() -> Iterator[None]:
    """A test's controller makes its own robot of a prepared world, released after it."""
    controller.Robot.created = None
    yield
    controller.Robot.created = None
    simulations.release()
