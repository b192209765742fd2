"""The ROS 1 bridge's own bag (``mazesim ros bridge --bag PATH``, the ``bag`` parameter).

A ``rosbag record`` node beside a lockstep bridge misses messages: on simulated time it waits for
a first ``/clock`` and loses the steps before it (22 of 95 in one run of ``maze.launch``), and a
recorder short of CPU drops messages once its subscriber queue (100 messages, fixed in rosbag) is
full (96 of 1,062 of one topic, measured on a loaded machine). The bridge writes what it sends and
takes as it does so: every message it publishes (the state of each step, ``/clock`` and the
standard messages) and every command it takes, the command before the state it leads to. The bag
holds every step by construction. Messages are stamped with the wall clock, as a recorder on wall
time stamps them; a state the bridge sends again (see
:class:`~mazesim.ros.lockstep.UnansweredState`) is written once.

The bag is written to ``PATH.active`` and renamed to ``PATH`` when the bridge stops, as ``rosbag
record`` does: a run cut short leaves the ``.active`` file, never a half-written ``PATH``.
"""

from __future__ import annotations

import os
import threading
import time
from typing import Any

from mazesim.errors import MazesimIOError

__all__ = ["BagWriter"]


class BagWriter:
    """Writes messages into a ROS 1 bag, from any thread; see the module's description."""

    def __init__(self, ros: Any, path: str) -> None:
        import rosbag

        self.path = os.path.abspath(path)
        self.active = self.path + ".active"
        self._time = ros.rospy.Time
        self._lock = threading.Lock()
        if os.path.isdir(self.path):
            raise MazesimIOError(
                f"expected a bag file to write; found the folder {self.path}: give --bag a file "
                "name such as run.bag"
            )
        try:
            self._bag: Any = rosbag.Bag(self.active, "w")
        except (OSError, rosbag.ROSBagException) as error:
            raise MazesimIOError(
                f"cannot write the bag {self.path}: {error}; give --bag a path in a folder you "
                "can write"
            ) from None

    def write(self, topic: str, message: Any) -> None:
        """Writes ``message`` on ``topic`` (a resolved name), stamped now; nothing once closed."""
        with self._lock:
            if self._bag is not None:
                self._bag.write(topic, message, self._time.from_sec(time.time()))

    def close(self) -> None:
        """Finishes the bag and gives it its name (once; later calls do nothing)."""
        with self._lock:
            if self._bag is None:
                return
            self._bag.close()
            self._bag = None
        os.replace(self.active, self.path)
