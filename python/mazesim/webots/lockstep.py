"""Running a Webots world with several robots, as Webots runs it.

Each robot's ``controller`` field names a folder of the project's ``controllers/`` (a Python
controller ``controllers/NAME/NAME.py``), or else one of Webots' stock controllers
(:mod:`mazesim.webots.stock_controllers`; a node that leaves the field out names its PROTO's
default, the E-puck's ``e-puck_avoid_obstacles``); each controller runs in a process of its own
(:mod:`mazesim.webots.controller_process`, forked from one template process that imported
mazesim once: :mod:`mazesim.webots.process_template`), so controllers share no module-level
state, and this process owns the world: every basic time step waits until every running
controller has asked for it (lockstep), transmits the radio's packets
(:mod:`mazesim.webots.radio`), then steps every robot. A robot without a controller (``void``,
``<generic>``, ``<none>``, an empty field), with an ``<extern>`` one not given on the command
line, or with one that is not Python, stands still, as in Webots, whose motor nodes hold
their wheels where the world file puts them until a controller commands them (``WbMotor``'s
first target position is its joint's position, src/webots/nodes/WbMotor.cpp). A robot whose
controller has ended, returned, raised, or died without a word (killed, crashed in native
code), goes on as its motors' last commands have it (:mod:`mazesim.webots.last_commands`).
A controller process that ends without its report is said to, naming its robot, as it really
ended: its exit status (``os._exit``), the signal that killed it (in the words of a crashed C
controller: "killed by SIGSEGV"), or why its link to this process was lost (it closed the
pipe's file descriptor, a process it forked called the API).
A robot that is not an e-puck runs its controller on a body that does not move by
itself and touches no wall. A supervisor sees and moves every robot through the
:class:`Fleet`; its ``simulationQuit`` ends every controller's run (``Robot.step`` returns
-1). So does Ctrl-C: the controllers' processes ignore it, and the world's process ends their
runs (:class:`Interruption`), then says that the run was interrupted (``WorldRun.interrupted``);
a second Ctrl-C stops at once.

The e-pucks share one simulator (:mod:`mazesim.webots.shared_world`): they collide with and
see each other and the world's movable bodies, which they push; an e-puck whose node lists its
own ``DistanceSensor`` nodes reads through their tables (:mod:`mazesim.webots.own_sensors`), as
in a run of one robot. This process also holds each imported E-puck's wheel traction
(:mod:`mazesim.webots.traction`), so that a robot a supervisor puts elsewhere starts again from
rest, whichever process moved it. E-pucks written overlapping share it too, put at their starts
as a supervisor puts one onto another (:mod:`mazesim.webots.shared_world`). A world the shared
simulator refuses (an e-puck in a wall, more robots than a world holds) runs each robot in a
simulator of its own, with a warning: there robots neither collide with nor see each other; the
radio and the supervisor see them all.
"""

from __future__ import annotations

import contextlib
import math
import os
import signal
import sys
import threading
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from multiprocessing.connection import wait
from typing import Any, cast

import numpy as np

from mazesim._core import RobotProfile, Simulator, World
from mazesim._toml import dump_toml, load_toml
from mazesim.errors import (
    ControllerBuildError,
    MazesimIOError,
    WorldFormatError,
    _closest_name,
    _shown,
)
from mazesim.webots.controller_process import (
    ControllerJob,
    answer,
    held_commands,
    state_after_step,
)
from mazesim.webots.keyboard import KeyScript
from mazesim.webots.last_commands import Coasting, WheelCommand
from mazesim.webots.line_of_sight import LineOfSight, robot_body_radii
from mazesim.webots.native_controller import (
    C_SUFFIXES,
    CPP_SUFFIXES,
    EXIT_CRASHED,
    crash_error,
    language_name,
)
from mazesim.webots.own_sensors import own_sensors
from mazesim.webots.process_template import ControllerProcesses
from mazesim.webots.proto_fields import default_controller, robot_label
from mazesim.webots.radio import Radio
from mazesim.webots.requirements import PreparedController, prepare_controller, unbuilt
from mazesim.webots.robots_changed import RemovedRobot, RobotChange, robot_change
from mazesim.webots.runner import (
    CONTROLLER_SUFFIXES,
    EXIT_INTERRUPTED,
    OTHER_LANGUAGES,
    folder_controller,
)
from mazesim.webots.scene import Scene, read_scene, read_scenes, read_world_text
from mazesim.webots.shared_world import (
    RobotView,
    carrying,
    carrying_imported,
    shared_simulator,
    with_robots_of,
)
from mazesim.webots.simulation import WorldReset, robot_profile_name
from mazesim.webots.solids import Pose2, WorldSolids, carried_over
from mazesim.webots.stock_controllers import stock_controller
from mazesim.webots.traction import Traction, epuck_traction
from mazesim.webots.virtual_display import virtual_display, window_environment
from mazesim.webots.walls_now import WallsNow, WorldWalls

__all__ = [
    "Fleet",
    "RobotRun",
    "StepObserver",
    "WorldRun",
    "controller_name",
    "controller_of",
    "refuse_import_warnings",
    "run_world",
]

#: Called before every step with the world, the robots' runs, their simulators and the wheel
#: speeds each steps with, and once after the last step with ``None`` for the wheel speeds
#: (what ``--html``, ``--video`` and ``--record`` record).
StepObserver = Callable[
    [World, "list[RobotRun]", "list[Any]", "Mapping[int, tuple[float, float]] | None"], None
]

#: ``controller`` fields that name no controller: the robot stands still.
NO_CONTROLLER = {"", "void", "<generic>", "<none>"}
#: The controller field of a robot whose controller is started outside the simulation.
EXTERN = "<extern>"
#: Real seconds a controller process may take to exit after its run ended, before it is killed.
EXIT_WAIT_SECONDS = 5.0
#: Real seconds between two looks at whether Ctrl-C was pressed while no controller speaks.
_POLL_SECONDS = 0.2


@dataclass
class RobotRun:
    """What one robot did in a run of a world.

    Attributes:
        index: Its index among the world's robots (file order).
        name: Its ``name`` field, else its PROTO's default (an E-puck's "e-puck"; the DEF
            name of one of several robots that would share it), else its DEF name or model.
        model: Its model as found (``E-puck``, ``e-puck2``, ``Robot``...).
        controller: The controller file that ran, or None.
        note: Why no controller ran, or "".
        xs: Its x after each step, the start first.
        ys: Its y after each step, the start first.
        distance_m: Distance it travelled.
        collisions: Contacts with walls that began during the run.
        final_pose: x, y, yaw at the end.
        exit_status: Its controller's exit status (0 without a controller).
        error: Its controller's traceback, or "".
        reached_end: Whether its ``Robot.step`` returned -1.
        stopped: Whether its controller went on after the end and was stopped.
        quit_requested: Whether it (a supervisor) quit the simulation.
        missing: What its controller needs that mazesim lacks (said at the run's start).
        imported_s: When a supervisor imported it (s), or None for a robot of the world file;
            its path starts there.
        removed_s: When a supervisor removed it (s), or None; its path ends there.
        restarts_s: When a supervisor restarted its controller (s), each time; what the
            run's other attributes say of the controller is the last process's.
    """

    index: int
    name: str
    model: str
    controller: str | None
    note: str = ""
    xs: list[float] = field(default_factory=list, repr=False)
    ys: list[float] = field(default_factory=list, repr=False)
    distance_m: float = 0.0
    collisions: int = 0
    final_pose: tuple[float, float, float] = (0.0, 0.0, 0.0)
    exit_status: int = 0
    error: str = field(default="", repr=False)
    reached_end: bool = False
    stopped: bool = False
    quit_requested: bool = False
    missing: tuple[str, ...] = ()
    imported_s: float | None = None
    removed_s: float | None = None
    restarts_s: list[float] = field(default_factory=list)


