"""``mazesim ros2 demo`` starts two nodes (the bridge and a controller); neither outlives it. A
Ctrl-C while it waited for the bridge stopped the controller node but left the bridge running,
waiting for a driver for its idle timeout (10 minutes) and writing to the terminal (found by the
surface walk, whose call limit interrupts a call as Ctrl-C does). No ROS 2 is needed: the nodes
are stand-ins that sleep."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
from pathlib import Path
from typing import Any

import pytest

from mazesim.ros2 import demo


def test_ctrl_c_during_the_demo_leaves_no_node_running(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    started: list[subprocess.Popen[Any]] = []
    popen = subprocess.Popen

    def recorded(*args: Any, **kwargs: Any) -> subprocess.Popen[Any]:
        process = popen(*args, **kwargs)
        started.append(process)
        return process

    sleeper = [sys.executable, "-c", "import time; time.sleep(60)"]
    monkeypatch.setattr(demo, "_command", lambda *arguments: sleeper)
    monkeypatch.setattr(demo.subprocess, "Popen", recorded)
    timer = threading.Timer(2.0, os.kill, (os.getpid(), signal.SIGINT))  # Ctrl-C
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            demo.run_demo(tmp_path / "out", controller="avoid-collision")
    finally:
        timer.cancel()
    assert len(started) == 2, started
    assert all(process.poll() is not None for process in started), "a node outlived the demo"
