"""A ROS 2 bridge that no node drives gives up after its idle timeout (``--idle-timeout``), in
lockstep (where it waits for a command writer before its reset state) and free-running (where
it steps on its own), instead of running for ever."""

from __future__ import annotations

import subprocess
import time

import pytest

from mazesim.ros.lockstep import IDLE_EXIT_STATUS
from ros2_support import MAZESIM, needs_namespace, needs_ros2, run_in_namespace


@needs_ros2
@needs_namespace
@pytest.mark.parametrize("mode", ["lockstep", "free"])
def test_a_bridge_no_node_drives_gives_up_after_its_idle_timeout(mode: str) -> None:
    started = time.monotonic()
    result = run_in_namespace(
        [],
        [*MAZESIM, "ros2", "bridge", "--world", "arena", "--mode", mode, "--idle-timeout", "1.5"],
    )
    assert result.returncode == IDLE_EXIT_STATUS, result.stderr
    assert time.monotonic() - started >= 1.5
    assert "no command came and no node had a command topic open for 1.5 s; giving up" in (
        result.stderr
    )
    assert "stopped after" in result.stderr  # it stopped in order: bag and domain closed


@needs_ros2
def test_an_idle_timeout_that_is_no_time_is_refused_on_the_command_line() -> None:
    result = subprocess.run(
        [*MAZESIM, "ros2", "bridge", "--idle-timeout", "-1"],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert result.returncode == 2
    assert "--idle-timeout" in result.stderr and "expected seconds of wall-clock time" in (
        result.stderr
    )
