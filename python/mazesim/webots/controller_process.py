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
  report (``os._exit``, killed, crashed in native code) leaves the commands its last step sent;
  the template it was forked from then writes how it ended (:mod:`mazesim.webots.process_template`).

The report is sent whatever the controller did to its standard streams (closed, replaced). Only
the controller's own process asks the world's process: a process the controller forks gets
:class:`LinkLost` at its first call (the answers would go to either process), and so does a
controller whose pipe is gone (it closed its file descriptor). A process that lost its link
cannot report; it leaves why in its :class:`~mazesim.webots.process_template.LastWords` and ends
with status 1, and the world's process says so (a forked process's words go with its
controller's report).

The controller itself runs as in a run of one robot (:func:`mazesim.webots.runner.run_controller`)
against a :class:`RemoteSimulator`, which forwards the simulator's methods over the pipe.
"""

from __future__ import annotations

import contextlib
import errno
import os
import sys
import threading
from collections.abc import Sequence
from dataclasses import asdict, dataclass, replace
from multiprocessing.connection import Connection
from types import FrameType
from typing import TYPE_CHECKING, Any

from mazesim.webots.last_commands import WheelCommand

if TYPE_CHECKING:
    from mazesim._core import RobotProfile
    from mazesim.webots.keyboard import KeyScript
    from mazesim.webots.process_template import LastWords
    from mazesim.webots.requirements import PreparedController

__all__ = [
    "STATE_AFTER_STEP",
    "ControllerJob",
    "ControllerSummary",
    "LinkLost",
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
        custom_data: The robot's ``customData`` field as the run has left it, for a controller
            started while the world runs (a restart, a robot imported) after a write of the
            field (by a supervisor, or the robot's former controller); None: the file's. Webots
            hands a starting controller the field's value at that time.
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
    custom_data: str | None = None


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
    #: Why a process the controller forked was refused the link, or "".
    lost: str = ""


#: Held while a question to the world's process waits for its answer.
_ASKING = threading.RLock()


class LinkLost(BaseException):
    """Raised by a call to the world's process that cannot be made: the controller's pipe is
    gone, or the caller is a process the controller forked. It derives from ``BaseException``
    so that a controller's ``except Exception`` does not take it for its own error."""


#: The controller's process, the only one that asks the world's process (set when its run
#: starts); why its link was lost (None while it works); and why a process the controller
#: forked was refused it (None while none called the API).
_link: dict[str, Any] = {"pid": None, "lost": None, "refused": None}


#: The file whose frame runs the controller's code.
_RUNNER = os.path.join("webots", "runner.py")


def _refusal(message: tuple[Any, ...]) -> LinkLost:
    """The :class:`LinkLost` of a process the controller forked that asks ``message``; noted in
    ``_link`` when the controller's own code asked (not the run's own reads at its end)."""
    from mazesim.webots.termination import is_controllers

    what = "Robot.step" if message[0] == "step" else "the controller API"
    refused = (
        f"a process the controller forked (pid {os.getpid()}) called {what}: only the "
        "controller's own process is linked to the world's process, so that process was "
        "stopped; call the API from the controller's process (a thread, or a forked process "
        "that only computes)"
    )
    # The controller's code runs inside the runner's frame; the runner's own reads do not.
    frame: FrameType | None = sys._getframe(1)
    while frame is not None and not frame.f_code.co_filename.endswith(_RUNNER):
        if is_controllers(frame) and _link["refused"] is None:
            _link["refused"] = refused
        frame = frame.f_back
    return LinkLost(refused)


def _lost(failure: BaseException) -> LinkLost:
    """The :class:`LinkLost` of a failed message on the pipe, which no later call uses."""
    if isinstance(failure, OSError) and failure.errno == errno.EBADF:
        why = (
            "the controller closed its file descriptor (os.close or os.closerange): close only "
            "the files it opened"
        )
        # The pipe's object would close that descriptor again when it is collected (its
        # number may name a file the controller opened since; it is left alone) and print
        # the failure as an ignored exception: that one is said once, above.
        sys.unraisablehook = _closed_pipe_quiet(sys.unraisablehook)
    elif isinstance(failure, (EOFError, BrokenPipeError, ConnectionError)):
        why = "the world's process closed it"
    else:
        why = f"{type(failure).__name__}: {failure}"
    _link["lost"] = f"the controller's link to the world's process was lost: {why}"
    return LinkLost(_link["lost"])


