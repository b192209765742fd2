"""``mazesim webots run WORLD.wbt``: every robot of a Webots world with its own controller.

The summary, the picture, the table, ``--html``/``--video``/``--record`` and the ``--live``
window cover every robot (:class:`WorldWatch`); ``--keys`` types on every controller's
Keyboard, as Webots sends the keys typed with no robot selected to every robot. A run of one
controller in a mazesim world of several robots (``webots run CONTROLLER --world WORLD.toml``)
covers them all too (:class:`RobotPaths`).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from collections.abc import Mapping
from typing import Any, TextIO

from mazesim._atomic import atomic_file
from mazesim._core import RobotProfile, World
from mazesim.errors import InvalidArgumentError, _shown

__all__ = [
    "RobotPaths",
    "WorldWatch",
    "robot_controllers",
    "run_world_command",
    "whole_world_run",
    "write_paths_table",
]


class WorldWatch:
    """Records every robot of a world run, step by step, for ``--html``, ``--video`` and
    ``--record``, and shows them ``--live`` (a :data:`mazesim.webots.lockstep.StepObserver`).

    Args:
        seed: The run's seed.
        record: Whether to record.
        live: Whether to show the run in the live window.
    """

    def __init__(self, seed: int, record: bool = True, live: bool = False) -> None:
        self.seed = seed
        self.record = record
        self.live = live
        self.fleet: Any = None
        self.view: Any = None

    def __call__(
        self,
        world: World,
        runs: list[Any],
        simulators: list[Any],
        wheels: Mapping[int, tuple[float, float]] | None,
    ) -> None:
        """Records (and shows) every robot's frame before a step (after the last: ``wheels``
        None); ``world`` is the world as it runs now (the window draws its walls)."""
        import numpy as np

        from mazesim.replay.recorder import FleetRecorder
        from mazesim.replay.views import FleetLiveView
        from mazesim.webots.robots_changed import RemovedRobot

        if self.fleet is None:
            robots = [
                (run.name, _profile_of(simulator)) for run, simulator in zip(runs, simulators)
            ]
            step_ms = float(simulators[0].control_step_ms)
            self.fleet = FleetRecorder(world, robots, "world controllers", self.seed, step_ms)
            if self.live:
                self.view = FleetLiveView(world, robots[0][1], step_ms, f"mazesim: {world.name}")
        if self.view is not None:
            self.view.follow(world)
            self.view.show(
                [
                    None if isinstance(simulator, RemovedRobot) else simulator.pose
                    for simulator in simulators
                ],
                [bool(simulator.colliding) for simulator in simulators],
                f"t {simulators[0].time:6.2f} s",
            )
            if wheels is None:
                self.view.close()
        if not self.record:
            return
        self.fleet.follow(world)
        for index in range(len(self.fleet.recorders), len(simulators)):
            simulator = simulators[index]
            readings = np.concatenate((simulator.distance_sensors(), simulator.ground_sensors()))
            self.fleet.join(runs[index].name, _profile_of(simulator), simulator.pose, readings)
        for index, simulator in enumerate(simulators):
            if isinstance(simulator, RemovedRobot):
                self.fleet.leave(index)
            readings = np.concatenate((simulator.distance_sensors(), simulator.ground_sensors()))
            self.fleet.capture(index, simulator.pose, readings, bool(simulator.colliding))
            if wheels is not None:
                self.fleet.acted(index, *wheels.get(index, (0.0, 0.0)))


class RobotPaths:
    """Every robot's path in a run of one controller in a world of several robots, where the
    controller drives robot 0 and the others stand where they start (an observer of
    :func:`mazesim.webots.simulation.observing_steps`): robot 0's path is the run's own, the
    others' are their poses before each step and at the end.

    Args:
        world: The run's world.
    """

    def __init__(self, world: World) -> None:
        self.world = world
        self.simulator: Any = None
        self._points: dict[int, Any] = {}

    def __call__(self, simulation: Any, left: float, right: float) -> None:
        """Keeps every robot's position before a step of ``simulation`` (its ``simulator``)."""
        if self.simulator is None:
            self.simulator = simulation.simulator
        if simulation.simulator is self.simulator and self.several:
            self._points.setdefault(int(self.simulator.steps), self.simulator.poses()[:, :2])

    @property
    def several(self) -> bool:
        """Whether the run's world holds several robots."""
        return len(self.world.robots) > 1

    def robots(
        self, controller: str, profile: str, xs: list[float], ys: list[float]
    ) -> tuple[list[dict[str, Any]], list[tuple[str, Any, Any]]]:
        """Each robot's entry of the summary (name, profile, controller, distance, collisions,
        final pose) and its path (name, xs, ys), after the run; robot 0 drove along ``xs``,
        ``ys`` with ``controller``. Before any step (a controller that failed at once) every
        robot is where it starts, with the world's profile or ``profile``."""
        import numpy as np

        simulator = self.simulator
        if simulator is None:
            states = [
                {
                    "profile": robot["profile"] or profile,
                    "distance_travelled": 0.0,
                    "collisions": 0,
                    "pose": robot["start"],
                }
                for robot in self.world.robots
            ]
            self._points[0] = np.array([robot["start"][:2] for robot in self.world.robots])
        else:
            states = [simulator.robot_state(i) for i in range(simulator.num_robots)]
            self._points.setdefault(int(simulator.steps), simulator.poses()[:, :2])
        points = np.stack([self._points[step] for step in sorted(self._points)])
        entries, paths = [], []
        for index, (robot, state) in enumerate(zip(self.world.robots, states)):
            entries.append(
                {
                    "name": robot["name"],
                    "robot": str(state["profile"]),
                    "controller": controller if index == 0 else None,
                    "distance_m": float(state["distance_travelled"]),
                    "collisions": int(state["collisions"]),
                    "final_pose": [float(v) for v in state["pose"]],
                }
            )
            path_x, path_y = (xs, ys) if index == 0 else (points[:, index, 0], points[:, index, 1])
            paths.append((str(robot["name"]), path_x, path_y))
        return entries, paths


