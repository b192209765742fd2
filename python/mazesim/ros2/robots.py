"""The robots of a world of several robots as the ROS 2 bridge publishes them: one namespace each
(the rule both bridges share, :mod:`mazesim.ros.robots`)."""

from __future__ import annotations

from mazesim.ros.robots import RobotOf, frame_prefix, next_round, robot_namespaces, step_rounds

__all__ = ["RobotOf", "frame_prefix", "next_round", "robot_namespaces", "step_rounds"]
