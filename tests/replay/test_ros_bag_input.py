"""A bag given to the bag reader is opened by mazesim's input opener before ROS 1's rosbag reads
it: a path that is not a regular file, loops, or is not a path fails in the package's tree."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

pytest.importorskip("rosbag", reason="ROS 1's rosbag is not installed (make ros-deps)")

from mazesim.errors import InvalidArgumentError, MazesimIOError  # noqa: E402
from mazesim.replay.ros_bag import read_topics  # noqa: E402


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
