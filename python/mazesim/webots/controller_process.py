"""One robot's controller in its own process, talking to the process that owns the world.

Webots starts each robot's controller in a process of its own, so controllers share no
module-level state; ``mazesim webots run WORLD`` does the same. The process that owns the world
(:mod:`mazesim.webots.lockstep`) has one process per robot forked from a template process that
imported mazesim once (:mod:`mazesim.webots.process_template`); each runs
:func:`controller_main` on a pipe of its own (``multiprocessing.connection.Connection``;
messages are pickled tuples). The protocol, from the controller's side:

- ``("call", target, name, args)``: calls ``name(*args)`` on ``target`` (``"simulator"``: the
  robot's simulator; ``"radio"``: the world's :class:`~mazesim.webots.radio.Radio`; ``"fleet"``:
  the world's robots, for a supervisor) and answers ``("ok", value)`` or ``("error",
  exception)``; ``name`` may also be an attribute, whose value is answered;
- ``("step", left, right)``: this robot's wheel speeds (rad/s) for the next basic step; answered
  ``("ok", (False, state))`` once every robot whose controller still runs has asked for the step
  and the world has taken it (lockstep), ``state`` being the robot's ``pose``, ``time`` and
  ``wheel_turns`` after the step (:data:`STATE_AFTER_STEP`, which the controller's process then
  reads without asking, until it moves its robot itself), the world's ``last_reset``
  (:class:`~mazesim.webots.simulation.WorldReset`) and the ``customData`` a supervisor last
  wrote into the robot's node (``Fleet.custom_data``) and how many times a supervisor has
  changed the walls (``Fleet.wall_changes``) and set a light's field (``light_changes``), or
  ``("ok", (True, None))`` without a step when a supervisor has quit the simulation
  (``Robot.step`` then returns -1); a step may also carry the robot's own ``customData``
  written since the last one, and the wheel motors' commands when they changed since the last
  step sent them (:func:`held_commands`);
- ``("done", summary)``: the controller has ended (a dict of :class:`ControllerSummary`'s
  fields); no answer. From then on the robot's wheels turn as its motors' last commands have
  them (:mod:`mazesim.webots.last_commands`), as in Webots. A process that ends without this
  report (killed, or crashed in native code) leaves the commands its last step sent.

The controller itself runs as in a run of one robot (:func:`mazesim.webots.runner.run_controller`)
against a :class:`RemoteSimulator`, which forwards the simulator's methods over the pipe.
"""

from __future__ import annotations

import os
import sys
import threading
from collections.abc import Sequence
from dataclasses import asdict, dataclass
from multiprocessing.connection import Connection
from typing import TYPE_CHECKING, Any

from mazesim.webots.last_commands import WheelCommand

if TYPE_CHECKING:
    from mazesim.webots.keyboard import KeyScript
    from mazesim.webots.requirements import PreparedController

__all__ = [
    "STATE_AFTER_STEP",
    "ControllerJob",
    "ControllerSummary",
    "Remote",
    "RemoteSimulator",
    "controller_main",
    "held_commands",
    "state_after_step",
]


@dataclass(frozen=True)
class ControllerJob:
    """What a controller process runs.

    Attributes:
        world_path: The ``.wbt`` file.
        robot_index: The robot's index among the world's robots.
        robot_line: The line of the robot's node in the file.
        controller: The controller's file or Webots folder.
        profile: The robot profile that simulates it.
        seconds: Simulated seconds after which ``Robot.step`` returns -1.
        noise: Whether the sensors are noisy.
        prepared: The controller as the world's process prepared it
            (:func:`~mazesim.webots.requirements.prepare_controller`), or None to prepare it in
            the controller's process.
        world_text: The running world's description, when a supervisor imported the robot
            (:mod:`mazesim.webots.scene_edits`; ``robot_line`` is a line of it), else None: the
            file's text.
        keys: The keyboard script its ``Keyboard`` plays, or None: no key is pressed.
    """

    world_path: str
    robot_index: int
    robot_line: int
    controller: str
    profile: str
    seconds: float
    noise: bool
    prepared: PreparedController | None = None
    world_text: str | None = None
    keys: KeyScript | None = None