@dataclass
class WorldRun:
    """What a run of a world did: its robots' runs, the simulated time and the real time, and
    whether Ctrl-C ended it (every controller's run then ended where the world was)."""

    world: World
    robots: list[RobotRun]
    steps: int
    simulated_seconds: float
    wall_clock_seconds: float
    interrupted: bool = False
    #: The import's summary (:func:`~mazesim.webots.importer.import_summary`) as printed.
    import_summary: dict[str, Any] = field(default_factory=dict)

    @property
    def exit_status(self) -> int:
        """130 when interrupted, else a supervisor's quit status, else the first non-zero exit
        status, else 0."""
        if self.interrupted:
            return EXIT_INTERRUPTED
        for robot in self.robots:
            if robot.quit_requested:
                return robot.exit_status
        return next((r.exit_status for r in self.robots if r.exit_status), 0)


#: A gap between two robots' bodies below this (m) counts as their contact, as the core counts
#: it (``ROBOT_CONTACT_GAP`` of ``mazesim_core::simulator``).
ROBOT_CONTACT_GAP = 2e-4


class Fleet:
    """The world's robots as a supervisor sees them (answered over the controllers' pipes), and
    the world's radio and last reset, which every robot's controller is told of."""

    def __init__(
        self,
        robots: list[Mapping[str, Any]],
        simulators: list[Any],
        report: Mapping[str, Any] | None = None,
        *,
        seed: int = 0,
        noise: bool = True,
    ) -> None:
        self._robots = robots
        self._simulators = simulators
        #: The run's noise seed and switch, which the first e-pucks a supervisor imports into a
        #: world without any are simulated with (:mod:`mazesim.webots.robots_changed`).
        self._seed = seed
        self._noise = noise
        #: The world file's import report, and the file (its ``path``), which a supervisor's
        #: changes edit.
        self.report: Mapping[str, Any] = report or {}
        self._path = str(self.report.get("path") or "")
        self.moved: set[int] = set()
        self._radii: list[float | None] = []
        #: The robots a supervisor removed (:mod:`mazesim.webots.robots_changed`).
        self.gone: set[int] = set()
        #: The world's walls and movable bodies (``report``: the world's import report).
        self.solids = WorldSolids(self._worlds(), report or {})
        self.radio = Radio()
        self._resets: list[WorldReset] = [WorldReset() for _ in simulators]
        #: Whether a supervisor asked for a reset, which the world applies at the step's end.
        self.reset_asked = False
        #: Whether a supervisor asked for the world to be reloaded (:meth:`reload_world`),
        #: which the world does before its next step.
        self.reload_asked = False
        #: Each robot's ``controller`` field as the world file gives it, which a reload
        #: brings back.
        self._file_controllers = [robot.get("controller") for robot in robots]
        #: The robots imported, and removed, since the run last took note (their controllers
        #: start, and end).
        self.joined: list[int] = []
        self.left: list[int] = []
        #: The robots whose controllers a supervisor asked to restart since the run last took
        #: note (each one's process ends and a new one starts).
        self.restarts: list[int] = []
        #: The robots whose ``controller`` field a supervisor wrote: from then on the field
        #: names the controller (:func:`controller_of`'s ``by_field``).
        self.fields_written: set[int] = set()
        #: The running world's description as a supervisor last changed it, which the
        #: controllers of the robots it imports read, and the world file's number of lines
        #: (the imported nodes' come after them).
        self.text: str | None = None
        self._file_lines = 0
        #: How many times a supervisor has changed the walls (moved, imported or removed a
        #: node, reset the world), which every robot is told of with each step's answer, and
        #: the world as drawn after the last change (:meth:`world_now`).
        self.wall_changes = 0
        self._drawn: tuple[int, World] | None = None
        #: The ``customData`` a supervisor last wrote into each robot's node, numbered in the
        #: order written, which the robot reads after the world's next step.
        self._custom_data: dict[int, tuple[int, str]] = {}
        self._fields: dict[int, str] = {}
        #: The world's clock and the robots' poses before its last step (:meth:`velocity`).
        self._before: tuple[float, dict[int, tuple[float, float, float]]] = (0.0, {})
        if self._path:
            self._file_lines = read_world_text(self._path).count("\n") + 1

    def robots(self) -> list[dict[str, Any]]:
        """Each robot's index, ``def_name``, ``name``, ``model`` and ``line`` (a removed robot's
        are not listed; an imported one's are, after the running ones)."""
        keys = ("def_name", "name", "model", "line")
        return [
            {"index": i, **{k: r.get(k) for k in keys}}
            for i, r in enumerate(self._robots)
            if i not in self.gone
        ]

    def body_radii(self) -> list[float | None]:
        """The body radius of each robot simulated as one, by index, those a supervisor
        imported included (None: a robot whose collision shapes are walls)."""
        if len(self._radii) != len(self._robots):
            self._radii = robot_body_radii({"robots": self._robots})
        return self._radii

    def robots_of(self, indices: list[int]) -> list[Mapping[str, Any]]:
        """The import report entries of robots ``indices``."""
        return [self._robots[index] for index in indices]

    def clock(self) -> float:
        """The world's clock now (s)."""
        return float(next(s for i, s in enumerate(self._simulators) if i not in self.gone).time)

    def pose(self, index: int) -> tuple[float, float, float]:
        """A robot's x, y, yaw now."""
        x, y, yaw = self._simulators[index].pose
        return float(x), float(y), float(yaw)

    def note_poses(self) -> None:
        """Notes every robot's pose before the world's step (or at rest, after a reset), which
        :meth:`velocity` measures the step's motion from."""
        self._before = (self.clock(), {i: self.pose(i) for i in self._here()})

    def velocity(self, index: int) -> tuple[float, float, float]:
        """A robot's world-frame velocity over the world's last step: vx, vy (m/s) and turn
        rate (rad/s), as its own controller measures it (0 before its first step and after a
        supervisor put it somewhere)."""
        clock, poses = self._before
        dt = self.clock() - clock
        if index not in poses or not dt > 0.0:
            return 0.0, 0.0, 0.0
        (x0, y0, yaw0), (x, y, yaw) = poses[index], self.pose(index)
        return (x - x0) / dt, (y - y0) / dt, math.remainder(yaw - yaw0, math.tau) / dt

    def _here(self) -> list[int]:
        """The robots in the world now (those a supervisor removed left out)."""
        return [i for i in range(len(self._simulators)) if i not in self.gone]

    def poses(self) -> list[tuple[float, float, float] | None]:
        """Every robot's x, y, yaw now, in the world's order, None for one a supervisor
        removed (one answer for a camera that recognises robots)."""
        return [
            None if index in self.gone else self.pose(index)
            for index in range(len(self._simulators))
        ]

    def contact_points(self, index: int) -> list[list[float]]:
        """Where robot ``index`` touches something now (x, y, 0 on the floor, m): for each
        other robot it touches, the point where their bodies meet; for a wall it touches, its
        own centre. Empty while it touches nothing, or once a supervisor removed it."""
        if index in self.gone or not self._simulators[index].colliding:
            return []
        radii = self.body_radii()
        x, y, _ = self.pose(index)
        own = radii[index] or 0.0
        points = []
        for other in self._here():
            radius = radii[other]
            if other == index or radius is None:
                continue
            ox, oy, _ = self.pose(other)
            apart = math.hypot(ox - x, oy - y)
            if 0.0 < apart <= own + radius + ROBOT_CONTACT_GAP:
                share = own / apart
                points.append([x + (ox - x) * share, y + (oy - y) * share, 0.0])
        return points or [[x, y, 0.0]]

    def move(self, index: int, x: float, y: float, yaw: float) -> None:
        """Puts a robot at a new pose, at rest."""
        self._simulators[index].set_pose_pushed_out(x, y, yaw)
        self.moved.add(index)
        self._before[1].pop(index, None)

    def restart_controller(self, index: int) -> bool:
        """Asks for robot ``index``'s controller to be restarted (as Webots'
        ``wb_supervisor_node_restart_controller``); False for a robot removed."""
        if index in self.gone or not 0 <= index < len(self._simulators):
            return False
        if index not in self.restarts:
            self.restarts.append(index)
        return True

    def reload_world(self) -> None:
        """Notes a supervisor's ``worldReload``: before the next step the world is put back as
        its file has it (:meth:`reset_scene`, the supervisor's ``controller`` and
        ``customData`` writes undone) and every robot's controller, the caller's too, ends
        (its ``Robot.step`` returns -1) and starts again on a clock back at 0, as Webots
        reloads the world file and restarts every controller process."""
        self.reload_asked = True

    def reload_scene(self) -> list[int]:
        """Does the reload :meth:`reload_world` asked for; returns the robots whose controllers
        start again (every robot present after the reset)."""
        self.reload_asked = False
        self.reset_scene()
        for index, controller in enumerate(self._file_controllers):
            if index not in self.gone and controller is not None:
                self._robots[index] = {**self._robots[index], "controller": controller}
        self._custom_data.clear()
        self._fields.clear()
        here = [i for i in range(len(self._simulators)) if i not in self.gone]
        self.restarts = here
        return here

    def change_controller(self, index: int, name: str) -> bool:
        """Gives robot ``index`` the controller ``name``, as a supervisor's write of its node's
        ``controller`` field does in Webots: its controller is restarted as that one
        (:meth:`restart_controller`); False for a robot removed."""
        if index in self.gone or not 0 <= index < len(self._robots):
            return False
        self._robots[index] = {**self._robots[index], "controller": str(name)}
        self.fields_written.add(index)
        return self.restart_controller(index)

    def set_custom_data(self, index: int, text: str) -> None:
        """Notes a supervisor's write of a robot's ``customData`` field, which the robot's
        controller reads after the world's next step (:meth:`custom_data`)."""
        number = max((n for n, _ in self._custom_data.values()), default=0) + 1
        self._custom_data[index] = (number, str(text))
        self._fields[index] = str(text)

    def note_own_custom_data(self, index: int, text: str) -> None:
        """Notes robot ``index``'s own ``setCustomData``, sent with the step the world now
        takes: its node's field holds it from then on (:meth:`custom_data_field`)."""
        self._fields[index] = text

    def custom_data_field(self, index: int) -> str | None:
        """Robot ``index``'s node's ``customData`` field as the last write left it, by the
        robot itself or by a supervisor, or None when there was none."""
        return self._fields.get(index)

    def custom_data(self, index: int) -> tuple[int, str] | None:
        """The ``customData`` a supervisor last wrote into robot ``index``'s node and the
        number of that write (a robot's own ``setCustomData`` stands until a later one), or
        None when none did."""
        return self._custom_data.get(index)

    def _worlds(self) -> list[Any]:
        """The simulators that each hold the world's walls and movable bodies: the e-pucks'
        shared one first, then those of e-pucks that run in simulators of their own (another
        robot's holds neither); all of them in a world without e-pucks."""
        shared = [s.simulator for s in self._simulators if isinstance(s, RobotView)][:1]
        here = [
            (s, robot)
            for index, (s, robot) in enumerate(zip(self._simulators, self._robots))
            if index not in self.gone and not isinstance(s, RobotView)
        ]
        own = [s for s, robot in here if robot.get("profile") is not None]
        return shared + own or [s for s, _ in here]

    def world_now(self, start: World) -> World:
        """The world as it runs now, for what draws the whole world (the ``--live`` window):
        ``start`` until a supervisor changes the walls, then the world of a simulator that holds
        them (the e-pucks'), moved, imported and removed walls and all."""
        if self.wall_changes == 0:
            return start
        if self._drawn is None or self._drawn[0] != self.wall_changes:
            e_pucks = any(
                robot.get("profile") is not None
                for index, robot in enumerate(self._robots)
                if index not in self.gone
            )
            # Without e-pucks no simulator holds the walls (a robot that is no e-puck's has
            # none): the window keeps the start's.
            world = self._worlds()[0].world if e_pucks else start
            self._drawn = (self.wall_changes, world)
        return self._drawn[1]

    def body_poses(self) -> list[tuple[float, float, float]]:
        """The movable bodies' poses (x, y, yaw) now, in world order."""
        return self.solids.body_poses()

    def body_velocities(self) -> list[tuple[float, float, float]]:
        """The movable bodies' velocities (vx, vy, turn rate) now, in world order."""
        return self.solids.body_velocities()

    def drawn_bodies(self) -> list[tuple[Pose2, Mapping[str, Any]]]:
        """The movable bodies as a camera draws them now (see
        :meth:`~mazesim.webots.solids.WorldSolids.drawn_bodies`)."""
        return self.solids.drawn_bodies()

    def set_body_velocity(self, index: int, vx: float, vy: float, turn_rate: float) -> None:
        """Sets a movable body's velocity in every simulator that holds the world's bodies."""
        self.solids.set_body_velocity(index, vx, vy, turn_rate)

    def request_reset(self) -> None:
        """Notes a supervisor's ``simulationReset``: the world applies it at the end of the
        next step (:meth:`reset_scene`), as Webots does."""
        self.reset_asked = True

    def reset_scene(self) -> None:
        """Puts every robot at its start and the walls and movable bodies where the world file
        has them, all at rest, the noise streams started again (a supervisor's
        ``simulationReset``), in every simulator; drops the radio's packets and restarts every
        robot's clock and wheel sensors; each robot learns of it with the step's answer."""
        self.reset_asked = False
        if self.text is not None:  # Webots' reset takes a supervisor's imports out
            kept = self.text.split("\n")[: self._file_lines]
            self.change_world("\n".join(kept + [""] * (self.text.count("\n") + 1 - len(kept))))
        self.solids.forget_moves()
        self.wall_changes += 1
        done: set[int] = set()
        here = [s for i, s in enumerate(self._simulators) if i not in self.gone]
        for simulator in here:
            whole = simulator.simulator if isinstance(simulator, RobotView) else simulator
            if id(whole) not in done:
                done.add(id(whole))
                whole.reset_scene()
        self.moved.update(range(len(self._simulators)))
        self.radio.clear()
        count, now = self._resets[0].count + 1, float(here[0].time)
        for robot, simulator in enumerate(self._simulators):
            left, right = (float(v) for v in simulator.wheel_turns)
            self._resets[robot] = WorldReset(count, now, (left, right))

    def last_reset(self, index: int) -> WorldReset:
        """The world's last reset as robot ``index`` counts from it."""
        return self._resets[index]

    def node_moves(self) -> dict[int, tuple[Pose2, Pose2]]:
        """The nodes a supervisor moved since the start or the last reset (see
        :meth:`~mazesim.webots.solids.WorldSolids.node_moves`)."""
        return self.solids.node_moves()

    def edit_light(self, line: int, name: str, value: Any) -> None:
        """Notes a supervisor's edit of a light's field (see
        :meth:`~mazesim.webots.solids.WorldSolids.edit_light`); each robot is told with the
        next step's answer (``light_changes``) and asks for the edits then."""
        self.solids.edit_light(line, name, value)

    def light_edits(self) -> dict[int, dict[str, Any]]:
        """The fields supervisors set on light nodes, by the line of each light's node."""
        return self.solids.light_edits()

    def move_node(self, line: int, from_pose: Any, to_pose: Any) -> None:
        """Moves what the node on ``line`` holds, in every simulator that holds the world's
        walls and bodies (see :meth:`~mazesim.webots.solids.WorldSolids.move_node`)."""
        walls = self.solids.node_moves()
        self.solids.move_node(line, from_pose, to_pose)
        if self.solids.node_moves() != walls:  # a node holding bodies alone moves no wall
            self.wall_changes += 1

    def change_world(self, text: str) -> None:
        """Runs on in the world of ``text`` (the world file as a supervisor changed it: see
        :mod:`mazesim.webots.scene_edits`) in every simulator that holds the world's walls and
        bodies, each imported as its own was.

        Robots imported and removed join and leave the run as
        :mod:`mazesim.webots.robots_changed` has them.

        Raises:
            MazesimError: The text is no world the importer reads, or it imports a robot
                mazesim does not add; nothing changed.
        """
        from mazesim.webots.importer import import_wbt_text

        world, report = import_wbt_text(text, self._path)
        # The e-pucks a supervisor imports carry their shapes, as the world file's do.
        running = {int(r["line"]) for i, r in enumerate(self._robots) if i not in self.gone}
        with_shapes = carrying_imported(report.get("robots") or [], text, running)
        report["robots"] = cast(Any, with_shapes)
        change = robot_change(self._robots, self._simulators, self.gone, report, world)
        shared = {id(s.simulator) for s in self._simulators if isinstance(s, RobotView)}
        own = {
            id(simulator): robot
            for simulator, robot in zip(self._simulators, self._robots)
            if not isinstance(simulator, RobotView)
        }
        leaving = {id(self._simulators[i]) for i in (change.removed if change else [])}
        simulators = [s for s in self._worlds() if id(s) not in leaving]
        worlds = []
        for simulator in simulators:
            if id(simulator) in shared:
                worlds.append(change.world if change else with_robots_of(world, simulator.world))
                continue
            robot = own[id(simulator)]
            changed, _ = import_wbt_text(text, self._path, robot_line=int(robot["line"]))
            worlds.append(changed if robot.get("profile") else _without_walls(changed))
        kept = change.kept if change and change.world is not None else None
        profiles = _imported_profiles(change, text) if change and kept is not None else None
        opened = None
        if change is not None and change.opens and change.world is not None:
            opened = self._opened(change.world, len(change.added), profiles)
            simulators, worlds = [opened, *simulators], [change.world, *worlds]
            kept = profiles = None
        # What the removed robots were, read before their simulator changes.
        removed = {i: RemovedRobot(self._simulators[i]) for i in (change.removed if change else [])}
        self.solids = carried_over(
            self.solids, simulators, worlds, report, kept_robots=kept, robot_profiles=profiles
        )
        self.text = text
        self.wall_changes += 1
        if change is not None:
            self._take(change, removed, opened)

    def _opened(
        self, world: World, count: int, profiles: list[RobotProfile | None] | None
    ) -> Simulator:
        """The e-pucks' shared simulator of ``world``, whose ``count`` robots a supervisor
        imported as the world's first e-pucks, at rest on the running clock."""
        if profiles:
            opened = Simulator(world, seed=self._seed, noise=self._noise, robot_profiles=profiles)
        else:
            opened = Simulator(world, seed=self._seed, noise=self._noise)
        steps = round(self.clock() * 1000.0 / float(opened.control_step_ms))
        at_rest = np.zeros((count, 2), dtype=np.float64)
        for _ in range(steps):
            opened.step_robots(at_rest)
        return opened

    def _take(
        self,
        change: RobotChange,
        removed: dict[int, RemovedRobot],
        opened: Simulator | None = None,
    ) -> None:
        """Takes the robots' change: the ``removed`` ones leave, the imported ones join (into
        ``opened`` when they are the world's first e-pucks)."""
        for index, stand_in in removed.items():
            self._simulators[index] = stand_in
            self.gone.add(index)
            self.left.append(index)
        last = self._resets[0]
        for entry in change.added:
            self.joined.append(len(self._robots))
            self._robots.append(entry)
            self._simulators.append(None)
            self._resets.append(WorldReset(last.count, last.time, (0.0, 0.0)))
        shared = opened or next(s.simulator for s in self._simulators if isinstance(s, RobotView))
        for place, index in enumerate(change.order):
            self._simulators[index] = RobotView(shared, place)


