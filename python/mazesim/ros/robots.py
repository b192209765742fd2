"""The robots of a world of several robots as both ROS bridges serve them: one namespace each.

As Webots' ROS 2 driver runs several robots (one driver node per robot, each in a namespace of its
own, as ``webots_ros2_universal_robot/launch/multirobot_launch.py`` of cyberbotics/webots_ros2
launches them), and as the e-puck's ROS 1 driver's ``multi_epuck.launch`` groups each robot's
nodes in a namespace of its own, the bridges publish robot ``west``'s topics as ``/west/sensors``,
``/west/odom``... and read its commands on ``/west/cmd_vel``, ``/west/motor`` and
``/west/action``; ``/clock`` is one for all. :func:`robot_namespaces` turns the world's robot
names into ROS names; a :class:`RobotOf` is one robot of a simulator, read as a simulator of one
robot is; :func:`frame_prefix` names a robot's frames after its namespace; :func:`next_round` is
the lockstep rule over several robots.
"""

from __future__ import annotations

import re
from collections import deque
from collections.abc import Callable, Sequence
from typing import Any, Protocol

from mazesim._core import Simulator
from mazesim.errors import InvalidArgumentError, _shown
from mazesim.webots.shared_world import RobotView

__all__ = ["RobotOf", "frame_prefix", "next_round", "robot_namespaces", "step_rounds"]

#: What a ROS name token may not hold (it holds letters, digits and underscores).
_NOT_IN_NAME = re.compile(r"[^A-Za-z0-9_]")


def robot_namespaces(names: Sequence[str]) -> list[str]:
    """Each robot's namespace, ``"/" + name`` with every character a ROS name may not hold
    (``-``, ``.``, spaces...) replaced by ``_`` and ``r_`` before a leading digit.

    Raises:
        InvalidArgumentError: Two names give the same namespace.
    """
    namespaces: list[str] = []
    for name in names:
        token = _NOT_IN_NAME.sub("_", name) or "robot"
        if not token[0].isalpha():
            token = "r_" + token
        namespace = "/" + token
        if namespace in namespaces:
            other = names[namespaces.index(namespace)]
            raise InvalidArgumentError(
                "expected robot names that give distinct ROS namespaces; found "
                f"{_shown(other)} and "
                f"{_shown(name)}, both {namespace}: rename one in the world file"
            )
        namespaces.append(namespace)
    return namespaces


def frame_prefix(namespace: str) -> str:
    """What the frames of the robot in ``namespace`` start with, in both bridges: ``"west/"``
    for ``"/west"`` (``west/odom``, ``west/base_link``...), ``""`` for no namespace, as
    ros2_controllers' diff drive controller names its frames after its namespace."""
    name = namespace.strip("/")
    return name + "/" if name else ""


class RobotOf(RobotView):
    """Robot ``index`` of a simulator of several robots, with the calls the bridge's topics
    read of a simulator of one robot: a :class:`~mazesim.webots.shared_world.RobotView` with the
    robot's profile and its last checkpoint crossing."""

    def __init__(self, simulator: Simulator, index: int) -> None:
        super().__init__(simulator, index)
        self.robot = simulator.robot_profile(index)

    @property
    def last_crossing(self) -> int:
        """The signed checkpoint crossed in the last step (0: none)."""
        return int(self._state("last_crossing"))


def next_round(
    pending: Sequence[deque[tuple[float, float]]], driven: Sequence[bool]
) -> list[tuple[float, float] | None] | None:
    """Lockstep over several robots, the rule of both bridges: the world steps once every robot
    that is driven (a node writes on one of its command topics) has a command waiting, and at
    least one has. Takes each waiting robot's oldest command off its queue and returns them, one
    entry per robot (``None``: the robot keeps its wheel speeds, as a robot nobody drives does);
    ``None`` when the world must wait.
    """
    if not any(pending):
        return None
    if not all(queue or not is_driven for queue, is_driven in zip(pending, driven)):
        return None
    return [queue.popleft() if queue else None for queue in pending]


class _Commanded(Protocol):
    pending: deque[tuple[float, float]]
    wheel_speeds: tuple[float, float]

    def driven(self) -> bool: ...


def step_rounds(robots: Sequence[_Commanded], stop: Any, step: Callable[[], None]) -> None:
    """Lockstep: while :func:`next_round` gives a round (and ``stop``, an event, is not set),
    sets each robot's wheel speeds to its command of the round and calls ``step``."""
    while not stop.is_set():
        pending = [robot.pending for robot in robots]
        taken = next_round(pending, [robot.driven() for robot in robots])
        if taken is None:
            return
        for robot, command in zip(robots, taken):
            if command is not None:
                robot.wheel_speeds = command
        step()
