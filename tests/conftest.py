"""Shared fixtures of the Python tests."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from mazesim.ros.local_master import LocalMaster

#: The worlds every installed mazesim carries.
BUILTIN_WORLDS = ("seed-maze", "line-follow", "arena")


@pytest.fixture(params=BUILTIN_WORLDS)
def builtin_name(request: pytest.FixtureRequest) -> str:
    """Each built-in world name in turn."""
    return str(request.param)


@pytest.fixture
def master(tmp_path: Path) -> Iterator[LocalMaster]:
    """A ROS master on a free loopback port; every process started on it is gone afterwards."""
    graph = LocalMaster(home=str(tmp_path / "ros"))
    graph.start()
    try:
        yield graph
    finally:
        spawned = [process for _, process in graph.processes]
        left_behind = graph.close()
    assert all(process.returncode is not None for process in spawned)
    assert left_behind == []  # nothing had to be swept up after the orderly stop
    assert graph.leftovers() == []


@pytest.fixture(scope="session")
def navigator_demo(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """The shipped navigator's demo run once with ``--record``, ``--html`` and a GIF: the paths
    of its outputs (``run``, ``html``, ``gif``, ``out``)."""
    from mazesim.cli import main

    folder = tmp_path_factory.mktemp("navigator-demo")
    paths = {
        "run": folder / "run.json.gz",
        "html": folder / "replay.html",
        "gif": folder / "run.gif",
        "out": folder / "demo",
    }
    code = main(
        [
            "demo",
            "--controller",
            "hrl",
            "--out",
            str(paths["out"]),
            "--record",
            str(paths["run"]),
            "--html",
            str(paths["html"]),
            "--video",
            str(paths["gif"]),
        ]
    )
    assert code == 0
    return paths


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    """A headless Chromium driven by selenium (the browser tests skip where there is none)."""
    from mazesim.replay.screenshot import headless_chromium

    driver = headless_chromium()
    try:
        yield driver
    finally:
        driver.quit()