def _say_unmatched(
    given: Mapping[str, str], robots: list[Mapping[str, Any]], world_path: str
) -> None:
    """Warns of a controller given for a robot that no robot of the world is: none has that
    name (as Webots calls it, its default too), DEF name or controller field. It was left
    unused without a word, and the robot meant ran the world's controller or stood still. It
    still applies to a robot a supervisor imports by that name."""
    known = [
        {robot_label(r), r.get("name"), r.get("def_name"), r.get("controller")} for r in robots
    ]
    for key in given:
        if not any(key in keys for keys in known):
            listed = "; ".join(
                f"{_shown(robot_label(r))} (DEF {r.get('def_name') or '-'}, controller "
                f"{_shown(r.get('controller'))})"
                for r in robots[:20]
            )
            print(
                f"mazesim: warning: a controller was given for robot {_shown(key)}, but no "
                f"robot of {_shown(os.path.basename(world_path))} has that name, DEF name or "
                f"controller field (it applies to a robot a supervisor imports so): expected "
                f"one of its {len(robots)} robots: {listed}",
                file=sys.stderr,
            )


def controller_of(
    robot: Mapping[str, Any], world_path: str, given: Mapping[str, str], by_field: bool = False
) -> tuple[str | None, str]:
    """The controller file a robot runs, or None and why not; with a file, a note when it
    was found where Webots would not look (beside the world file), else "".

    Args:
        robot: The robot's entry of the import report's ``robots``.
        world_path: The world file; controllers are looked for in ``../controllers/`` of its
            folder (Webots' project layout), then beside it.
        given: Controller files given on the command line, by robot name, DEF name or
            controller field.
        by_field: Whether a supervisor wrote the robot's ``controller`` field: Webots then
            starts the controller the field names, so a file given by the robot's name or DEF
            name no longer applies (one given by the new field's value does, and so does one
            given by name when the field now reads ``<extern>``, the controller Webots leaves
            to be started outside).
    """
    keys = [robot.get("name"), robot_label(robot), robot.get("def_name"), robot.get("controller")]
    if by_field and robot.get("controller") != EXTERN:
        keys = keys[3:]
    for key in keys:
        if key and key in given:
            return os.path.abspath(given[key]), ""
    name = controller_name(robot)
    if name in NO_CONTROLLER:
        return None, "no controller"
    if name == EXTERN:
        return None, (
            f"an <extern> controller: give it with --robot-controller {robot_label(robot)}=FILE"
        )
    folder = os.path.dirname(os.path.abspath(world_path))
    for project in (os.path.dirname(folder), folder):
        candidate = folder_controller(os.path.join(project, "controllers", name))
        if candidate is not None:
            return candidate, "" if project != folder else _BESIDE_THE_WORLD.format(name)
    stock = stock_controller(name)
    if stock is not None:  # Webots' own, which it finds among its projects
        return stock, ""
    return None, _other_language(name, world_path) or (
        f"no controller controllers/{name}/{name}{', '.join(CONTROLLER_SUFFIXES)}"
        + _controller_meant(name, world_path)
    )


