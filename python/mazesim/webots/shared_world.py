"""The e-pucks of a Webots world in one simulator, where they collide with and see each other.

:func:`shared_simulator` puts every e-puck of an imported world into one
:class:`~mazesim.Simulator` (the world's ``[[robots]]``, see ``docs/multi-robot.md``); a
:class:`RobotView` is one of them with the calls of a one-robot simulator, which is what a
controller's process asks for over its pipe (:mod:`mazesim.webots.controller_process`). An
e-puck's node holding shapes beside its body (a bumper in its ``bodySlot``, a box on its turret)
carries them there (:func:`carrying`): the other e-pucks' infra-red rays and bodies meet them,
as Webots' rays meet every Shape. The world's movable bodies are in the shared simulator too:
every e-puck pushes them and sees them where they are. Robots that overlap at their written
starts share it too, put there as a supervisor puts one onto another (a world whose supervisor
scatters them before the first step). A world the shared simulator refuses (more robots than it
holds) is run with a simulator per robot instead, with a warning.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping, Sequence
from typing import Any

from mazesim._core import RobotProfile, Simulator, World
from mazesim._toml import dump_toml, load_toml
from mazesim.errors import MazesimError
from mazesim.webots.robot_frames import carried_shapes
from mazesim.webots.scene import Scene, read_scenes

#: The heights (m) the E-puck's infra-red rays run at: from its sensors, 3.3 cm above the
#: floor, to 4.4 cm at the end of their 7 cm (``docs/webots.md``). A shape another e-puck
#: carries that spans them is met by the rays.
INFRARED_HEIGHTS = (0.033, 0.044)
#: The e-puck's body radius (m): a carried shape within it changes nothing.
E_PUCK_BODY_RADIUS = 0.037

__all__ = [
    "E_PUCK_BODY_RADIUS",
    "INFRARED_HEIGHTS",
    "RobotView",
    "carrying",
    "carrying_imported",
    "placed_robot",
    "shared_simulator",
    "with_robots_of",
]


class RobotView:
    """Robot ``index`` of a shared simulator, read and moved as a one-robot simulator is."""

    def __init__(self, simulator: Simulator, index: int) -> None:
        self.simulator = simulator
        self.index = index

    def _state(self, key: str) -> Any:
        return self.simulator.robot_state(self.index)[key]

    @property
    def pose(self) -> tuple[float, float, float]:
        """x, y, yaw now."""
        x, y, yaw = self._state("pose")
        return float(x), float(y), float(yaw)

    @property
    def time(self) -> float:
        """Simulated seconds since the start."""
        return float(self.simulator.time)

    @property
    def control_step_ms(self) -> float:
        """The control step in milliseconds."""
        return float(self.simulator.control_step_ms)

    @property
    def colliding(self) -> bool:
        """Whether the body touches a wall or another robot."""
        return bool(self._state("colliding"))

    @property
    def collisions(self) -> int:
        """Contacts begun since the start."""
        return int(self._state("collisions"))

    @property
    def distance_travelled(self) -> float:
        """Metres travelled."""
        return float(self._state("distance_travelled"))

    @property
    def encoders(self) -> tuple[float, float]:
        """The wheels' turns (rad) to the profile's encoder resolution."""
        left, right = self._state("encoders")
        return float(left), float(right)

    @property
    def wheel_turns(self) -> tuple[float, float]:
        """The wheels' turns (rad) unrounded."""
        left, right = self._state("wheel_turns")
        return float(left), float(right)

    def other_robots(self) -> list[tuple[float, float, float]]:
        """(x, y, body radius) of each other robot of the simulator now (what a camera sees
        of them)."""
        bodies = []
        for index in range(self.simulator.num_robots):
            if index != self.index:
                state = self.simulator.robot_state(index)
                x, y, _ = state["pose"]
                radius = self.simulator.robot_profile(index).body_radius
                bodies.append((float(x), float(y), float(radius)))
        return bodies

    def set_pose_pushed_out(self, x: float, y: float, yaw: float) -> tuple[float, float]:
        """Puts the robot at a pose, at rest: onto another robot too, as a Webots supervisor may
        put it (the contacts of the next steps push them apart), and out of a wall it would lie
        in (:meth:`mazesim.Simulator.set_pose_pushed_out`); returns the x, y it stands at."""
        return self.simulator.set_pose_pushed_out(
            x, y, yaw, robot_index=self.index, overlap_robots=True
        )

    def distance_sensors(self) -> Any:
        """The proximity readings."""
        return self.simulator.distance_sensors(robot_index=self.index)

    def ground_sensors(self) -> Any:
        """The ground readings."""
        return self.simulator.ground_sensors(robot_index=self.index)