def _closed_pipe_quiet(hook: Any) -> Any:
    """``hook`` (an unraisable-exception hook) but for the bad file descriptor of a pipe the
    controller closed, which a pipe's collection raises and nothing can catch."""

    def quiet(unraisable: Any) -> None:
        failure = unraisable.exc_value
        if not (isinstance(failure, OSError) and failure.errno == errno.EBADF):
            hook(unraisable)

    return quiet


class Remote:
    """A stand-in for an object of the world's process: attribute reads and method calls are
    forwarded over the pipe."""

    def __init__(self, connection: Connection, target: str) -> None:
        self._connection = connection
        self._target = target
        self._methods: dict[str, Any] = {}

    def _ask(self, message: tuple[Any, ...]) -> Any:
        if _link["pid"] is not None and os.getpid() != _link["pid"]:
            raise _refusal(message)
        if _link["lost"] is not None:
            # Its file descriptor may name a file the controller opened since.
            raise LinkLost(_link["lost"])
        # One question at a time on the pipe: a controller's threads that call the API at once
        # would read each other's answers (Webots' C library serialises its calls alike).
        with _ASKING:
            try:
                self._connection.send(message)
                status, value = self._connection.recv()
            except (OSError, EOFError) as failure:
                raise _lost(failure) from None
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

    def __init__(self, connection: Connection, profile: str | RobotProfile) -> None:
        from mazesim._core import RobotProfile

        super().__init__(connection, "simulator")
        #: The profile, built here from the robot's node as the world's process builds it
        #: (:func:`~mazesim.webots.simulation.robot_profile`): it does not cross the pipe.
        self.robot = RobotProfile.builtin(profile) if isinstance(profile, str) else profile
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


def controller_main(
    connection: Connection, job: ControllerJob, last_words: LastWords | None = None
) -> None:
    """Runs one robot's controller against the world of the process at the other end of
    ``connection`` (the entry point of a controller process); ``last_words``: where it says why
    it cannot report its end (:mod:`mazesim.webots.process_template`)."""
    from mazesim.webots import runner
    from mazesim.webots.importer import import_wbt, import_wbt_text
    from mazesim.webots.runner import run_controller
    from mazesim.webots.scene import body_y_up, read_scene, read_world_text
    from mazesim.webots.simulation import robot_profile

    _link["pid"] = os.getpid()
    runner.OWN_PROCESS = True  # its os._exit ends this process alone, as in Webots
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
    # The robot's own sensors and drive make its profile here as in the world's process.
    profile = robot_profile({"robot_profile": job.profile}, scene)
    if job.custom_data is not None:
        scene.robot_custom_data = job.custom_data
    summary = ControllerSummary(1, "", False, False, False, 0)
    try:
        run = run_controller(
            job.controller,
            world,
            seconds=job.seconds,
            noise=job.noise,
            report=report,
            scene=scene,
            simulator=RemoteSimulator(connection, profile),
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
            _say(run.error)
    except LinkLost:
        words = _link["lost"] if os.getpid() == _link["pid"] else _link["refused"]
        if last_words is not None and words:
            last_words.say(words)
        raise SystemExit(1 if words else 0) from None
    finally:
        if os.getpid() == _link["pid"] and _link["lost"] is None:
            _report(connection, summary, last_words)
    if os.getpid() != _link["pid"]:
        # A process the controller forked that left its code without a call: it ends as its
        # run did, without a report (its controller's process sends the robot's).
        raise SystemExit(summary.exit_status)


def _say(text: str) -> None:
    """Writes ``text`` on the standard error, or on its file descriptor when the controller
    closed or broke ``sys.stderr``."""
    try:
        sys.stderr.write(text)
        sys.stderr.flush()
    except (OSError, ValueError, AttributeError):
        with contextlib.suppress(OSError):
            os.write(2, text.encode("utf-8", "backslashreplace"))


def _report(
    connection: Connection, summary: ControllerSummary, last_words: LastWords | None
) -> None:
    """Sends the controller's report, whatever the controller did to its standard streams; a
    link that fails now is left in ``last_words`` and the process ends with status 1."""
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(OSError, ValueError, AttributeError):
            stream.flush()
    if last_words is not None:
        summary = replace(summary, lost=last_words.read())
    try:
        connection.send(("done", asdict(summary)))
        connection.close()
    except OSError as failure:
        if last_words is not None:
            last_words.say(str(_lost(failure)))
        raise SystemExit(1) from None
