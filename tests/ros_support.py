"""What the ROS tests share: whether ROS 1 can be used here, and the mark that skips without it."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import time
import uuid
import xmlrpc.client
from pathlib import Path
from typing import Any

import pytest

from mazesim.ros import local_master
from mazesim.ros.local_master import LocalMaster

__all__ = [
    "MAZESIM",
    "PROBE",
    "REPO",
    "needs_ros",
    "processes_with",
    "ros_available",
    "run_probe",
    "spawn_bridge",
    "spawn_launch",
    "stop_launch",
]

#: The repository's root folder.
REPO = Path(__file__).resolve().parents[1]
#: The ROS client the tests run against a bridge (``ros_probe.py``).
PROBE = Path(__file__).with_name("ros_probe.py")
#: The ``mazesim`` command of this interpreter.
MAZESIM = (sys.executable, "-m", "mazesim")


def ros_available() -> bool:
    """Whether roscore, roslaunch, rosbag and the Python ROS modules the bridge needs are
    installed."""
    if any(shutil.which(tool) is None for tool in ("roscore", "roslaunch", "rosbag")):
        return False
    check = subprocess.run(
        [sys.executable, "-c", "import rospy, rosbag, std_msgs.msg, rosgraph_msgs.msg"],
        capture_output=True,
        check=False,
    )
    return check.returncode == 0


#: Skips a test where ROS 1 is missing, saying how to install it.
needs_ros = pytest.mark.skipif(
    not ros_available(), reason="ROS 1 is not installed (run 'make ros-deps')"
)


def run_probe(master: LocalMaster, *args: str, namespace: str = "") -> dict[str, Any]:
    """Runs ``ros_probe.py ARGS`` (in the ROS namespace ``namespace``, if given) to its end;
    returns what it printed last (JSON)."""
    env = {**master.env, "ROS_NAMESPACE": namespace} if namespace else master.env
    result = subprocess.run(
        [sys.executable, str(PROBE), *args],
        env=env,
        capture_output=True,
        text=True,
        timeout=600,  # a ceiling for a hang: the probe ends on the messages it counts
        check=False,
    )
    assert result.returncode == 0, result.stdout + result.stderr
    return dict(json.loads(result.stdout.strip().splitlines()[-1]))


def start_probe(env: dict[str, str], *args: str) -> subprocess.Popen[str]:
    """Starts ``ros_probe.py ARGS`` with ``env`` (a master's) and returns it running, its output
    piped as text (read it with ``communicate``)."""
    return subprocess.Popen(
        [sys.executable, str(PROBE), *args],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def spawn_bridge(master: LocalMaster, *options: str) -> subprocess.Popen[bytes]:
    return master.spawn("bridge", [*MAZESIM, "ros", "bridge", *options])


def spawn_launch(
    master: LocalMaster, launch_file: str, *args: str, **env: str
) -> tuple[subprocess.Popen[bytes], str]:
    """Runs ``roslaunch mazesim_ros LAUNCH_FILE ARGS`` in the package folder of the repository;
    returns the process and the tag in its environment (for :func:`processes_with`)."""
    tag = uuid.uuid4().hex
    launch = master.spawn(
        "roslaunch",
        ["roslaunch", "mazesim_ros", launch_file, *args],
        env={"ROS_PACKAGE_PATH": str(REPO / "ros"), "MAZESIM_TEST_LAUNCH": tag, **env},
    )
    return launch, tag


def stop_launch(launch: subprocess.Popen[bytes]) -> int:
    """Stops a ``roslaunch`` as Ctrl-C does and returns its exit code. roslaunch gives each node
    its own SIGINT timeout, then SIGTERM's, before it exits (``roslaunch.nodeprocess``: 15 s and
    2 s): the wait here is longer than both, so that a node slow to stop on a loaded machine is
    ended by roslaunch's own rule, not by a test's SIGTERM to roslaunch that leaves it behind."""
    from roslaunch.nodeprocess import DEFAULT_TIMEOUT_SIGINT, DEFAULT_TIMEOUT_SIGTERM

    return LocalMaster.stop_process(
        launch, grace=DEFAULT_TIMEOUT_SIGINT + DEFAULT_TIMEOUT_SIGTERM + 5.0
    )


def processes_with(variable: str, value: str) -> list[int]:
    """PIDs of running (not zombie) processes whose environment has variable=value."""
    return [pid for pid, _ in local_master.processes_with(variable, value)]


def topic_types(master: LocalMaster) -> dict[str, str]:
    """The type of every topic someone publishes or subscribes on ``master``, as ``rostopic
    list -v`` shows them: ``{"/odom": "nav_msgs/Odometry", ...}``."""
    with xmlrpc.client.ServerProxy(master.uri) as proxy:
        code, message, types = proxy.getTopicTypes(local_master.CALLER_ID)
    assert code == 1, message
    return {str(topic): str(kind) for topic, kind in types}


def wait_for_subscriber(master: LocalMaster, topic: str, timeout: float = 120.0) -> None:
    """Waits until some node subscribes ``topic`` (an absolute name such as ``/pose``)."""
    deadline = time.monotonic() + timeout
    while True:
        _, subscribers, _ = master.system_state()
        if any(name == topic and nodes for name, nodes in subscribers):
            return
        assert time.monotonic() <= deadline, f"no node subscribed {topic} within {timeout:g} s"
        time.sleep(0.05)
