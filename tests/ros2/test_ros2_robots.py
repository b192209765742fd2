"""The ROS 2 bridge on a world of two robots: each robot's topics in its own namespace, each
moved by its own cmd_vel, one /clock; driven over DDS from another process in a private network
namespace."""

from __future__ import annotations

import json
import math
import re
import sys
from pathlib import Path
from typing import Any

import pytest

import mazesim
from mazesim.errors import InvalidArgumentError
from mazesim.ros2 import cdr
from mazesim.ros2.robots import RobotOf, robot_namespaces
from mazesim.ros2.state import StateTopics
from ros2_support import MAZESIM, TWO_ROBOTS, needs_namespace, needs_ros2, run_in_namespace

SWARM_DRIVER = Path(__file__).parent / "swarm_driver.py"


def test_namespaces_are_ros_names_and_distinct() -> None:
    assert robot_namespaces(["west", "east-1", "2nd robot"]) == ["/west", "/east_1", "/r_2nd_robot"]
    with pytest.raises(InvalidArgumentError, match="'a-b' and 'a_b', both /a_b"):
        robot_namespaces(["a-b", "a_b"])


def test_a_robot_in_a_namespace_has_every_topic_there_but_the_clock() -> None:
    simulator = mazesim.Simulator(mazesim.World.from_toml(TWO_ROBOTS), seed=0)
    alone = [t.name for t in StateTopics(simulator, "humble").topics]
    east = StateTopics(RobotOf(simulator, 1), "humble", "/east_1", clock=False)  # type: ignore[arg-type]
    assert [t.name for t in east.topics] == [f"/east_1{name}" for name in alone if name != "/clock"]
    assert east.static_topic().name == "/east_1/tf_static"
    assert len(east.messages(cdr.stamp_of(1), 0.0)) == len(east.topics)


@needs_ros2
def test_a_frame_prefix_names_each_robots_frames_and_puts_its_transforms_on_tf() -> None:
    from mazesim.ros2 import messages

    simulator = mazesim.Simulator(mazesim.World.from_toml(TWO_ROBOTS), seed=0)
    east = StateTopics(
        RobotOf(simulator, 1),
        "humble",
        "/east_1",
        clock=False,
        frame_prefix="east_1/",  # type: ignore[arg-type]
    )
    names = [t.name for t in east.topics]
    assert "/tf" in names and "/east_1/tf" not in names and "/east_1/odom" in names
    assert east.static_topic().name == "/tf_static"
    store = messages.typestore("humble")
    stamp = cdr.stamp_of(1)
    encoded = dict(zip(names, east.messages(stamp, 0.0)))
    tf = store.deserialize_cdr(encoded["/tf"], "tf2_msgs/msg/TFMessage").transforms[0]
    assert (tf.header.frame_id, tf.child_frame_id) == ("east_1/odom", "east_1/base_link")
    assert tf.transform.translation.x == pytest.approx(0.2)
    odom = store.deserialize_cdr(encoded["/east_1/odom"], "nav_msgs/msg/Odometry")
    assert (odom.header.frame_id, odom.child_frame_id) == ("east_1/odom", "east_1/base_link")
    ps0 = store.deserialize_cdr(encoded["/east_1/ps0"], "sensor_msgs/msg/Range")
    assert ps0.header.frame_id == "east_1/ps0"
    scan = store.deserialize_cdr(encoded["/east_1/scan"], "sensor_msgs/msg/LaserScan")
    assert scan.header.frame_id == "east_1/laser_scanner"
    static = store.deserialize_cdr(east.static_transforms(stamp), "tf2_msgs/msg/TFMessage")
    pairs = {(t.header.frame_id, t.child_frame_id) for t in static.transforms}
    assert ("east_1/base_link", "east_1/ps7") in pairs and (
        "east_1/base_link",
        "east_1/gs0",
    ) in pairs
    # The world's map frame holds each robot's odometry frame, which is the world's own.
    assert ("map", "east_1/odom") in pairs
    assert all(parent == "east_1/base_link" for parent, child in pairs if parent != "map")


@needs_ros2
def test_the_frame_prefix_is_refused_for_a_world_of_one_robot(
    capsys: pytest.CaptureFixture[str],
) -> None:
    from mazesim.cli import main

    assert main(["ros2", "bridge", "--frame-prefix", "--stop-after", "1"]) == 2
    assert "expected a world of several robots for --frame-prefix" in capsys.readouterr().err