#: The note of a controller found in ``controllers/`` beside the world file, where mazesim looks
#: too and Webots does not (``WbProject::projectPathFromWorldFile``: the project is the folder
#: above the world's).
_BESIDE_THE_WORLD = (
    "its controller {} was found in controllers/ beside the world file; Webots looks for it only "
    "in the project's controllers/, in the folder above the world's, and would not start it"
)


def _controller_meant(name: str, world_path: str) -> str:
    """ "; did you mean 'NAME'?" naming the project's controller folder closest to ``name`` (a
    typo in a world's ``controller`` field), or ""."""
    folder = os.path.dirname(os.path.abspath(world_path))
    names = []
    for project in (os.path.dirname(folder), folder):
        with contextlib.suppress(OSError):
            controllers = os.path.join(project, "controllers")
            names += [n for n in sorted(os.listdir(controllers))[:1000] if n != name]
    meant = _closest_name(name, names)
    return f" (did you mean {_shown(meant)}?)" if meant else ""


def _other_language(name: str, world_path: str) -> str:
    """Why the controller ``name`` of a world does not run: "a LANGUAGE controller
    controllers/NAME/NAME.SUFFIX, which mazesim does not run" when its folder (in the project
    of ``world_path``) holds one in a language mazesim does not run (:data:`OTHER_LANGUAGES`:
    Java, MATLAB), else ""."""
    folder = os.path.dirname(os.path.abspath(world_path))
    for project in (os.path.dirname(folder), folder):
        for suffix, language in OTHER_LANGUAGES.items():
            if os.path.isfile(os.path.join(project, "controllers", name, f"{name}{suffix}")):
                return (
                    f"a {language} controller controllers/{name}/{name}{suffix}, which mazesim "
                    "does not run"
                )
    return ""


def controller_name(robot: Mapping[str, Any]) -> str:
    """The controller a robot's node names: its ``controller`` field, or where the world file
    leaves the field out, its default (:func:`~mazesim.webots.proto_fields.default_controller`);
    "" for none."""
    name = robot.get("controller")
    return default_controller(robot) if name is None else str(name)