def carrying(
    robots: Sequence[Mapping[str, Any]], scenes: Sequence[Scene]
) -> list[Mapping[str, Any]]:
    """The import report's ``robots`` (each with the scene of its node, ``scenes``), each
    e-puck's with ``carried``: the Box, Cylinder and Sphere shapes its node holds beside its
    body (in its slots or among its children) where they span the infra-red rays' heights
    (:data:`INFRARED_HEIGHTS`), which the other e-pucks' rays and bodies meet in the shared
    simulator (:func:`~mazesim.webots.robot_frames.carried_shapes`)."""
    placed: list[Mapping[str, Any]] = []
    for index, robot in enumerate(robots):
        carried = []
        if robot.get("profile") is not None and len(scenes) > 1:
            # The node as another robot's run reads it: one of the others, shapes and all.
            seen_from = scenes[(index + 1) % len(scenes)]
            line = int(robot.get("line") or 0)
            carried = carried_shapes(seen_from, line, E_PUCK_BODY_RADIUS, INFRARED_HEIGHTS)
        placed.append({**robot, "carried": carried} if carried else robot)
    return placed


def carrying_imported(
    robots: Sequence[Mapping[str, Any]], text: str, running: Collection[int]
) -> list[Mapping[str, Any]]:
    """A changed world's import report ``robots`` (the world's text ``text``), each e-puck a
    supervisor imported (on none of the ``running`` robots' lines) with the shapes its node
    carries, as :func:`carrying` gives a world file's e-pucks theirs: read in the scene of a
    running robot's run, in which the imported node is one of the others."""
    added = [r for r in robots if r.get("profile") is not None and int(r["line"]) not in running]
    if not added or not running:
        return list(robots)
    new_lines = {int(r["line"]) for r in added}
    seen_from = next((r for r in robots if int(r["line"]) in running), None)
    model = None if seen_from is None else seen_from.get("model")
    line = min(running) if seen_from is None else int(seen_from["line"])
    y_up = None if seen_from is None else seen_from.get("y_up")
    scene = read_scenes(text, [(None if model is None else str(model), line)], [y_up])[0]
    placed: list[Mapping[str, Any]] = []
    for robot in robots:
        carried = []
        line = int(robot["line"])
        if line in new_lines:
            carried = carried_shapes(scene, line, E_PUCK_BODY_RADIUS, INFRARED_HEIGHTS)
        placed.append({**robot, "carried": carried} if carried else robot)
    return placed


def placed_robot(name: str, robot: Mapping[str, Any], pose: Sequence[float]) -> dict[str, Any]:
    """The ``[[robots]]`` entry of the shared simulator's world for a robot of an import report
    (``robot``) at ``pose``: its name there, its profile and the shapes it carries
    (:func:`carrying`, :func:`carrying_imported`). Every robot the shared simulator holds, of
    the world file or imported by a supervisor, is placed by it, so that they are alike."""
    x, y, yaw = (float(v) for v in pose)
    entry: dict[str, Any] = {"name": name, "x": x, "y": y, "yaw": yaw}
    entry["profile"] = robot.get("profile") or "e-puck"
    if robot.get("carried"):
        entry["carried"] = list(robot["carried"])
    return entry