def write_paths_table(
    path: str, paths: list[tuple[str, Any, Any]], step_s: float, starts: list[float] | None = None
) -> None:
    """Writes every robot's path as the table ``robot,time_s,x_m,y_m`` (atomically); path
    ``i`` starts at ``starts[i]`` seconds when given (a robot a supervisor imported), else 0."""
    begin = starts or [0.0] * len(paths)
    with atomic_file(path) as handle:
        rows = [
            f"{name},{start + i * step_s:.3f},{x:.5f},{y:.5f}"
            for (name, xs, ys), start in zip(paths, begin)
            for i, (x, y) in enumerate(zip(xs, ys))
        ]
        handle.write(("robot,time_s,x_m,y_m\n" + "\n".join(rows) + "\n").encode("utf-8"))


def _profile_of(simulator: Any) -> RobotProfile:
    """The profile of a simulator of one robot, or of a shared simulator's robot."""
    shared = getattr(simulator, "simulator", None)
    if shared is not None:
        profile_of_robot: RobotProfile = shared.robot_profile(simulator.index)
        return profile_of_robot
    if getattr(simulator, "profile", None) is not None:  # a robot a supervisor removed
        removed: RobotProfile = simulator.profile
        return removed
    profile: RobotProfile = simulator.robot
    return profile