def run_world(
    world_path: str,
    *,
    seconds: float = 60.0,
    seed: int = 0,
    noise: bool = True,
    controllers: Mapping[str, str] | None = None,
    observer: StepObserver | None = None,
    keys: KeyScript | None = None,
) -> WorldRun:
    """Runs every robot of a ``.wbt`` world with its own controller, in lockstep.

    It starts as a run of one controller does, with one line on stderr summing up the import,
    then each thing not imported as in Webots (all the import's warnings but those about the
    world's other e-pucks, which this run simulates), each prefixed ``mazesim: warning:``.

    Args:
        world_path: The world file.
        seconds: Simulated seconds after which every ``Robot.step`` returns -1.
        seed: Seed of the sensor noise (each robot gets a stream of its own).
        noise: Whether the sensors are noisy.
        controllers: Controller files for some robots, by robot name, DEF name or controller
            field (they win over the world's ``controller`` fields, until a supervisor writes
            that robot's field: :func:`controller_of`).
        observer: Called before every step and after the last (:data:`StepObserver`).
        keys: The keyboard script, played on every controller's ``Keyboard`` (a controller
            that enables its keyboard reads it, one that does not is untouched), as Webots
            sends the keys typed with no robot selected to every robot; None: no key.

    Returns:
        What each robot did.

    Raises:
        MazesimIOError: The world has no robot.
    """
    world, report, summary = _imported(world_path)
    robots: list[Mapping[str, Any]] = list(report.get("robots") or [])
    _say_unmatched(controllers or {}, robots, world_path)
    _say_import(summary)
    streams = np.random.SeedSequence(seed).spawn(len(robots))
    e_pucks = [i for i, robot in enumerate(robots) if robot.get("profile") is not None]
    scenes = _robot_scenes(world_path, robots)
    own = _own_profiles(robots, scenes)
    placed = carrying(robots, scenes)
    shared, refusal = shared_simulator(world, placed, e_pucks, seed=seed, noise=noise, profiles=own)
    if refusal and e_pucks:
        print(
            f"mazesim: warning: the e-pucks run in simulators of their own, without seeing or "
            f"touching each other: {refusal}",
            file=sys.stderr,
        )
    simulators: list[Any] = []
    runs, jobs = [], {}
    for index, robot in enumerate(robots):
        profile = robot_profile_name({"robot_profile": robot.get("profile")})
        if shared is not None and index in e_pucks:
            simulators.append(RobotView(shared, e_pucks.index(index)))
        else:
            robot_seed = int(streams[index].generate_state(1)[0])
            simulators.append(
                _own_simulator(world_path, robot, own.get(index, profile), robot_seed, noise)
            )
        run, job = _robot_run(world_path, index, robot, controllers or {}, seconds, noise, keys)
        runs.append(run)
        if job is not None:
            jobs[index] = job
    _tell_apart(runs, robots)
    drawn, environment, prepared = _say_what_is_missing(runs)
    # Each controller process runs its controller as prepared here (its display, if it needs
    # one, is this process's), rather than preparing it again.
    jobs = {
        index: replace(job, prepared=replace(prepared[job.controller], virtual_display=False))
        for index, job in jobs.items()
    }
    fleet = Fleet(
        robots, simulators, dict(report, path=os.path.abspath(world_path)), seed=seed, noise=noise
    )

    def joined(index: int, restart: bool = False) -> tuple[RobotRun, ControllerJob | None]:
        """The run and controller job of robot ``index``, which a supervisor imported or whose
        controller it restarted: its controller has what is left of the run's ``seconds`` of
        world time, as Webots' one simulation clock ends every robot's run together. A
        restarted controller's robot keeps its body and wheels as they are."""
        imported_s = float(simulators[index].time)
        left = max(seconds - imported_s, 1e-9)
        by_field = index in fleet.fields_written
        run, job = _robot_run(
            world_path, index, robots[index], controllers or {}, left, noise, keys, by_field
        )
        run.imported_s = imported_s
        robot, text = robots[index], fleet.text or ""  # the world as the import changed it
        if not restart:
            scene = read_scene(text, robot.get("model"), robot["line"], robot.get("y_up"))
            traction.join(index, robot, scene)
        if job is None:
            return run, None
        _, _, ready = _say_what_is_missing([run])
        done = replace(ready[job.controller], virtual_display=False)
        written = fleet.custom_data_field(index)
        return run, replace(job, prepared=done, world_text=fleet.text, custom_data=written)

    # The walls (where a supervisor moved, imported or removed them), the robots' bodies and
    # the movable bodies stop infra-red packets.
    walls_now = WallsNow(WorldWalls(fleet, world, fleet.report))
    fleet.radio.sight = LineOfSight(walls_now.walls, fleet.body_radii, report, fleet)
    traction = WorldTraction(scenes, robots, simulators)
    movable = [robot.get("profile") is not None for robot in robots]
    started = time.perf_counter()
    watch = (
        None if observer is None else lambda *state: observer(fleet.world_now(world), runs, *state)
    )
    # The controllers' processes inherit the display their windows need.
    with contextlib.ExitStack() as display:
        if drawn:
            display.enter_context(virtual_display())
        display.enter_context(window_environment(environment))
        steps, interrupted = _lockstep(
            jobs, simulators, movable, fleet, runs, traction, watch, joined
        )
        if not jobs and not interrupted:
            steps, interrupted = _unattended(simulators, fleet, runs, traction, watch, seconds)
    if watch is not None:
        watch(simulators, None)
    for run, simulator in zip(runs, simulators):
        run.distance_m = float(simulator.distance_travelled)
        run.collisions = int(simulator.collisions)
        run.final_pose = tuple(float(v) for v in simulator.pose)  # type: ignore[assignment]
    here = [s for i, s in enumerate(simulators) if i not in fleet.gone]
    return WorldRun(
        world=world,
        robots=runs,
        steps=steps,
        simulated_seconds=float(here[0].time),
        wall_clock_seconds=time.perf_counter() - started,
        interrupted=interrupted,
        import_summary=summary,
    )


def _tell_apart(runs: list[RobotRun], robots: Sequence[Mapping[str, Any]]) -> None:
    """Names apart the robots that share a name only by their PROTO's default (several E-pucks
    without a ``name`` field, all "e-puck" in Webots): by their DEF name, else their index, so
    that the summary and the trajectory tell them apart."""
    counts: dict[str, int] = {}
    for run in runs:
        counts[run.name] = counts.get(run.name, 0) + 1
    for run, robot in zip(runs, robots):
        if counts[run.name] > 1 and not robot.get("name"):
            run.name = str(robot.get("def_name") or f"{run.name}({run.index})")


def _robot_run(
    world_path: str,
    index: int,
    robot: Mapping[str, Any],
    given: Mapping[str, str],
    seconds: float,
    noise: bool,
    keys: KeyScript | None = None,
    by_field: bool = False,
) -> tuple[RobotRun, ControllerJob | None]:
    """Robot ``index``'s run, and the job of its controller process (None without one);
    ``by_field``: a supervisor wrote its ``controller`` field (:func:`controller_of`)."""
    profile = robot_profile_name({"robot_profile": robot.get("profile")})
    file, note = controller_of(robot, world_path, given, by_field)
    label = robot_label(robot)
    if file is not None and note:  # found where Webots would not look
        print(f"mazesim: warning: robot {_shown(label)}: {note}", file=sys.stderr)
        note = ""
    run = RobotRun(index, str(label), str(robot.get("model")), file, note)
    if file is None:
        # A controller in a language mazesim does not run is what the run lacks, said in its
        # summary's missing features as a Python package not installed is.
        if note == _other_language(controller_name(robot), world_path):
            run.missing = (note,)
        return run, None
    job = ControllerJob(
        world_path, index, int(robot["line"]), file, profile, seconds, noise, keys=keys
    )
    return run, job


def _imported(world_path: str) -> tuple[World, dict[str, Any], dict[str, Any]]:
    """The world of a world run, its import report and the summary of what it lost.

    Raises:
        MazesimIOError: The world has no robot.
    """
    from mazesim.webots.importer import import_summary, import_wbt, world_run_warnings

    world, report = import_wbt(world_path)
    robots = list(report.get("robots") or [])
    if not robots:
        raise MazesimIOError(f"{world_path}: expected a world with robots, found none")
    lost = world_run_warnings(report)
    return world, dict(report), import_summary(world_path, report, lost, robots=len(robots))


def _say_import(summary: Mapping[str, Any]) -> None:
    """Prints the import's summary line and each thing not imported, as a run starts."""
    print(f"mazesim: {summary['sentence']}", file=sys.stderr)
    for warning in summary["not_imported"]:
        print(f"mazesim: warning: {warning}", file=sys.stderr)


