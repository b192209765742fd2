"""A bag given to the bag reader is opened by mazesim's input opener before ROS 1's rosbag reads
it: a path that is not a regular file, loops, or is not a path fails in the package's tree. The
run read from a bag keeps the robot's profile, as a run file does."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

pytest.importorskip("rosbag", reason="ROS 1's rosbag is not installed (make ros-deps)")

import mazesim  # noqa: E402
from mazesim import RobotProfile  # noqa: E402
from mazesim.errors import InvalidArgumentError, MazesimIOError  # noqa: E402
from mazesim.replay.ros_bag import read_topics, run_from_bag  # noqa: E402
from mazesim.replay.run import load_run, save_run  # noqa: E402
from mazesim.ros import topics  # noqa: E402


def test_a_symlink_loop_a_folder_and_a_long_name_are_io_errors_naming_the_bag(
    tmp_path: Path,
) -> None:
    loop = tmp_path / "loop.bag"
    os.symlink(loop.name, loop)
    for path, reason in (
        (loop, "symbolic links"),
        (tmp_path, "expected a regular file"),
        (tmp_path / ("x" * 300), "too long"),
    ):
        with pytest.raises(MazesimIOError, match=reason) as caught:
            read_topics(str(path), ("/pose",))
        assert caught.value.filename == str(path)


def test_a_file_descriptor_number_is_not_a_bag() -> None:
    # open(True) would read (and then close) standard output.
    with pytest.raises(InvalidArgumentError, match="bag_path"):
        read_topics(True, ("/pose",))  # type: ignore[arg-type]
    print("standard output still open")


def _big_slow_epuck() -> RobotProfile:
    """The e-puck's profile renamed ``big-slow``, with a motor limit of 3 rad/s: no built-in
    profile has its name."""
    text = RobotProfile.builtin("e-puck").to_toml()
    for old, new in (('name = "e-puck"', 'name = "big-slow"'),
                     ("max_wheel_speed = 6.28", "max_wheel_speed = 3.0")):  # fmt: skip
        assert old in text
        text = text.replace(old, new)
    return RobotProfile.from_toml(text)


def test_a_bag_of_a_profile_file_s_robot_replays_with_its_profile(tmp_path: Path) -> None:
    # The bag's run keeps the profile the bridge drove, as a run of the simulator does: its file
    # holds it (format 1.3), rather than a name no built-in profile has.
    import rosbag
    from std_msgs.msg import Float64MultiArray

    profile = _big_slow_epuck()
    world = mazesim.load_world("seed-maze")
    simulator = mazesim.Simulator(world, robot=profile, seed=0)
    bag_path = tmp_path / "maze.bag"
    with rosbag.Bag(str(bag_path), "w") as bag:
        for _ in range(5):
            readings = [*simulator.distance_sensors(), *simulator.ground_sensors()]
            bag.write("/pose", Float64MultiArray(data=topics.pose_values(simulator)))
            bag.write("/sensors", Float64MultiArray(data=readings))
            bag.write("/motor", Float64MultiArray(data=[3.0, 2.0]))
            simulator.step(3.0, 2.0)
    run = run_from_bag(str(bag_path), world, profile, "avoid-collision", 0, 32.0)
    assert run.robot == "big-slow" and run.robot_profile == profile
    assert run.episodes[0].frames == 5
    run_file = tmp_path / "run.json"
    save_run(run, run_file)
    assert json.loads(run_file.read_text())["version"] == "1.3"
    assert load_run(run_file).robot_profile.max_wheel_speed == 3.0