def whole_world_run(args: argparse.Namespace, controller_file: str) -> argparse.Namespace | None:
    """The arguments of a world run standing for ``webots run CONTROLLER --world WORLD.wbt``
    when another robot of the world leaves its ``controller`` field out and so runs its PROTO's
    default controller in Webots (the E-puck's ``e-puck_avoid_obstacles``), else None.

    The given controller runs on the robot a run of one controller chooses (the first e-puck
    whose ``controller`` field names it, else the first e-puck), named by its ``controller``
    field, its name or its DEF name; the other robots run their own controllers, as in
    ``webots run WORLD.wbt``. A run with ``--keys`` (one controller's Keyboard) or ``--strict``
    (which then checks the import for that one controller, the other e-pucks' warnings
    included), or whose robot no name tells from the others, stays a run of one controller.
    """
    from mazesim.webots.importer import import_wbt
    from mazesim.webots.lockstep import controller_of

    world = getattr(args, "world", None)
    one_robot_only = getattr(args, "keys", None) or getattr(args, "strict", False)
    if not world or not str(world).lower().endswith(".wbt") or one_robot_only:
        return None
    controller = os.path.splitext(os.path.basename(controller_file))[0]
    _, report = import_wbt(world, controller=controller)
    robots = list(report.get("robots") or [])
    chosen = [robot for robot in robots if robot.get("line") == report.get("robot_line")]
    defaults = [
        robot
        for robot in robots
        if robot not in chosen
        and robot.get("controller") is None
        and controller_of(robot, str(world), {})[0] is not None
    ]
    if len(chosen) != 1 or not defaults:
        return None
    key = _robot_key(chosen[0], robots, controller)
    if key is None:
        return None
    labels = ", ".join(repr(r.get("name") or r.get("def_name") or r.get("model")) for r in defaults)
    print(
        f"mazesim: robots {labels} leave their controller field out and run their PROTO's "
        f"default controller, as in Webots: the whole world runs, {_shown(controller)} on robot "
        f"{_shown(key)}",
        file=sys.stderr,
    )
    return argparse.Namespace(
        **{
            **vars(args),
            "controller": world,
            "world": None,
            "robot_controller": [f"{key}={controller_file}"],
        }
    )


def _robot_key(robot: Mapping[str, Any], robots: list[Any], controller: str) -> str | None:
    """What names ``robot`` alone among ``robots`` for ``--robot-controller``: its controller
    field when it names ``controller``, else its name or DEF name if no other robot has it."""
    if robot.get("controller") == controller:
        return controller
    for field in ("name", "def_name"):
        value = robot.get(field)
        others = [r for r in robots if value in (r.get("name"), r.get("def_name"))]
        if value and len(others) == 1 and robot.get("controller") != value:
            return str(value)
    return None


def robot_controllers(pairs: list[str] | None) -> dict[str, str]:
    """The ``--robot-controller NAME=FILE`` arguments as {robot: controller file}.

    Raises:
        InvalidArgumentError: An argument is not NAME=FILE.
    """
    given: dict[str, str] = {}
    for pair in pairs or []:
        name, _, file = pair.partition("=")
        if not name or not file:
            raise InvalidArgumentError(
                f"--robot-controller expects NAME=FILE (a robot's name, DEF name or controller "
                f"field, then a controller file or folder), found {_shown(pair)}"
            )
        given[name] = file
    return given


