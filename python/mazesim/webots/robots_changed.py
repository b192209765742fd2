"""Robots a supervisor imports into a running world of several robots, or removes from it
(``importMFNodeFromString`` of an ``E-puck { ... }``, ``Node.remove()`` of a robot's node), as
Webots has them.

A robot's identity is the line of its node in the running world's description
(:mod:`mazesim.webots.scene_edits` keeps every node on its line, appending imported ones): the
robots of the changed world on the lines of running ones are those robots, which go on as they
were; the others are imported now. An imported e-puck joins the e-pucks' shared simulator
(:mod:`mazesim.webots.shared_world`) at its node's pose, at rest, on the running clock, with a
noise stream of its own (``Simulator.change_world``'s ``kept_robots``), and its controller
starts at once, to step in lockstep with the others from the next step. The first e-pucks
imported into a world that had none (its only robot a supervisor that imports the swarm) make
that shared simulator, on the running clock. A removed robot
leaves the simulation: a :class:`RemovedRobot` keeps where it was and what it did, and its
controller's next ``Robot.step`` returns -1. An imported robot that is not an e-puck is kept
as an obstacle, as the import of a world file keeps one (its controller does not run). Refused,
with an error naming it: an e-puck imported into a world whose e-pucks run in simulators of
their own.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from mazesim._core import World
from mazesim._toml import dump_toml, load_toml
from mazesim.errors import MazesimError, _shown
from mazesim.webots.proto_fields import robot_label
from mazesim.webots.shared_world import RobotView, placed_robot, with_robots_of

__all__ = ["RemovedRobot", "RobotChange", "kept_robots", "robot_change"]


class RemovedRobot:
    """A robot a supervisor removed from the world: its pose, clock, counters and last readings
    as they were then; it steps no more and is no longer moved."""

    def __init__(self, simulator: Any) -> None:
        self.pose = tuple(float(v) for v in simulator.pose)
        self.time = float(simulator.time)
        self.encoders = tuple(float(v) for v in simulator.encoders)
        self.wheel_turns = tuple(float(v) for v in simulator.wheel_turns)
        self.distance_travelled = float(simulator.distance_travelled)
        self.collisions = int(simulator.collisions)
        self.control_step_ms = float(simulator.control_step_ms)
        self.colliding = False
        self._readings = (
            np.array(simulator.distance_sensors(), dtype=np.float32),
            np.array(simulator.ground_sensors(), dtype=np.float32),
        )
        #: The profile of a shared simulator's robot, or the simulator's own.
        self.robot = getattr(simulator, "robot", None)
        shared = getattr(simulator, "simulator", None)
        self.profile = shared.robot_profile(simulator.index) if shared else None

    def distance_sensors(self) -> Any:
        """The proximity readings when it was removed."""
        return self._readings[0]

    def ground_sensors(self) -> Any:
        """The ground readings when it was removed."""
        return self._readings[1]

    def step(self, left: float, right: float) -> None:
        """Nothing: a removed robot does not move."""

    def set_pose_pushed_out(self, x: float, y: float, yaw: float) -> tuple[float, float]:
        """Refused: the robot is no longer in the world.

        Raises:
            MazesimError: Always.
        """
        raise MazesimError("expected a robot of the world, found one a supervisor removed")


@dataclass(frozen=True)
class RobotChange:
    """How a supervisor's change of the world changes its robots.

    Attributes:
        world: The new world of the e-pucks' shared simulator (None without one).
        kept: For each robot of ``world``, the index in the shared simulator of the robot it
            is, or None for an imported one (``Simulator.change_world``'s ``kept_robots``).
        order: The run's index of each robot of ``world``.
        added: The import report entries of the imported robots, in order; they take the
            run's next indices.
        removed: The run's indices of the robots taken out.
        opens: Whether the imported robots are the run's first e-pucks, whose shared
            simulator the run makes now of ``world`` (in a world that had none, such as one
            whose only robot is a supervisor that imports the swarm).
    """

    world: World | None
    kept: list[int | None]
    order: list[int]
    added: list[dict[str, Any]]
    removed: list[int]
    opens: bool = False


def kept_robots(report: Mapping[str, Any], running: Collection[int]) -> list[dict[str, Any]]:
    """The robots of a changed world's import ``report`` that the run has or adds: those on
    the ``running`` robots' lines, and the imported e-pucks; an imported robot that is not an
    e-puck is an obstacle (its collision shapes, as the import of a world file keeps one)."""
    return [
        dict(r)
        for r in report.get("robots") or []
        if r.get("profile") is not None or int(r["line"]) in running
    ]


def robot_change(
    robots: Sequence[Mapping[str, Any]],
    simulators: Sequence[Any],
    gone: set[int],
    report: Mapping[str, Any],
    world: World,
) -> RobotChange | None:
    """How the changed world (``world``, imported with ``report``) changes the run's
    ``robots`` (import report entries, by run index; those in ``gone`` removed before), each
    run by ``simulators``; None when its robots are the running ones.

    Raises:
        MazesimError: A robot is imported that mazesim does not add (see the module notes).
    """
    running = {int(r["line"]): i for i, r in enumerate(robots) if i not in gone}
    found = kept_robots(report, running)
    lines = {int(r["line"]) for r in found}
    if lines == set(running):
        return None
    added = [dict(r) for r in found if int(r["line"]) not in running]
    shared = next((s.simulator for s in simulators if isinstance(s, RobotView)), None)
    removed = sorted(i for line, i in running.items() if line not in lines)
    if shared is None and added:
        if any(robots[i].get("profile") is not None for i in running.values()):
            label = robot_label(added[0])
            raise MazesimError(
                "expected a world whose e-pucks share one simulator to import robot "
                f"{_shown(label)} "
                "into, found e-pucks in simulators of their own"
            )
        return _first_e_pucks(world, len(robots), added, removed)
    if shared is None:
        return RobotChange(None, [], [], added, removed)
    layout = load_toml(with_robots_of(world, shared.world).to_toml(), shared.world.name)
    entries = {str(e["name"]): e for e in layout.get("robots") or []}
    kept: list[int | None] = []
    order: list[int] = []
    placed = []
    for robot in found:
        index = running.get(int(robot["line"]))
        if index is None and robot in added:
            index = len(robots) + added.index(robot)
            placed.append(placed_robot(f"robot-{index}", robot, robot["pose"]))
            kept.append(None)
        elif index is not None and isinstance(simulators[index], RobotView):
            placed.append(entries[f"robot-{index}"])
            kept.append(simulators[index].index)
        else:
            continue
        order.append(index)
    if not placed:
        raise MazesimError(
            "expected an e-puck left in the world, found every one removed: mazesim runs a world "
            "of one e-puck at least"
        )
    layout["robots"] = placed
    changed = World.from_toml(dump_toml(layout), source=shared.world.name)
    return RobotChange(changed, kept, order, added, removed)


def _first_e_pucks(
    world: World, count: int, added: list[dict[str, Any]], removed: list[int]
) -> RobotChange:
    """The change of a world without e-pucks into which a supervisor imports its first ones
    (``added``; the run had ``count`` robots): they make the e-pucks' shared simulator, whose
    world is ``world`` with them alone (``RobotChange.opens``)."""
    source = f"{world.name} (every e-puck)"
    layout = load_toml(world.to_toml(), source)
    layout.pop("start", None)
    placed = []
    for k, robot in enumerate(added):
        placed.append(placed_robot(f"robot-{count + k}", robot, robot["pose"]))
    layout["robots"] = placed
    changed = World.from_toml(dump_toml(layout), source=source)
    order = [count + k for k in range(len(added))]
    return RobotChange(changed, [None] * len(added), order, added, removed, opens=True)
