"""The private ROS master's port: chosen where no outgoing connection can take it, and another
one tried when roscore finds its own taken; its waits are ceilings a loaded machine does not
reach."""

from __future__ import annotations

import inspect
import socket
from pathlib import Path

import pytest

from mazesim.ros import local_master
from mazesim.ros.local_master import LISTEN_PORTS, LocalMaster, free_loopback_port
from ros_support import needs_ros


def test_a_free_port_lies_below_the_ephemeral_range() -> None:
    high = min(LISTEN_PORTS[1], local_master._ephemeral_start())
    for _ in range(20):
        port = free_loopback_port()
        if high > LISTEN_PORTS[0]:  # a system whose ephemeral range starts lower gets its pick
            assert LISTEN_PORTS[0] <= port < high
        with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
            probe.bind(("127.0.0.1", port))  # free indeed


@needs_ros
def test_a_master_whose_port_is_taken_starts_on_another(tmp_path: Path) -> None:
    master = LocalMaster(home=str(tmp_path / "ros"))
    taken = master.port
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as holder:
        # Bound, not listening: what an outgoing connection given that port looks like.
        holder.bind(("127.0.0.1", taken))
        with master:
            assert master.port != taken and master.is_online()
            assert master.uri == f"http://127.0.0.1:{master.port}"
            assert master.env["ROS_MASTER_URI"] == master.uri
        assert master.leftovers() == []


def test_the_master_s_waits_bound_a_hang_and_not_a_slow_start() -> None:
    # roscore and rosout are Python processes: on a loaded 2-core machine their start took
    # longer than the 15 s the master waited, and it gave up on a roscore about to answer.
    for method in (LocalMaster.start, LocalMaster.wait_for_connections):
        default = inspect.signature(method).parameters["timeout"].default
        assert default == local_master.START_TIMEOUT_S >= 120.0, method


@pytest.mark.parametrize("name", ["../escape", "a/b", "..", "", "x" * 201, "nul\x00"])
def test_a_process_name_that_is_no_plain_file_name_is_refused(tmp_path: Path, name: str) -> None:
    # spawn("../x") made or emptied x.log outside the master's home (/etc/x.log as root).
    import mazesim

    graph = LocalMaster(home=str(tmp_path / "home"))
    with pytest.raises(mazesim.InvalidArgumentError, match="plain file name"):
        graph.spawn(name, ["true"])
    assert not (tmp_path / "escape.log").exists()
    assert graph.log_path("bridge") == str(tmp_path / "home" / "bridge.log")
