"""The robots of a world of several robots as the ROS 2 bridge publishes them: one namespace each.

As Webots' ROS 2 driver runs several robots (one driver node per robot, each in a namespace of its
own, as ``webots_ros2_universal_robot/launch/multirobot_launch.py`` of cyberbotics/webots_ros2
launches them), the bridge publishes robot ``west``'s topics as ``/west/ps0``, ``/west/odom``,
``/west/tf``... and reads its commands on ``/west/cmd_vel``, ``/west/motor`` and ``/west/action``;
``/clock`` is one for all. :func:`robot_namespaces` turns the world's robot names into ROS names;
a :class:`RobotOf` is one robot of a simulator, read as a simulator of one robot is.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from mazesim._core import Simulator
from mazesim.errors import InvalidArgumentError, _shown
from mazesim.webots.shared_world import RobotView

__all__ = ["RobotOf", "robot_namespaces"]

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
