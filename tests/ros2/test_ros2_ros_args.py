"""``--ros-args`` on the ROS 2 commands, as a launch file (``launch_ros``'s ``Node`` with a
namespace, remappings and ``use_sim_time``) or ``ros2 run`` passes them: the bridge takes its
namespace, name and topic remappings from them, refuses parameters it does not have, and a node
reading the remapped topics in the namespace drives it."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from mazesim.errors import InvalidArgumentError, UnknownNameError
from mazesim.ros2.ros_args import RosArguments, split_ros_arguments
from mazesim.ros2.unpublished import why_no_service
from ros2_support import AWAIT_BACKGROUND, MAZESIM, needs_namespace, needs_ros2, run_in_namespace

LAUNCHED = ["-r", "__node:=sim", "-r", "__ns:=/robot", "-r", "scan:=base_scan"]


def test_a_launch_files_section_is_taken_out_and_read(tmp_path: Path) -> None:
    params = tmp_path / "params.yaml"
    params.write_text("/**:\n  ros__parameters:\n    use_sim_time: true\n", encoding="utf-8")
    rest, ros = split_ros_arguments(
        ["ros2", "bridge", "--mode", "free", "--ros-args", *LAUNCHED, "--params-file",
         str(params), "-p", "use_sim_time:=true", "--log-level", "info", "--", "--paused"]
    )  # fmt: skip
    assert rest == ["ros2", "bridge", "--mode", "free", "--paused"]
    assert (ros.namespace, ros.node_name) == ("/robot", "sim")
    # Relative names resolve against the namespace, absolute ones stay; the first rule wins.
    assert ros.remap("/robot/scan", "sim", "/robot") == "/robot/base_scan"
    assert ros.remap("/robot/odom", "sim", "/robot") == "/robot/odom"
    node_only = split_ros_arguments(["--ros-args", "-r", "other:/odom:=/x", "-r", "~/a:=b"])[1]
    assert node_only.remap("/odom", "sim", "/") == "/odom"
    assert node_only.remap("/sim/a", "sim", "/") == "/b"
    assert RosArguments().remap("/odom", "sim", "/") == "/odom"


@pytest.mark.parametrize(
    ("arguments", "expected"),
    [
        (["-p", "seed:=3"], "perhaps --seed"),
        (["-r", "scan"], "expected a remapping FROM:=TO"),
        (["-r", "scan:=base scan"], "expected ROS topic names"),
        (["--remap"], "found the end of the line"),
        (["--seed", "3"], "expected ROS 2 arguments after --ros-args"),
    ],
)
def test_what_ros_2_would_not_take_is_refused(arguments: list[str], expected: str) -> None:
    with pytest.raises((InvalidArgumentError, UnknownNameError), match=expected):
        split_ros_arguments(["bridge", "--ros-args", *arguments])


def test_a_parameters_file_with_a_parameter_the_bridge_lacks_is_refused(tmp_path: Path) -> None:
    params = tmp_path / "params.yaml"
    params.write_text(
        "mazesim_bridge:\n  ros__parameters:\n    use_sim_time: true\n    world: maze\n",
        encoding="utf-8",
    )
    with pytest.raises(UnknownNameError, match="perhaps --world"):
        split_ros_arguments(["--ros-args", "--params-file", str(params)])


@needs_ros2
def test_only_the_bridge_takes_remappings() -> None:
    result = subprocess.run(
        [*MAZESIM, "ros2", "avoid-collision", "--ros-args", "-r", "__ns:=/robot"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert result.returncode == 2
    assert "only mazesim ros2 bridge takes __ns" in result.stderr


DRIVER = textwrap.dedent(
    """
    import sys
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.pub import DataWriter
    from cyclonedds.sub import DataReader
    from cyclonedds.topic import Topic
    from cyclonedds.util import duration
    from mazesim.ros2 import messages
    from mazesim.ros2.qos import COMMAND, SENSOR, cyclone_qos

    ty = lambda name: messages.idl_type("humble", name)
    p = DomainParticipant(0)
    scan = DataReader(p, Topic(p, "rt/robot/base_scan", ty("sensor_msgs/msg/LaserScan")),
                      qos=cyclone_qos(SENSOR))
    cmd = DataWriter(p, Topic(p, "rt/robot/cmd_vel", ty("geometry_msgs/msg/Twist")),
                     qos=cyclone_qos(COMMAND))
    V = ty("geometry_msgs/msg/Vector3")
    answered = 0
    while answered < 21:  # the reset state and 20 steps
        for _ in scan.take_iter(timeout=duration(seconds=300)):
            cmd.write(ty("geometry_msgs/msg/Twist")(linear=V(x=0.05, y=0.0, z=0.0),
                                                    angular=V(x=0.0, y=0.0, z=0.0)))
            answered += 1
            break
    print("answered", answered)
    """
)


@needs_ros2
@needs_namespace
def test_a_launched_bridge_drives_on_its_remapped_topics_in_its_namespace() -> None:
    bridge = [*MAZESIM, "ros2", "bridge", "--stop-after", "20", "--ros-args", *LAUNCHED,
              "-p", "use_sim_time:=true"]  # fmt: skip
    result = run_in_namespace([bridge], [sys.executable, "-c", DRIVER])
    assert result.returncode == 0, result.stderr
    assert "answered 21" in result.stdout
    assert "(namespace /robot)" in result.stderr
    assert "stopped after 20 steps" in result.stderr


def test_a_call_of_a_service_of_the_bridge_is_explained_and_others_left_alone() -> None:
    reason = why_no_service("/sim/get_loggers", "/sim")
    assert reason is not None and "/sim/list_parameters" in reason and "--seed" in reason
    assert why_no_service("/sim/set_parameters", "/sim") is None  # offered
    assert why_no_service("/go_to_pose/_action/send_goal", "/sim") is None
    assert why_no_service("/simulator/get_parameters", "/sim") is None


PARAMETER_CLIENT = (
    "from mazesim.ros2.node import Node\n"
    "from mazesim.ros2.qos import COMMAND\n"
    "node = Node('param_client')\n"
    # A client of a service of the launched bridge's node that it does not offer (its node name
    # given by __node; rclcpp's logger levels), and an action client of another node's server.
    "kept = [node._dds_writer(f'rq/{name}Request', 'std_msgs/msg/String', COMMAND,"
    " ros_topic=False) for name in ('robot/sim/get_loggers', 'go_to_pose/_action/send_goal')]\n"
    + AWAIT_BACKGROUND
    + "await_background(0, 'a node calls the service')\n"
)


@needs_ros2
@needs_namespace
def test_the_bridge_names_a_service_of_its_node_that_it_does_not_offer() -> None:
    result = run_in_namespace(
        [[*MAZESIM, "ros2", "bridge", "--mode", "free", "--ros-args", *LAUNCHED]],
        [sys.executable, "-c", PARAMETER_CLIENT],
        grace=1.0,
    )
    assert result.returncode == 0, result.stderr
    message = "a node calls the service /robot/sim/get_loggers, which this bridge does not"
    assert result.stderr.count(message) == 1, result.stderr
    assert "go_to_pose" not in result.stderr
