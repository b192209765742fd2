"""Shared fixtures of the Python tests."""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from mazesim.ros.local_master import LocalMaster
from recorded_demos import record_demo
from ros2_support import needs_ros2
from ros_support import needs_ros


@pytest.fixture(autouse=True, scope="session")
def sandboxed_environment(tmp_path_factory: pytest.TempPathFactory) -> Iterator[None]:
    """What the tests write or fetch stays inside pytest's own temporary folder, for them and
    the processes they start: Webots worlds' PROTO URLs are never downloaded (only tests that
    serve them from 127.0.0.1 allow it) and no user's download cache is read; and
    Stable-Baselines3, which makes a new ``SB3-<date>`` log folder in the system's temporary
    directory at every ``learn`` unless ``SB3_LOGDIR`` names one, logs into one made here."""
    names = ("MAZESIM_OFFLINE", "MAZESIM_PROTO_CACHE", "SB3_LOGDIR")
    saved = {name: os.environ.get(name) for name in names}
    os.environ["MAZESIM_OFFLINE"] = "1"
    os.environ["MAZESIM_PROTO_CACHE"] = str(tmp_path_factory.mktemp("proto-cache"))
    os.environ["SB3_LOGDIR"] = str(tmp_path_factory.mktemp("sb3-logs"))
    yield
    for name, value in saved.items():
        if value is None:
            os.environ.pop(name, None)
        else:
            os.environ[name] = value


#: Test folders whose tests time a bridge process against the nodes it talks to: `make test` runs
#: them one at a time after the rest (the `alone` marker), never beside other tests' processes;
#: so too every other test that needs ROS 1 or ROS 2 (it starts a bridge too).
ALONE_FOLDERS = ("ros", "ros2")


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Mark ``alone`` the tests of ``ALONE_FOLDERS`` and those that need ROS 1 or ROS 2."""
    tests = Path(__file__).parent
    ros_marks = (needs_ros.mark, needs_ros2.mark)
    for item in items:
        folder = Path(str(item.fspath)).parent
        in_folder = folder.parent == tests and folder.name in ALONE_FOLDERS
        if in_folder or any(mark in ros_marks for mark in item.iter_markers("skipif")):
            item.add_marker(pytest.mark.alone)


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
    folder = tmp_path_factory.mktemp("navigator-demo")
    paths = {
        "run": folder / "run.json.gz",
        "html": folder / "replay.html",
        "gif": folder / "run.gif",
        "out": folder / "demo",
    }
    return record_demo(["--controller", "hrl"], paths)


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    """A headless Chromium driven by selenium (the browser tests skip where there is none)."""
    from mazesim.replay.screenshot import headless_chromium

    driver = headless_chromium()
    try:
        yield driver
    finally:
        driver.quit()