def shared_simulator(
    world: World,
    robots: Sequence[Mapping[str, Any]],
    indices: Sequence[int],
    *,
    seed: int,
    noise: bool,
    profiles: Mapping[int, RobotProfile] | None = None,
) -> tuple[Simulator | None, str]:
    """One simulator of the robots ``indices`` of a world's ``robots`` (import report entries),
    in that order, or None and why not.

    Args:
        world: The imported world (its walls, paint and movable bodies).
        robots: The import report's ``robots``.
        indices: The robots to put in the simulator (the e-pucks).
        seed: Seed of the sensor noise; each robot's stream derives from it and its name.
        noise: Whether the sensors are noisy.
        profiles: The profile of some robots (by index in ``robots``) instead of the built-in
            one their entry names: a robot node's own sensors
            (:func:`~mazesim.webots.own_sensors.own_sensors`).
    """
    source = f"{world.name} (every e-puck)"
    layout = load_toml(world.to_toml(), source)
    layout.pop("start", None)
    starts = [tuple(float(v) for v in robots[index]["pose"]) for index in indices]
    try:
        return _built(layout, robots, indices, starts, source, seed, noise, profiles), ""
    except MazesimError as refusal:
        if "do not overlap" not in str(refusal):
            return None, str(refusal)
    # Robots that overlap at their written starts (a world whose supervisor scatters them
    # before the first step): built apart, beyond the world's walls and bodies, then put at
    # their starts as a supervisor puts one onto another, whose contacts push them apart at
    # the next steps unless a supervisor moves them first, as Webots' physics does.
    far = _beyond(world, layout, starts)
    apart = [(far + 0.2 * k, far, 0.0) for k in range(len(indices))]
    try:
        simulator = _built(layout, robots, indices, apart, source, seed, noise, profiles)
        for k, (x, y, yaw) in enumerate(starts):
            simulator.set_pose(x, y, yaw, robot_index=k, overlap_robots=True)
    except MazesimError as refusal:
        return None, str(refusal)
    return simulator, ""


def with_robots_of(world: World, running: World) -> World:
    """``world`` (a world file imported again, as a supervisor changed it) with the robots of
    ``running``, the world of the simulator :func:`shared_simulator` made."""
    source = running.name
    layout = load_toml(world.to_toml(), source)
    layout.pop("start", None)
    layout["robots"] = load_toml(running.to_toml(), source).get("robots", [])
    return World.from_toml(dump_toml(layout), source=source)


def _built(
    layout: dict[str, Any],
    robots: Sequence[Mapping[str, Any]],
    indices: Sequence[int],
    poses: Sequence[tuple[float, ...]],
    source: str,
    seed: int,
    noise: bool,
    profiles: Mapping[int, RobotProfile] | None,
) -> Simulator:
    """The simulator of ``layout`` with the robots ``indices`` at ``poses``."""
    placed = dict(layout, robots=[])
    for index, pose in zip(indices, poses):
        placed["robots"].append(placed_robot(f"robot-{index}", robots[index], pose))
    shared = World.from_toml(dump_toml(placed), source=source)
    if not profiles:
        return Simulator(shared, seed=seed, noise=noise)
    given = [profiles.get(index) for index in indices]
    return Simulator(shared, seed=seed, noise=noise, robot_profiles=given)


def _beyond(world: World, layout: Mapping[str, Any], starts: Sequence[tuple[float, ...]]) -> float:
    """A coordinate 1 m beyond every wall, movable body and start of the world, on both axes."""
    reach = [abs(v) for x, y, _ in starts for v in (x, y)]
    for cx, cy, sx, sy, *_ in world.wall_boxes():
        reach.append(float(max(abs(cx), abs(cy)) + max(sx, sy)))
    for body in layout.get("bodies") or []:
        cx, cy = (float(v) for v in body.get("center", (0.0, 0.0)))
        size = body.get("size") or [2 * float(body.get("radius", 0.0))] * 2
        reach.append(max(abs(cx), abs(cy)) + max(float(v) for v in size))
    return float(max(reach, default=0.0)) + 1.0
