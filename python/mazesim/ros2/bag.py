"""``--bag FILE``: a rosbag2 in MCAP of exactly what the bridge published.

Each message is stored as the bytes that went out on the wire, with its topic's type definition
and hash for the distribution (``rosbags`` writes the bag), received time = its stamp (simulated
nanoseconds), so one step's message set shares one time. The bag is a folder; it is written in a
temporary folder beside the target and moved into place when closed, so a bag that exists is
complete.
"""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Any

from mazesim.errors import MazesimIOError
from mazesim.ros2 import messages

__all__ = ["BagRecorder"]


class BagRecorder:
    """Records published messages into a rosbag2 MCAP folder.

    Args:
        path: The bag folder to create (it must not exist).
        distro: The ROS 2 distribution of the messages.

    Raises:
        MazesimIOError: ``path`` exists, or its folder cannot be written.
    """

    def __init__(self, path: str | Path, distro: str) -> None:
        from rosbags.rosbag2 import StoragePlugin, Writer

        self.path = Path(path)
        if self.path.exists():
            raise MazesimIOError(f"expected a new bag folder; found {self.path}, which exists")
        # rosbags names the MCAP file after its folder: the folder keeps its final name inside a
        # temporary parent until the bag is complete.
        self.partial = self.path.parent / f".{self.path.name}.partial"
        if self.partial.exists():
            shutil.rmtree(self.partial)
        self.partial.mkdir(parents=True)
        self.distro = distro
        self.typestore = messages.typestore(distro)
        try:
            self.writer = Writer(
                self.partial / self.path.name, version=9, storage_plugin=StoragePlugin.MCAP
            )
            self.writer.open()
        except OSError as error:
            raise MazesimIOError(f"expected to write a bag at {self.path}; {error}") from error
        self.connections: dict[str, Any] = {}
        self.count = 0

    def write(self, topic: str, msgtype: str, nanoseconds: int, data: bytes) -> None:
        """Records one message of ``topic`` at ``nanoseconds``."""
        connection = self.connections.get(topic)
        if connection is None:
            connection = self.writer.add_connection(topic, msgtype, typestore=self.typestore)
            self.connections[topic] = connection
        self.writer.write(connection, nanoseconds, data)
        self.count += 1

    def close(self) -> None:
        """Finishes the bag and moves it into place."""
        self.writer.close()
        (self.partial / self.path.name).rename(self.path)
        self.partial.rmdir()