@dataclass(frozen=True)
class ControllerSummary:
    """What a controller's run reports back to the world's process when it ends."""

    exit_status: int
    error: str
    reached_end: bool
    stopped: bool
    quit_requested: bool
    steps: int
    #: The wheel motors' commands as the controller left them, each a
    #: :class:`~mazesim.webots.last_commands.WheelCommand`'s fields.
    wheel_commands: tuple[dict[str, float], ...] = ()


#: Held while a question to the world's process waits for its answer.
_ASKING = threading.RLock()


class Remote:
    """A stand-in for an object of the world's process: attribute reads and method calls are
    forwarded over the pipe."""

    def __init__(self, connection: Connection, target: str) -> None:
        self._connection = connection
        self._target = target
        self._methods: dict[str, Any] = {}

    def _ask(self, message: tuple[Any, ...]) -> Any:
        # One question at a time on the pipe: a controller's threads that call the API at once
        # would read each other's answers (Webots' C library serialises its calls alike).
        with _ASKING:
            self._connection.send(message)
            status, value = self._connection.recv()
        if status == "error":
            raise value
        return value

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_"):
            raise AttributeError(name)
        if name in self._methods:
            return self._methods[name]
        value = self._ask(("call", self._target, name, None))
        if isinstance(value, _Method):
            method = self._methods[name] = lambda *args: self._ask(
                ("call", self._target, name, args)
            )
            return method
        return value


@dataclass(frozen=True)
class _Method:
    """The answer to reading an attribute that is a method: call it with arguments."""


#: The answer to reading a method's name.
METHOD = _Method()


#: What the answer to a step carries of the robot's state after it: what a controller reads of
#: its robot at every step, which changes only when the world steps or the robot is moved.
STATE_AFTER_STEP = ("pose", "time", "wheel_turns")


def state_after_step(simulator: Any) -> dict[str, Any]:
    """The robot's :data:`STATE_AFTER_STEP`, read in the world's process."""
    return {name: getattr(simulator, name) for name in STATE_AFTER_STEP}


class RemoteSimulator(Remote):
    """The robot's simulator in the world's process; ``step`` waits for the lockstep.

    Its ``pose``, ``time`` and ``wheel_turns`` after a step come with the step's answer; until the
    next step they are read from it (a pose this process sets is asked for again). A robot that
    another robot's supervisor puts elsewhere during a step reads its new pose after the next
    step, as a Webots robot's sensors do.
    """

    def __init__(self, connection: Connection, profile: str) -> None:
        from mazesim._core import RobotProfile

        super().__init__(connection, "simulator")
        #: The profile, built here: it does not cross the pipe.
        self.robot = RobotProfile.builtin(profile)
        self._after_step: dict[str, Any] = {}
        #: The world's last reset, as the last step's answer told it (None before the first).
        self.last_reset: Any = None
        #: The ``customData`` a supervisor last wrote into the robot's node and the number of
        #: that write, as the last step's answer told it (None while none did).
        self.custom_data: tuple[int, str] | None = None
        #: How many times a supervisor has changed the world's walls, as the last step's
        #: answer told it (:class:`~mazesim.webots.walls_now.WallsNow`).
        self.wall_changes = 0
        #: How many times a supervisor has set a light's field (or a reset undid it), as the
        #: last step's answer told it (``RobotSimulation.lights_now``).
        self.light_changes = 0
        #: The robot's own ``setCustomData`` since its last step, which goes with the next.
        self.own_custom_data: str | None = None
        #: The wheel motors' commands the next step sends (:meth:`hold_wheel_commands`), and
        #: those the world's process holds already.
        self._commands: tuple[tuple[float, ...], ...] | None = None
        self._commands_held: tuple[tuple[float, ...], ...] | None = None

    def hold_wheel_commands(self, commands: tuple[WheelCommand, ...]) -> None:
        """Notes the wheel motors' commands as the next step sends them, which the world's
        process holds for the robot (:func:`held_commands`); each wheel's angle goes as its
        difference to the wheel's turns, which changes only when the world is reset."""
        turns = self.wheel_turns
        self._commands = tuple(
            (c.target_position, c.velocity, c.max_velocity, c.angle - float(turned))
            for c, turned in zip(commands, turns)
        )

    def _state(self, name: str) -> Any:
        if name in self._after_step:
            return self._after_step[name]
        return self._ask(("call", "simulator", name, None))

    @property
    def pose(self) -> Any:
        """The robot's x, y, yaw."""
        return self._state("pose")

    @property
    def time(self) -> Any:
        """Simulated seconds since the start."""
        return self._state("time")

    @property
    def wheel_turns(self) -> Any:
        """The wheels' turns (rad), unrounded."""
        return self._state("wheel_turns")

    def set_pose_pushed_out(self, x: float, y: float, yaw: float) -> tuple[float, float]:
        """Puts the robot at a new pose at rest, or at the nearest clear of the walls; returns
        the x, y it stands at."""
        self._after_step.clear()
        x, y = self._ask(("call", "simulator", "set_pose_pushed_out", (x, y, yaw)))
        return x, y

    def step(self, left: float, right: float) -> bool:
        """Asks for the next basic step with these wheel speeds; returns once taken, True when
        the world's run is over instead (a supervisor quit it)."""
        written, self.own_custom_data = self.own_custom_data, None
        commands = None if self._commands == self._commands_held else self._commands
        self._commands_held = self._commands
        over, state = self._ask(("step", float(left), float(right), written, commands))
        self._after_step = dict(state or {})
        self.last_reset = self._after_step.pop("last_reset", self.last_reset)
        self.custom_data = self._after_step.pop("custom_data", self.custom_data)
        self.wall_changes = self._after_step.pop("wall_changes", self.wall_changes)
        self.light_changes = self._after_step.pop("light_changes", self.light_changes)
        return bool(over)