def refuse_import_warnings(world_path: str) -> None:
    """What ``--strict`` checks before a world run: that the world imports without a warning
    a run of the whole world shares; else prints the import as a run would and raises.

    Raises:
        MazesimIOError: The world has no robot.
        WorldFormatError: The import has warnings.
    """
    _, _, summary = _imported(world_path)
    if summary["not_imported"]:
        _say_import(summary)
        raise WorldFormatError(
            f"{world_path}: --strict expects a world imported without warnings, found "
            f"{len(summary['not_imported'])} (listed above)",
            source=world_path,
        )


def _robot_scenes(world_path: str, robots: list[Mapping[str, Any]]) -> list[Scene]:
    """What the world file says of each robot's node (:func:`~mazesim.webots.scene.read_scenes`
    of the node on its line)."""
    return read_scenes(
        read_world_text(world_path),
        [(robot.get("model"), robot.get("line")) for robot in robots],
        [robot.get("y_up") for robot in robots],
    )


def _own_profiles(
    robots: Sequence[Mapping[str, Any]], scenes: Sequence[Scene]
) -> dict[int, RobotProfile]:
    """The profile of each e-puck whose node lists its own sensors other than its built-in
    profile's (:func:`~mazesim.webots.own_sensors.own_sensors`), by robot index; says at the
    run's start, robot by robot, what of a node's sensors is not used."""
    profiles: dict[int, RobotProfile] = {}
    for index, (robot, scene) in enumerate(zip(robots, scenes)):
        if robot.get("profile") is None:
            continue
        own = own_sensors(robot_profile_name({"robot_profile": robot.get("profile")}), scene)
        label = robot_label(robot)
        for warning in own.warnings:
            print(f"mazesim: warning: robot {_shown(label)}: {warning}", file=sys.stderr)
        if own.profile is not None:
            profiles[index] = own.profile
    return profiles


def _imported_profiles(change: RobotChange, text: str) -> list[RobotProfile | None] | None:
    """The profile of each robot of a changed world (``change.kept``'s order) that its node's
    own sensors make (:func:`_own_profiles`, as for a robot of the world file), None for a kept
    robot or one of its built-in profile; None when no imported robot has one."""
    scenes = read_scenes(text, [(robot.get("model"), robot.get("line")) for robot in change.added])
    own = _own_profiles(change.added, scenes)
    if not own:
        return None
    new = iter(range(len(change.added)))
    return [own.get(next(new)) if index is None else None for index in change.kept]


#: The tables of a world file that a robot's body meets: walls and movable bodies.
_SOLID_TABLES = ("walls", "segments", "bodies")


def _own_simulator(
    world_path: str | os.PathLike[str],
    robot: Mapping[str, Any],
    profile: str | RobotProfile,
    seed: int,
    noise: bool,
) -> Simulator:
    """A simulator of one robot of the world alone.

    A robot that is not an e-puck is not simulated: its controller runs and its stand-in body
    stays where it stands, in a copy of the world without walls or movable bodies (which it does
    not touch, since it does not move by itself, and which its devices, not simulated, do not
    see). There a supervisor puts it wherever Webots would, its own controller sliding it
    through a wall by its ``translation`` as much as another's placing it; and a robot with no
    body at all (a Supervisor that only sends orders) may stand where an e-puck's disc would
    overlap a wall. An e-puck whose start overlaps a wall is refused as ever.
    """
    from mazesim.webots.importer import import_wbt

    own_world, _ = import_wbt(world_path, robot_line=int(robot["line"]))
    if robot.get("profile") is not None:
        return Simulator(own_world, robot=profile, seed=seed, noise=noise)
    return Simulator(_without_walls(own_world), robot=profile, seed=seed, noise=noise)


def _without_walls(world: World) -> World:
    """``world`` without its walls and movable bodies (a robot that is not an e-puck's)."""
    source = f"{world.name} (without walls)"
    layout = load_toml(world.to_toml(), source)
    text = dump_toml({key: value for key, value in layout.items() if key not in _SOLID_TABLES})
    return World.from_toml(text, source=source)


def _say_what_is_missing(
    runs: list[RobotRun],
) -> tuple[bool, dict[str, str], dict[str, PreparedController]]:
    """Prepares each robot's controller once (a C or C++ one is built into the cache, which its
    process then takes) and says at the run's start what each one lacks, as a run of one robot
    does (but for the supervisor's imports and removals, which a run of the whole world does),
    each statement once for the world with the robots it concerns (thirty robots of one
    controller are named on one line); the list is kept on its robot's run. A C or C++
    controller that does not compile leaves its robot standing still, the others running, as in
    Webots. Returns whether a controller's Tk windows need a virtual display, the environment
    the controllers' windows need and each controller file's preparation."""
    prepared: dict[str, PreparedController] = {}
    concerned: dict[str, list[str]] = {}
    for run in runs:
        if run.controller is None:
            continue
        if run.controller not in prepared:
            try:
                done = prepare_controller(run.controller)
            except ControllerBuildError as failure:
                done = unbuilt(run.controller, failure)
            prepared[run.controller] = done
            for note in done.notes:
                print(f"mazesim: {note}", file=sys.stderr)
        done = prepared[run.controller]
        run.missing = tuple(m for m in done.missing if m not in done.met_in_world_runs)
        for missing in run.missing:
            concerned.setdefault(missing, []).append(repr(run.name))
    for missing, names in concerned.items():
        print(f"mazesim: missing: {_robots_named(names)}: {missing}", file=sys.stderr)
    environment: dict[str, str] = {}
    for done in prepared.values():
        environment.update(done.environment)
    return any(done.virtual_display for done in prepared.values()), environment, prepared


#: How many robots a statement of what is missing names before it counts the rest.
NAMED_ROBOTS = 5


def _robots_named(names: list[str]) -> str:
    """``robot 'a'``, or ``robots 'a', 'b'``, the first :data:`NAMED_ROBOTS` then how many more
    (names already quoted)."""
    if len(names) == 1:
        return f"robot {names[0]}"
    shown = ", ".join(names[:NAMED_ROBOTS])
    rest = len(names) - NAMED_ROBOTS
    return f"robots {shown}" + (f" and {rest} more ({len(names)} in all)" if rest > 0 else "")


class Interruption:
    """Ctrl-C during a world run, noted rather than raised (a context manager, in the main
    thread only): raised in the middle of a message on a controller's pipe, it would leave the
    pipe holding half a message or an unread answer. The first Ctrl-C sets ``requested``; a
    second one raises ``KeyboardInterrupt``."""

    def __init__(self) -> None:
        self.requested = False
        self._previous: Any = None

    def _note(self, signum: int, frame: Any) -> None:
        if self.requested:
            raise KeyboardInterrupt
        self.requested = True

    def __enter__(self) -> Interruption:
        if threading.current_thread() is threading.main_thread():
            self._previous = signal.signal(signal.SIGINT, self._note)
        return self

    def __exit__(self, *exc: object) -> None:
        if self._previous is not None:
            signal.signal(signal.SIGINT, self._previous)