@needs_ros2
@pytest.mark.parametrize(
    "options, words",
    [
        (["--namespace", "2nd"], "expected a ROS namespace for --namespace"),
        (["--namespace", "a//b"], "expected a ROS namespace for --namespace"),
        (
            ["--namespace", "west", "--world", "TWO"],
            "expected a world of one robot for --namespace",
        ),
    ],
)
def test_a_namespace_that_is_no_ros_name_or_for_several_robots_is_refused(
    options: list[str], words: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from mazesim.cli import main

    world = tmp_path / "two.toml"
    world.write_text(TWO_ROBOTS)
    options = [str(world) if option == "TWO" else option for option in options]
    assert main(["ros2", "bridge", *options, "--stop-after", "1"]) == 2
    assert words in capsys.readouterr().err


def _drive_two_robots(tmp_path: Path, steps: int, *options: str) -> Any:
    """The bridge on :data:`TWO_ROBOTS` and the swarm driver, both given ``options``, for
    ``steps`` lockstep steps in a private network namespace; their result."""
    world = tmp_path / "two.toml"
    world.write_text(TWO_ROBOTS)
    bridge = [*MAZESIM, "ros2", "bridge", "--world", str(world), "--stop-after", str(steps)]
    driver = [sys.executable, str(SWARM_DRIVER), "--world", str(world), "--steps", str(steps)]
    result = run_in_namespace([[*bridge, *options]], [*driver, *options])
    assert result.returncode == 0, result.stderr
    assert f"stopped after {steps} steps" in result.stderr
    return result


@needs_ros2
@needs_namespace
def test_two_robots_each_move_on_their_own_cmd_vel(tmp_path: Path) -> None:
    steps = 60
    result = _drive_two_robots(tmp_path, steps)
    assert f"{steps} steps, every robot equal on its own topics" in result.stdout
    assert "2 robots (namespaces /west, /east_1)" in result.stderr
    poses = json.loads(result.stdout.strip().splitlines()[-1])
    # West drove straight on along +x; east turned where it stood.
    west_x, west_y, west_yaw = poses["/west"]
    assert west_x > -0.2 + 0.1 and west_y == pytest.approx(0.0, abs=5e-3)
    east_x, east_y, east_yaw = poses["/east_1"]
    assert math.hypot(east_x - 0.2, east_y) < 5e-3
    assert abs(math.remainder(east_yaw - math.pi, 2 * math.pi)) > 1.0


@needs_ros2
@needs_namespace
def test_with_a_frame_prefix_each_robots_transform_is_on_the_one_tf(tmp_path: Path) -> None:
    # Webots' e-puck driver moves the robot through ros2_control's diff drive controller, which
    # in namespace /west publishes west/odom -> west/base_link on /tf: a node looking a robot
    # up there finds it, in step with the robot's own pose.
    result = _drive_two_robots(tmp_path, 40, "--frame-prefix")
    assert "40 steps, every robot equal on its own topics and on /tf" in result.stdout
    assert "frames prefixed with the namespace's name, on /tf" in result.stderr


@needs_ros2
@needs_namespace
def test_an_avoid_collision_node_per_robot_drives_each_in_its_namespace(tmp_path: Path) -> None:
    world = tmp_path / "two.toml"
    world.write_text(TWO_ROBOTS)
    bag = tmp_path / "bag"
    steps = 120
    bridge = [*MAZESIM, "ros2", "bridge", "--world", str(world), "--stop-after", str(steps)]
    nodes = [[*MAZESIM, "ros2", "avoid-collision", "--robot", name] for name in ("west", "east-1")]
    result = run_in_namespace(nodes, [*bridge, "--bag", str(bag)], grace=1.0)
    assert result.returncode == 0, result.stderr
    assert f"stopped after {steps} steps" in result.stderr
    # Each node answered every state of its own robot that stepped it: the reset state and
    # each step's before the last; the last state's answer comes after the bridge stopped, if
    # it reached the node before the node's own stop (a matter of time, so either count).
    answered = re.findall(r"avoid_collision: stopped after (\d+) commands", result.stderr)
    assert len(answered) == 2 and {int(n) for n in answered} <= {steps, steps + 1}, answered
    make_reader = pytest.importorskip("mcap.reader").make_reader
    decoder_factory = pytest.importorskip("mcap_ros2.decoder").DecoderFactory
    poses: dict[str, list[list[float]]] = {}
    with next(bag.glob("*.mcap")).open("rb") as stream:
        reader = make_reader(stream, decoder_factories=[decoder_factory()])
        for _schema, channel, _message, decoded in reader.iter_decoded_messages():
            if channel.topic.endswith("/pose"):
                poses.setdefault(channel.topic, []).append(list(decoded.data))
    assert sorted(poses) == ["/east_1/pose", "/west/pose"]
    for track in poses.values():
        assert len(track) == steps + 1
        travelled = sum(math.dist(a[:2], b[:2]) for a, b in zip(track, track[1:]))
        assert travelled > 0.1, travelled


def test_the_ros2_demo_refuses_a_world_of_several_robots(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from mazesim.cli import main

    world = tmp_path / "two.toml"
    world.write_text(TWO_ROBOTS)
    assert main(["ros2", "demo", "--world", str(world), "--out", str(tmp_path / "d")]) == 2
    assert "mazesim ros2 demo drives one robot" in capsys.readouterr().err