def held_commands(sent: Sequence[Sequence[float]], turns: Sequence[float]) -> list[WheelCommand]:
    """The wheel motors' commands as a robot's last step sent them
    (:meth:`RemoteSimulator.hold_wheel_commands`), each wheel's angle where its ``turns``
    (rad) now put it."""
    return [
        WheelCommand(target, velocity, max_velocity, offset + float(turned))
        for (target, velocity, max_velocity, offset), turned in zip(sent, turns)
    ]


def answer(target: Any, name: str, args: tuple[Any, ...] | None) -> tuple[str, Any]:
    """The world's process's answer to ``("call", target, name, args)`` on ``target``."""
    try:
        value = getattr(target, name)
        if args is None:
            return ("ok", METHOD if callable(value) else value)
        return ("ok", value(*args))
    except Exception as failure:  # noqa: BLE001 - the error is raised in the controller
        return ("error", failure)


def controller_main(connection: Connection, job: ControllerJob) -> None:
    """Runs one robot's controller against the world of the process at the other end of
    ``connection`` (the entry point of a controller process)."""
    from mazesim.webots.importer import import_wbt, import_wbt_text
    from mazesim.webots.runner import run_controller
    from mazesim.webots.scene import body_y_up, read_scene, read_world_text

    text = job.world_text
    if text is None:
        world, imported = import_wbt(job.world_path, robot_line=job.robot_line)
        text = read_world_text(job.world_path)
    else:
        world, imported = import_wbt_text(text, job.world_path, robot_line=job.robot_line)
    report: dict[str, Any] = dict(imported)
    report["path"] = os.path.abspath(job.world_path)
    line = report.get("robot_line")
    y_up = body_y_up(report.get("robots") or [], line)
    scene = read_scene(text, report.get("robot_model"), line, y_up)
    summary = ControllerSummary(1, "", False, False, False, 0)
    try:
        run = run_controller(
            job.controller,
            world,
            seconds=job.seconds,
            noise=job.noise,
            report=report,
            scene=scene,
            simulator=RemoteSimulator(connection, job.profile),
            radio=Remote(connection, "radio"),
            fleet=Remote(connection, "fleet"),
            robot_index=job.robot_index,
            prepared=job.prepared,
            keys=job.keys,
        )
        summary = ControllerSummary(
            run.exit_status,
            run.error,
            run.reached_end,
            run.stopped,
            run.quit_requested,
            run.steps,
            tuple(asdict(command) for command in run.wheel_commands),
        )
        if run.error:
            sys.stderr.write(run.error)
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        connection.send(("done", asdict(summary)))
        connection.close()