def _lockstep(
    jobs: Mapping[int, ControllerJob],
    simulators: list[Any],
    movable: list[bool],
    fleet: Fleet,
    runs: list[RobotRun],
    traction: WorldTraction,
    watch: Callable[[list[Any], Mapping[int, tuple[float, float]] | None], None] | None = None,
    joined: Callable[..., tuple[RobotRun, ControllerJob | None]] | None = None,
) -> tuple[int, bool]:
    """Starts the controller processes and steps the world whenever every running controller
    has asked for the step; returns the number of steps and whether Ctrl-C ended the run.

    A robot a supervisor imports gets its run and controller process from ``joined`` at once,
    and the world waits for its first step before the next; a removed robot's controller is
    answered the end at its next step (``Robot.step`` returns -1).

    Once the run is over (a supervisor quit, or Ctrl-C), each controller's next step is answered
    at once with the end (``Robot.step`` returns -1); after Ctrl-C, controllers that have not
    ended :data:`EXIT_WAIT_SECONDS` later are stopped."""
    processes = ControllerProcesses()
    connections = {index: processes.start(job) for index, job in jobs.items()}
    for run, simulator in zip(runs, simulators):
        x, y, _ = simulator.pose
        run.xs.append(float(x))
        run.ys.append(float(y))
    world = _Pipes(connections, simulators, movable, fleet, runs)
    steps = 0
    deadline: float | None = None
    exit_wait = EXIT_WAIT_SECONDS
    try:
        with Interruption() as interruption:
            while world.live:
                if interruption.requested and deadline is None:
                    world.over, deadline = True, time.monotonic() + EXIT_WAIT_SECONDS
                if deadline is not None and time.monotonic() > deadline:
                    for index in world.live:
                        runs[index].stopped = True
                    exit_wait = 0.0
                    break
                for ready in wait(world.pending(), timeout=_POLL_SECONDS):
                    world.serve(ready)
                    changed = fleet.joined or fleet.left or fleet.restarts or fleet.reload_asked
                    if joined is not None and changed:
                        world.regroup(processes, joined)
                wheels = world.wheels
                if wheels and (world.over or world.live <= set(wheels)):
                    if not world.over:
                        if watch is not None:
                            watch(simulators, wheels)
                        fleet.note_poses()
                        for index, text in world.own_custom_data.items():
                            fleet.note_own_custom_data(index, text)
                        world.own_custom_data.clear()
                        # A robot whose controller has ended goes on as its motors'
                        # last commands have it.
                        driven = {**world.coasting.wheels(traction.dt), **wheels}
                        _step_world(simulators, traction.drive(driven), world.radio, runs)
                        traction.settle()
                        if fleet.reset_asked:
                            fleet.reset_scene()
                            fleet.note_poses()
                            for run, simulator in zip(runs, simulators):
                                run.xs[-1], run.ys[-1] = (float(v) for v in simulator.pose[:2])
                        steps += 1
                    for index in sorted(wheels):
                        state = None
                        if not world.over and index not in fleet.gone:
                            state = state_after_step(simulators[index])
                            state["last_reset"] = fleet.last_reset(index)
                            state["custom_data"] = fleet.custom_data(index)
                            state["wall_changes"] = fleet.wall_changes
                            state["light_changes"] = fleet.solids.light_changes
                        connections[index].send(("ok", (state is None, state)))
                    wheels.clear()
    finally:
        processes.finish(exit_wait)
        for connection in [*connections.values(), *world.retired.values()]:
            connection.close()
    return steps, deadline is not None


def _unattended(
    simulators: list[Any],
    fleet: Fleet,
    runs: list[RobotRun],
    traction: WorldTraction,
    watch: Callable[[list[Any], Mapping[int, tuple[float, float]] | None], None] | None,
    seconds: float,
) -> tuple[int, bool]:
    """Steps a world none of whose robots runs a controller until ``seconds`` of world time (or
    Ctrl-C), as Webots runs such a world until it is stopped: bodies fall and roll, every
    robot's motors hold its wheels. Returns the number of steps and whether Ctrl-C ended it."""
    steps = 0
    with Interruption() as interruption:
        while float(simulators[0].time) < seconds - 1e-9 and not interruption.requested:
            if watch is not None:
                watch(simulators, {})
            fleet.note_poses()
            _step_world(simulators, traction.drive({}), fleet.radio, runs)
            traction.settle()
            steps += 1
    return steps, interruption.requested


class _Pipes:
    """The world's side of the controllers' pipes: which controllers still run, the wheel
    speeds of those that asked for the next step, and whether the run is over."""

    def __init__(
        self,
        connections: Mapping[int, Any],
        simulators: list[Any],
        movable: list[bool],
        fleet: Fleet,
        runs: list[RobotRun],
    ) -> None:
        self.connections = connections
        self.simulators = simulators
        self.movable = movable
        self.fleet = fleet
        self.runs = runs
        self.radio = fleet.radio
        self.by_connection = {id(c): i for i, c in connections.items()}
        self.live = set(connections)
        #: The controllers of removed robots, whose ``Robot.step`` returns -1 until they end.
        self.leaving: set[int] = set()
        #: The processes of restarted controllers, by their pipe: each one's ``Robot.step``
        #: returns -1 until it ends, while its robot's new controller runs (a robot may have
        #: several processes, the bookkeeping is the process's).
        self.retired: dict[int, Any] = {}
        self.wheels: dict[int, tuple[float, float]] = {}
        #: The robots whose controllers have ended, driven by their motors' last commands.
        self.coasting = Coasting()
        #: The wheel motors' commands each running controller's steps last sent, which its
        #: robot's motors keep should the controller die without its report.
        self.sent_commands: dict[int, Any] = {}
        #: Each robot's own ``setCustomData`` sent with the step it asked for.
        self.own_custom_data: dict[int, str] = {}
        #: Each restarted robot's last restart: the world's clock then and the ``controller``
        #: field it started (:meth:`regroup` makes the restarts of one step one).
        self.restarted: dict[int, tuple[float, Any]] = {}
        self.over = False

    def pending(self) -> list[Any]:
        """The pipes of the controllers that still run."""
        running = [self.connections[i] for i in sorted(self.live | self.leaving)]
        return running + list(self.retired.values())

    def regroup(
        self,
        processes: ControllerProcesses,
        joined: Callable[..., tuple[RobotRun, ControllerJob | None]],
    ) -> None:
        """Starts the controllers of the robots a supervisor imported (each steps from the
        next step on, the world waiting for it), ends those of the robots it removed, and
        restarts those it asked to: the running process is answered the end at its step, as a
        removed robot's, and a new one starts at once with what is left of the run's time."""
        if self.fleet.reload_asked:
            self.fleet.reload_scene()
            self.fleet.note_poses()
            self.restarted.clear()  # the clock is back at 0: every restart starts anew
            for index in self.fleet.restarts:
                x, y, _ = self.simulators[index].pose
                self.runs[index].xs[-1], self.runs[index].ys[-1] = float(x), float(y)
        for index in self.fleet.restarts:
            if index in self.fleet.left:
                continue
            now = float(self.simulators[index].time)
            field = self.fleet.robots_of([index])[0].get("controller")
            if self.restarted.get(index) == (now, field):
                # As Webots does, the restarts asked in one step start one controller: the
                # one a restart started in this step runs what the field names, not yet
                # stepped (a field write and a restartController() in the same step).
                continue
            self.restarted[index] = (now, field)
            if index in self.live:
                old = self.connections[index]
                self.retired[id(old)] = old
                self.live.discard(index)
                if self.wheels.pop(index, None) is not None:
                    old.send(("ok", (True, None)))
            restarted, job = joined(index, True)
            run = self.runs[index]
            run.restarts_s.append(now)
            run.controller, run.note = restarted.controller, restarted.note
            if job is not None:
                self._start(processes, index, job)
        self.fleet.restarts.clear()
        for index in self.fleet.left:
            self.runs[index].removed_s = float(self.fleet.clock())
            self.coasting.stop(index)
            if index in self.live:
                self.live.discard(index)
                self.leaving.add(index)
            if self.wheels.pop(index, None) is not None:
                self.connections[index].send(("ok", (True, None)))
        self.fleet.left.clear()
        for index in self.fleet.joined:
            run, job = joined(index)
            x, y, _ = self.simulators[index].pose
            run.xs.append(float(x))
            run.ys.append(float(y))
            self.runs.append(run)
            self.movable.append(self.fleet.robots_of([index])[0].get("profile") is not None)
            if job is not None:
                self._start(processes, index, job)
        self.fleet.joined.clear()

    def _start(self, processes: ControllerProcesses, index: int, job: ControllerJob) -> None:
        """Starts robot ``index``'s controller process for ``job``; the world waits for it."""
        self.coasting.stop(index)
        self.sent_commands.pop(index, None)
        connection = processes.start(job)
        self.connections[index] = connection  # type: ignore[index]
        self.by_connection[id(connection)] = index
        self.live.add(index)

    def serve(self, ready: Any) -> None:
        """Reads one message of a controller's pipe and answers a call, notes a step's wheel
        speeds, or notes the controller's end (a supervisor's quit ends the run)."""
        if id(ready) in self.retired:
            self._serve_retired(ready)
            return
        index = self.by_connection[id(ready)]
        run = self.runs[index]
        try:
            message: Any = ready.recv()
        except (EOFError, OSError):
            # The template that forked it is gone: nothing says how it ended.
            self._without_report(
                index, EXIT_CRASHED, "the controller's process ended without a report\n"
            )
            return
        except Exception as failure:  # noqa: BLE001 - any message that does not unpickle
            # Half a message, or another process's: nothing more on this pipe can be trusted.
            ready.close()
            self._without_report(
                index,
                EXIT_CRASHED,
                "the controller's link to the world's process was lost: a message could not "
                f"be read ({type(failure).__name__}: {failure}); it was ended\n",
            )
            return
        if message[0] == "exit":
            self._exited(index, message[1], message[2])
            return
        if message[0] == "call":
            self._answer(ready, index, message)
        elif message[0] == "step" and index in self.leaving:
            ready.send(("ok", (True, None)))
        elif message[0] == "step":
            self.wheels[index] = (message[1], message[2]) if self.movable[index] else (0.0, 0.0)
            if len(message) > 3 and message[3] is not None:
                self.own_custom_data[index] = str(message[3])
            if len(message) > 4 and message[4] is not None:
                self.sent_commands[index] = message[4]
        elif message[0] == "done":
            summary = message[1]
            self._ended(index)
            if self.movable[index] and index not in self.fleet.gone:
                commands = summary.get("wheel_commands") or ()
                self.coasting.start(index, [WheelCommand(**c) for c in commands])
            for key in ("exit_status", "error", "reached_end", "stopped"):
                setattr(run, key, summary[key])
            run.quit_requested = bool(summary["quit_requested"])
            self.over = self.over or run.quit_requested
            lost = summary.get("lost")
            if lost:
                # A process the controller forked called the API: the run failed with it.
                run.exit_status = run.exit_status or EXIT_CRASHED
                run.error = run.error or f"{lost}\n"
                sys.stderr.write(f"mazesim: robot {_shown(run.name)}: {lost}\n")

    def _exited(self, index: int, status: int, words: str) -> None:
        """Notes that robot ``index``'s controller process ended without its report, as the
        template saw it end: its exit ``status`` (minus the signal's number when killed) and the
        ``words`` it left (why it could not report, or "")."""
        run = self.runs[index]
        if words:
            self._without_report(index, status or EXIT_CRASHED, f"{words}\n")
        elif status < 0:
            self._without_report(index, EXIT_CRASHED, crash_error(_language(run), status))
        elif status:
            self._without_report(
                index,
                status,
                f"the {_language(run)} controller's process exited with status {status} "
                "without its report (as os._exit ends a process; sys.exit or a return "
                "sends it)\n",
            )
        else:
            self._without_report(index, 0, "")

    def _without_report(self, index: int, status: int, error: str) -> None:
        """Notes that robot ``index``'s controller ended without its report, with ``status``
        and ``error`` (said on stderr, naming the robot, unless ""): its motors keep what its
        last step sent."""
        run = self.runs[index]
        sent = self.sent_commands.get(index)
        self._ended(index)
        if sent is not None and self.movable[index] and index not in self.fleet.gone:
            self.coasting.start(index, held_commands(sent, self.simulators[index].wheel_turns))
        if run.error:
            return
        run.exit_status, run.error = status, error
        if error:
            # Its own process did not say so, as it says a controller's traceback.
            sys.stderr.write(f"mazesim: robot {_shown(run.name)}: {error}")

    def _serve_retired(self, ready: Any) -> None:
        """Reads one message of a restarted controller's old process: its calls are answered,
        its steps with the end, and its end (or its pipe's) forgets it."""
        index = self.by_connection[id(ready)]
        try:
            message: Any = ready.recv()
        except Exception:  # noqa: BLE001 - its pipe's end, or a message that does not unpickle
            message = ("done", None)
        if message[0] == "call":
            self._answer(ready, index, message)
        elif message[0] == "step":
            ready.send(("ok", (True, None)))
        elif message[0] in ("done", "exit"):
            del self.retired[id(ready)]

    def _answer(self, ready: Any, index: int, message: Any) -> None:
        """Answers robot ``index``'s controller's call ``message`` on its pipe ``ready``."""
        _, target, name, args = message
        targets = {"simulator": self.simulators[index], "radio": self.radio, "fleet": self.fleet}
        ready.send(answer(targets[target], name, args))

    def _ended(self, index: int) -> None:
        self.sent_commands.pop(index, None)
        self.live.discard(index)
        self.leaving.discard(index)
        self.wheels.pop(index, None)