def run_world_command(args: argparse.Namespace, out: TextIO) -> int:
    """Runs every robot of a ``.wbt`` world and writes the picture and summary of all of them.

    Returns:
        A supervisor's quit status, else the first controller's non-zero exit status, else 0.
    """
    import mazesim
    from mazesim._paths import make_output_folder, open_input, refuse_overwriting_inputs
    from mazesim.plotting import save_robot_paths_png
    from mazesim.replay.views import (
        recording_requested,
        viewing_outputs,
        write_views,
        written_lines,
    )
    from mazesim.webots.keyboard import read_keys
    from mazesim.webots.lockstep import refuse_import_warnings, run_world
    from mazesim.webots.runner import controller_file

    keys = read_keys(args.keys) if getattr(args, "keys", None) else None
    refuse_overwriting_inputs(viewing_outputs(args), [("the Webots world", args.controller)])
    given = {
        name: controller_file(file)
        for name, file in robot_controllers(args.robot_controller).items()
    }
    for file in given.values():
        open_input(file, "the controller").close()  # a regular file, readable, before any run
    if getattr(args, "strict", False):
        refuse_import_warnings(args.controller)
    out_dir = os.path.abspath(args.out)
    make_output_folder(out_dir)
    live = bool(getattr(args, "live", False))
    recorder = (
        WorldWatch(args.seed, recording_requested(args), live)
        if recording_requested(args) or live
        else None
    )
    run = run_world(
        args.controller,
        seconds=args.seconds,
        seed=args.seed,
        noise=not args.no_noise,
        controllers=given,
        observer=recorder,
        keys=keys,
    )
    for robot in run.robots:
        if robot.note:
            print(
                f"mazesim: warning: robot {_shown(robot.name)}: {robot.note}: it stands still",
                file=sys.stderr,
            )
    robots: list[dict[str, Any]] = [
        {
            "name": robot.name,
            "model": robot.model,
            "controller": robot.controller,
            "note": robot.note or None,
            "distance_m": robot.distance_m,
            "collisions": robot.collisions,
            "final_pose": list(robot.final_pose),
            "exit_status": robot.exit_status,
            "controller_error": robot.error.strip().splitlines()[-1] if robot.error else None,
            "reached_end": robot.reached_end,
            "stopped_after_end": robot.stopped,
            "quit_requested": robot.quit_requested,
            "missing_features": list(robot.missing),
            "imported_at_s": robot.imported_s,
            "removed_at_s": robot.removed_s,
            "controller_restarts_s": list(robot.restarts_s),
        }
        for robot in run.robots
    ]
    summary = {
        "world": run.world.name,
        "seed": args.seed,
        "simulated_seconds": run.simulated_seconds,
        "steps": run.steps,
        "robots": robots,
        "missing_features": [
            f"robot {robot.name}: {missing}" for robot in run.robots for missing in robot.missing
        ],
        "exit_status": run.exit_status,
        "interrupted": run.interrupted,
        "import": {key: value for key, value in run.import_summary.items() if key != "sentence"},
        "wall_clock_seconds": run.wall_clock_seconds,
        "mazesim_version": mazesim.__version__,
    }
    picture = os.path.join(out_dir, "trajectory.png")
    save_robot_paths_png(
        run.world,
        [(robot.name, robot.xs, robot.ys) for robot in run.robots],
        picture,
        title=f"{run.world.name}: {len(run.robots)} robots, {run.simulated_seconds:.0f} s, "
        f"seed {args.seed}",
    )
    summary_path = os.path.join(out_dir, "summary.json")
    with atomic_file(summary_path) as handle:
        handle.write((json.dumps(summary, indent=2) + "\n").encode("utf-8"))
    table = os.path.join(out_dir, "trajectory.csv")
    step_s = run.simulated_seconds / run.steps if run.steps else 0.0
    paths = [(robot.name, robot.xs, robot.ys) for robot in run.robots]
    write_paths_table(table, paths, step_s, [robot.imported_s or 0.0 for robot in run.robots])
    out.write(
        f"world              {run.world.name} (seed {args.seed}, {len(run.robots)} robots)\n"
        f"simulated time     {run.simulated_seconds:.2f} s ({run.steps} steps)\n"
    )
    for robot in run.robots:
        ran = os.path.basename(robot.controller) if robot.controller else robot.note
        out.write(
            f"  {robot.name:<16} {ran}: {robot.distance_m:.2f} m, "
            f"{robot.collisions} collisions, exit {robot.exit_status}\n"
        )
    views: list[str] = []
    if recorder is not None and recorder.record and recorder.fleet is not None:
        views = write_views(
            args,
            recorder.fleet.run(f"{run.simulated_seconds:.0f} s"),
            f"{run.world.name}: {len(run.robots)} robots, seed {args.seed}",
        )
    out.write(written_lines(args, picture, [picture, summary_path, table, *views]))
    if run.interrupted:
        print(
            f"mazesim: interrupted at {run.simulated_seconds:.2f} s of simulated time: every "
            "controller was stopped, and what was written covers the run until then",
            file=sys.stderr,
        )
    return run.exit_status
