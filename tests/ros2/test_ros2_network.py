"""Discovery stays on this machine unless asked; ROS 2's variables are honoured; without the
extra, ``mazesim ros2`` says what to install at once."""

from __future__ import annotations

import subprocess
import sys

import pytest

from mazesim.errors import InvalidArgumentError, UnknownNameError
from mazesim.ros2.clock import FreeRunning, stamp_nanoseconds
from mazesim.ros2.network import LOCALHOST, SUBNET, cyclone_config, discovery_from_environment
from ros2_support import MAZESIM, needs_namespace, needs_ros2


@pytest.mark.parametrize(
    ("environment", "network", "expected"),
    [
        ({}, False, (0, LOCALHOST)),
        ({"ROS_DOMAIN_ID": "7"}, False, (7, LOCALHOST)),
        ({"ROS_LOCALHOST_ONLY": "0"}, False, (0, SUBNET)),
        ({"ROS_LOCALHOST_ONLY": "1"}, False, (0, LOCALHOST)),
        ({"ROS_AUTOMATIC_DISCOVERY_RANGE": "SUBNET"}, False, (0, SUBNET)),
        ({"ROS_AUTOMATIC_DISCOVERY_RANGE": "localhost", "ROS_LOCALHOST_ONLY": "0"}, False,
         (0, LOCALHOST)),
        ({"ROS_AUTOMATIC_DISCOVERY_RANGE": "OFF"}, False, (0, LOCALHOST)),
        ({}, True, (0, SUBNET)),
    ],
)  # fmt: skip
def test_discovery_reach(environment: dict[str, str], network: bool, expected: tuple) -> None:
    assert tuple(discovery_from_environment(environment, network)) == expected


def test_localhost_config_binds_loopback_and_user_config_wins() -> None:
    local = discovery_from_environment({})
    assert 'address="127.0.0.1"' in cyclone_config(local, {})
    assert cyclone_config(local, {"CYCLONEDDS_URI": "file:///etc/dds.xml"}) == ""
    assert cyclone_config(discovery_from_environment({}, network=True), {}) == ""


@pytest.mark.parametrize(
    "environment",
    [{"ROS_DOMAIN_ID": "233"}, {"ROS_DOMAIN_ID": "x"}, {"ROS_AUTOMATIC_DISCOVERY_RANGE": "LAN"}],
)
def test_bad_variables_are_named(environment: dict[str, str]) -> None:
    with pytest.raises((InvalidArgumentError, UnknownNameError), match="ROS_"):
        discovery_from_environment(environment)


def test_time_zero_is_never_stamped_and_sim_control_is_checked() -> None:
    assert stamp_nanoseconds(0.0) == 1
    assert stamp_nanoseconds(0.032) == 32_000_000
    pace = FreeRunning(speed=0.0, control_step_s=0.032, paused=True)
    assert pace.due(0.0, 0.032) is None
    pace.control("step 2")
    assert pace.due(0.0, 0.032) == 0.0
    pace.stepped()
    pace.stepped()
    assert pace.paused
    pace.control("run_until 0.1")
    assert pace.due(0.064, 0.032) == 0.0
    assert pace.due(0.096, 0.032) is None  # a step would pass 0.1 s
    for bad in ("go", "step 0", "step x", "run_until inf"):
        with pytest.raises(Exception, match="expected pause, run"):
            pace.control(bad)


def test_without_the_extra_the_command_says_what_to_install() -> None:
    # Hide cyclonedds and rosbags from the command's interpreter.
    code = (
        "import sys, importlib.util as u\n"
        "real = u.find_spec\n"
        "u.find_spec = lambda name, *a: None if name in ('cyclonedds', 'rosbags') "
        "else real(name, *a)\n"
        "from mazesim.cli import main\n"
        "sys.exit(main(['ros2', 'bridge']))\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=300
    )
    assert result.returncode == 2
    assert 'pip install "mazesim[ros2]"' in result.stderr
    assert "cyclonedds and rosbags" in result.stderr


def test_the_pages_topic_table_says_what_the_bridge_publishes() -> None:
    """Each published topic's type and QoS in docs/ros2.md are those of the code."""
    import re
    from pathlib import Path

    import mazesim
    from mazesim.ros2.state import StateTopics

    page = (Path(__file__).parents[2] / "docs" / "ros2.md").read_text(encoding="utf-8")
    rows = [line.split(" | ") for line in page.splitlines() if line.startswith("| `")]
    described = {}
    for cells in rows:
        for name in re.findall(r"`(/[a-z_0-9]+)`", cells[0]):
            described[name] = (cells[1], cells[2])
    for robot in ("e-puck", "e-puck2", "seed"):
        simulator = mazesim.Simulator(mazesim.load_world("seed-maze"), robot=robot, seed=0)
        state = StateTopics(simulator, "humble")
        for topic in [*state.topics, state.static_topic()]:
            name = topic.name
            if re.fullmatch(r"/ps[1-6]|/gs1", name):
                continue  # the table's "/ps0 .. /ps7" and "/gs0 .. /gs2" rows
            assert name in described, name
            kind, qos = described[name]
            assert f"`{topic.msgtype}`" in kind, (name, kind)
            assert qos == topic.qos.describe(), (name, qos)


@needs_ros2
@needs_namespace
def test_no_usable_network_interface_is_a_clear_error() -> None:
    """In a network namespace whose loopback is down, Cyclone DDS cannot start: the command
    says so and what to check, as the package's error, not as an internal one."""
    result = subprocess.run(
        ["unshare", "-n", *MAZESIM, "ros2", "bridge", "--stop-after", "1"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    last = result.stderr.strip().splitlines()[-1]
    assert result.returncode != 0 and last.startswith("mazesim: error: Cyclone DDS could not"), last
    assert "'lo' up" in last and "internal error" not in result.stderr


@needs_ros2
def test_a_topic_dds_refuses_is_the_package_s_error() -> None:
    """A DDS topic, reader or writer that Cyclone refuses (``DDS_RETCODE_BAD_PARAMETER`` under a
    tight memory limit) came out of ``mazesim ros2 bridge`` as an internal error."""
    from cyclonedds.core import DDSException

    from mazesim.errors import MazesimIOError
    from mazesim.ros2 import node as ros2_node

    def refused(*_: object) -> None:
        raise DDSException(1, "a bad parameter")

    with pytest.raises(MazesimIOError, match="could not make a writer of rt/ps0"):
        ros2_node._joined(refused, "a writer of rt/ps0")
    assert ros2_node._joined(lambda: 7, "anything") == 7