class WorldTraction:
    """Each imported E-puck's wheel traction (:mod:`mazesim.webots.traction`), applied in the
    world's process to the wheel speeds the controllers ask for.

    A robot found elsewhere than where its last step left it was put there by a supervisor (its
    own, or another's through the :class:`Fleet`): it starts again from rest, as a run of one
    robot's ``move_robot`` has it.
    """

    def __init__(
        self, scenes: list[Scene], robots: list[Mapping[str, Any]], simulators: list[Any]
    ) -> None:
        self._simulators = simulators
        self.dt = float(simulators[0].control_step_ms) / 1000.0
        self.tractions: dict[int, Traction] = {}
        self._left: dict[int, tuple[float, float, float]] = {}
        for index, (robot, scene) in enumerate(zip(robots, scenes)):
            self.join(index, robot, scene)

    def join(self, index: int, robot: Mapping[str, Any], scene: Scene) -> None:
        """Gives robot ``index`` (its import report entry and its node's scene) its traction
        when it is an E-puck: one of the world file, or one a supervisor imported, at rest."""
        version = scene.traction_version
        if robot.get("profile") is None or version is None:
            return
        name = robot_profile_name({"robot_profile": robot.get("profile")})
        profile = RobotProfile.builtin(name)
        self.tractions[index] = epuck_traction(
            version,
            float(profile.wheel_radius),
            float(profile.axle_length),
            float(profile.max_wheel_speed),
        )
        x, y, yaw = (float(v) for v in self._simulators[index].pose)
        self._left[index] = (x, y, yaw)

    def drive(self, wheels: Mapping[int, tuple[float, float]]) -> dict[int, tuple[float, float]]:
        """The wheel speeds that move each robot this step as its traction allows (the others'
        as asked)."""
        driven = dict(wheels)
        for index, traction in self.tractions.items():
            pose = tuple(float(v) for v in self._simulators[index].pose)
            if pose != self._left[index]:
                traction.stop()
            driven[index] = traction.drive(*wheels.get(index, (0.0, 0.0)), self.dt)
        return driven

    def settle(self) -> None:
        """Notes where the step left each robot."""
        for index in self.tractions:
            self._left[index] = tuple(float(v) for v in self._simulators[index].pose)  # type: ignore[assignment]


def _language(run: RobotRun) -> str:
    """The language of robot ``run``'s controller, as a crash names it."""
    suffix = os.path.splitext(run.controller or "")[1].lower()
    if suffix in (*C_SUFFIXES, *CPP_SUFFIXES):
        return language_name(suffix)
    return "BotStudio" if suffix == ".bsg" else "Python"


def _step_world(
    simulators: list[Any],
    wheels: Mapping[int, tuple[float, float]],
    radio: Radio,
    runs: list[RobotRun],
) -> None:
    """One basic step of every robot: the motion, then the radio's packets, which each
    receiver measures (range, cone, line of sight, direction and strength) where the robots
    stand after the step's motion, as Webots' ``WbReceiver::postPhysicsStep`` does."""
    here = {i: s for i, s in enumerate(simulators) if not isinstance(s, RemovedRobot)}
    views = [(i, s) for i, s in enumerate(simulators) if isinstance(s, RobotView)]
    if views:
        commands = np.array([wheels.get(i, (0.0, 0.0)) for i, _ in views], dtype=np.float64)
        views[0][1].simulator.step_robots(commands)
    for index, simulator in here.items():
        if not isinstance(simulator, RobotView):
            simulator.step(*wheels.get(index, (0.0, 0.0)))
    radio.transmit({i: tuple(float(v) for v in s.pose) for i, s in here.items()})  # type: ignore[misc]
    for index, simulator in here.items():
        x, y, _ = simulator.pose
        runs[index].xs.append(float(x))
        runs[index].ys.append(float(y))
