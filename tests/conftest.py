"""Shared fixtures of the Python tests."""

from __future__ import annotations

import pytest

#: The worlds every installed mazesim carries.
BUILTIN_WORLDS = ("seed-maze", "line-follow", "arena")


@pytest.fixture(params=BUILTIN_WORLDS)
def builtin_name(request: pytest.FixtureRequest) -> str:
    """Each built-in world name in turn."""
    return str(request.param)
