"""The simulation behind mazesim's Webots ``controller`` module.

A :class:`RobotSimulation` is one e-puck in one world, stepped one basic time step at a time,
with an optional time limit after which ``Robot.step`` returns -1, and the trajectory of the run.
:func:`prepare` makes the simulation that the next ``controller.Robot()`` attaches to; the
``mazesim webots run`` command prepares one before it runs a controller file.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._core import RobotProfile, Simulator, World
from mazesim.errors import InvalidArgumentError, UnknownNameError, _shown
from mazesim.webots.keyboard import KeyScript
from mazesim.webots.lights import Light, carried, lit
from mazesim.webots.own_sensors import OwnSensors, own_sensors
from mazesim.webots.radio import Radio
from mazesim.webots.scene import Row, Scene
from mazesim.webots.solids import world_objects
from mazesim.webots.traction import Traction, epuck_traction

__all__ = [
    "RobotSimulation",
    "StepObserver",
    "WorldReset",
    "current",
    "observing_steps",
    "prepare",
    "release",
    "robot_profile",
    "robot_profile_name",
]

#: Displacement per step (metres) below which the robot counts as stopped.
STOP_DISPLACEMENT = 1e-4
#: The profile used when the import report names none (or one this build does not have).
DEFAULT_PROFILE = "e-puck"


@dataclass(frozen=True)
class WorldReset:
    """A reset of the world (a supervisor's ``simulationReset``) as a robot's clock and wheel
    sensors count from it, as Webots restarts them.

    Attributes:
        count: How many resets the world has had (0: none yet).
        time: The simulator's time at the last reset (s).
        turns: The robot's wheel turns at the last reset (rad).
    """

    count: int = 0
    time: float = 0.0
    turns: tuple[float, float] = (0.0, 0.0)


def robot_profile_name(report: Mapping[str, Any] | None) -> str:
    """The robot profile to simulate for an import report.

    Args:
        report: The import report of a ``.wbt`` world, or None for a mazesim world.

    Returns:
        The report's ``robot_profile`` when this build has that profile, else ``"e-puck"``.
    """
    name = (report or {}).get("robot_profile") or DEFAULT_PROFILE
    try:
        RobotProfile.builtin(str(name))
    except UnknownNameError:
        return DEFAULT_PROFILE
    return str(name)


def robot_profile(
    report: Mapping[str, Any] | None,
    scene: Scene | None,
    own: OwnSensors | None = None,
) -> str | RobotProfile:
    """The robot profile to simulate for an import report and the world's scene facts: the
    report's profile (see :func:`robot_profile_name`), or its copy with the robot node's own
    sensors' tables, poses, ray tilts and types (``own``, by default
    :func:`~mazesim.webots.own_sensors.own_sensors` of the scene: an ``E-puck`` PROTO's rays
    rise by its stock 0.16 rad); the profile's name when every sensor is the profile's."""
    name = robot_profile_name(report)
    if own is None:
        own = own_sensors(name, scene)
    return name if own.profile is None else own.profile


class RobotSimulation:
    """One e-puck in one world, driven by a Webots-style controller.

    Attributes:
        world: The world.
        simulator: The simulator, stepped one basic time step at a time.
        basic_time_step_ms: The world's basic time step in milliseconds.
        step_limit: The number of basic steps after which the run ends, or None for no limit.
        steps: Basic steps taken so far.
        ended: Whether ``Robot.step`` has returned -1.
        ended_at: When it did (``time.monotonic()``), or None.
        stopped: Whether the controller went on past :data:`~mazesim.webots.termination.
            GRACE_SECONDS` after the end and was stopped.
        xs: The robot's x after each step (the start first).
        ys: The robot's y after each step (the start first).
        longest_stop_steps: The longest run of consecutive steps in which the robot moved less
            than :data:`STOP_DISPLACEMENT`.
        report: The import report of the ``.wbt`` world (empty for a mazesim world).
        keys: The keyboard script (empty: no key is ever pressed).
        supervisor: Whether the robot is a supervisor (the world's ``supervisor TRUE``, or
            the controller created a ``Supervisor`` the world does not refuse:
            :mod:`~mazesim.webots.supervisor_refusal`).
        scene: DEF names, camera fields and north read from the world file.
        sensor_tables: The world's own lookup tables the robot's sensors read through, by
            sensor name (see :func:`~mazesim.webots.own_sensors.own_sensors`); empty when all
            are the profile's.
        sensor_types: The world's ``type`` of the robot's distance sensors that are not
            ``infra-red``, by sensor name (see :func:`~mazesim.webots.own_sensors.own_sensors`).
        noise: Whether the sensors are noisy.
        seed: The seed of the sensor noise.
        quit_status: The status a supervisor's ``simulationQuit`` asked for, or None.
        velocity: The robot's world-frame velocity over the last step: vx, vy (m/s), yaw rate
            (rad/s).
        acceleration: The robot's world-frame acceleration over the last step: ax, ay (m/s^2).
        robot_index: The robot's index among the world's robots (0 in a run of one robot).
        radio: The world's radio, which carries the packets of Emitters to Receivers.
        fleet: The world's robots when another process owns the world (for a supervisor), or
            None.
        world_over: Whether the world's run is over (a supervisor of another robot quit it).
        solids: The world's walls and movable bodies as a supervisor moves them, in a run of
            one robot (None until :func:`~mazesim.webots.solids.world_objects` is asked).
        scene_edits: The nodes a supervisor imported into the running world or removed from it
            (:class:`~mazesim.webots.scene_edits.SceneEdits`; None until its first change).
        reset_listeners: Called when the world's reset reaches this robot, at the end of a
            step (the devices' and a supervisor's nodes' own restarts).
        paused: Whether a supervisor paused the simulation (``simulationSetMode(PAUSE)``).
        owns_world: Whether this simulation steps the world itself (a run of one robot), and
            so transmits the radio's packets at each step; a robot of a world with several
            robots has the world stepped for it in lockstep with the others.
    """

    def __init__(
        self,
        world: World,
        *,
        seconds: float | None = None,
        seed: int = 0,
        noise: bool = True,
        report: Mapping[str, Any] | None = None,
        keys: KeyScript | None = None,
        supervisor: bool = False,
        scene: Scene | None = None,
        simulator: Any = None,
        radio: Any = None,
        fleet: Any = None,
        robot_index: int = 0,
        robot: str | RobotProfile | None = None,
    ) -> None:
        """Creates the simulator of the run.

        Args:
            world: The world to run in.
            seconds: Simulated seconds after which ``Robot.step`` returns -1; None runs forever.
            seed: Seed of the sensor noise.
            noise: Whether the sensors are noisy, as in Webots.
            report: The import report of a ``.wbt`` world: its robot profile, extension devices
                and DEF names are used.
            keys: The keyboard script the ``Keyboard`` device plays.
            supervisor: Whether the robot is a supervisor even if the controller creates a
                plain ``Robot``.
            scene: DEF names, camera fields and north read from the world file.
            simulator: The robot's simulator when another process owns the world (a stand-in
                with the :class:`~mazesim.Simulator` methods), else None: a new one.
            radio: The world's radio when another process owns the world, else None: a new one.
            fleet: The world's robots (:class:`~mazesim.webots.lockstep.Fleet`) when another
                process owns the world, for a supervisor; None in a run of one robot.
            robot_index: The robot's index among the world's robots.
            robot: The robot profile to simulate instead of the world's (a built-in name, a
                profile file's path or a :class:`~mazesim.RobotProfile`); None: the world's.

        Raises:
            InvalidArgumentError: ``seconds`` is not a positive number.
        """
        if seconds is not None and not (math.isfinite(seconds) and seconds > 0.0):
            raise InvalidArgumentError(
                f"expected a positive number of seconds, found {_shown(seconds)}"
            )
        self.world = world
        self.report: dict[str, Any] = dict(report or {})
        self.keys = keys if keys is not None else KeyScript([])
        self.scene = scene or Scene()
        self.supervisor = supervisor or self.scene.supervisor
        self.noise = noise
        self.seed = seed
        self.quit_status: int | None = None
        self.owns_world = simulator is None
        # The robot node's own sensors; when another process owns the world, it simulates
        # them and says what of them is not used.
        own = own_sensors(robot_profile_name(report), scene)
        self.sensor_tables: dict[str, list[Row]] = own.tables
        self.sensor_types: dict[str, str] = own.types
        if simulator is None:
            for warning in own.warnings:
                print(f"mazesim: warning: {warning}", file=sys.stderr)
        self.simulator = (
            Simulator(
                world,
                robot=robot_profile(report, scene, own) if robot is None else robot,
                seed=seed,
                noise=noise,
            )
            if simulator is None
            else simulator
        )
        self.radio = Radio() if radio is None else radio
        # The wheels' traction; in a world of several robots the world's process applies it
        # (:class:`mazesim.webots.lockstep.WorldTraction`).
        self.traction: Traction | None = None
        if self.scene.traction_version is not None and self.owns_world:
            robot = self.simulator.robot
            self.traction = epuck_traction(
                self.scene.traction_version,
                float(robot.wheel_radius),
                float(robot.axle_length),
                float(robot.max_wheel_speed),
            )
        self.robot_index = robot_index
        self.fleet = fleet
        self.solids: Any = None
        self.scene_edits: Any = None
        self.world_over = False
        self.velocity = (0.0, 0.0, 0.0)
        self.acceleration = (0.0, 0.0)
        self.basic_time_step_ms = float(self.simulator.control_step_ms)
        self.step_limit = (
            None
            if seconds is None
            else max(1, math.ceil(seconds * 1000.0 / self.basic_time_step_ms - 1e-9))
        )
        self.steps = 0
        self.ended = False
        self.ended_at: float | None = None
        self.stopped = False
        x, y, _ = self.simulator.pose
        self.xs: list[float] = [x]
        self.ys: list[float] = [y]
        self.longest_stop_steps = 0
        self._stop_steps = 0
        self._yaw = float(self.simulator.pose[2])
        self._distance: npt.NDArray[np.float32] | None = None
        self._ground: npt.NDArray[np.float32] | None = None
        #: The world's last reset (a supervisor's ``simulationReset``) this robot knows of: in
        #: a world run, the world's last one when the controller starts (a controller started
        #: after a reset, restarted or of a robot imported, does not reset its devices for it).
        self.last_reset: WorldReset = (
            WorldReset() if fleet is None else fleet.last_reset(robot_index)
        )
        self.reset_listeners: list[Callable[[], None]] = []
        #: The wheels' motors of the robot the controller made (left first), whose commands
        #: go on driving the wheels after its end in a world run.
        self.wheel_motors: list[Any] = []
        #: Whether a supervisor of this run of one robot asked for a reset, which the next step
        #: applies at its end.
        self._reset_asked = False
        self.paused = False
        #: The lights where they stood at a step (:meth:`lights_now`), by its number and the
        #: count of light edits then.
        self._lights_now: tuple[tuple[int, int], list[Light] | None] | None = None
        #: The lights with the fields supervisors set, by the count of edits they hold.
        self._lights_set: tuple[int, list[Light] | None] | None = None

    @property
    def own_robot(self) -> Mapping[str, Any]:
        """The import report's entry of the run's robot (its ``robots`` entry on
        ``robot_line``), empty without one."""
        line = self.report.get("robot_line")
        robots = self.report.get("robots") or []
        return next((r for r in robots if isinstance(r, Mapping) and r.get("line") == line), {})

    @property
    def robot_name(self) -> str:
        """What Webots calls the run's robot: its node's ``name`` once the project's PROTOs are
        expanded (a project robot PROTO's declared default when the instance writes none),
        else as :func:`~mazesim.webots.proto_fields.robot_label` calls it (its node type's
        default, the E-puck's "e-puck", a Robot's "robot"; another PROTO robot's DEF name or
        model, never "e-puck"), else the scene's."""
        from mazesim.webots.proto_fields import robot_label

        own = self.own_robot
        return str(own.get("name") or (robot_label(own) if own else self.scene.robot_name))

    @property
    def time_is_up(self) -> bool:
        """Whether the time limit has been reached."""
        return self.world_over or (self.step_limit is not None and self.steps >= self.step_limit)

    def advance(self, left: float, right: float) -> None:
        """Runs one basic time step with these wheel speeds (rad/s), after showing the
        observers (:func:`observing_steps`) the state before it."""
        for observer in _observers:
            observer(self, left, right)
        if self.traction is not None:
            left, right = self.traction.drive(left, right, self.basic_time_step_ms / 1000.0)
        holds = getattr(self.simulator, "hold_wheel_commands", None)
        if holds is not None and self.wheel_motors:
            # The world's process keeps the commands this step sends, which drive the wheels
            # should the controller die without a word (Webots' motor node keeps them).
            angles = self.wheel_angles()
            holds(tuple(m._last_command(a) for m, a in zip(self.wheel_motors, angles)))
        if self.simulator.step(left, right) is True:
            self.world_over = True
            return
        if self.owns_world:
            # Packets arrive where the robots stand after the step (see mazesim.webots.radio).
            self.radio.transmit({self.robot_index: self.simulator.pose})
        self.steps += 1
        resets = self.last_reset.count
        if self.fleet is not None:
            # A robot of a world run learns of a supervisor's reset with the step's answer.
            told: WorldReset | None = getattr(self.simulator, "last_reset", None)
            if told is not None and told.count > self.last_reset.count:
                self.last_reset = told
        elif self._reset_asked:
            self._reset_asked = False
            self._reset_world()
        self._distance = None
        self._ground = None
        x, y, yaw = self.simulator.pose
        moved = math.hypot(x - self.xs[-1], y - self.ys[-1])
        dt = self.basic_time_step_ms / 1000.0
        vx, vy = (x - self.xs[-1]) / dt, (y - self.ys[-1]) / dt
        turned = math.remainder(yaw - self._yaw, math.tau)
        previous = self.velocity
        self.velocity = (vx, vy, turned / dt)
        self.acceleration = ((vx - previous[0]) / dt, (vy - previous[1]) / dt)
        self._yaw = yaw
        self.xs.append(x)
        self.ys.append(y)
        self._stop_steps = self._stop_steps + 1 if moved < STOP_DISPLACEMENT else 0
        self.longest_stop_steps = max(self.longest_stop_steps, self._stop_steps)
        if self.last_reset.count != resets:
            self._at_rest(x, y, yaw)
            for listener in self.reset_listeners:
                listener()

    @property
    def time(self) -> float:
        """Simulated seconds since the start (what the run's summary and time limit count)."""
        return float(self.simulator.time)

    @property
    def clock(self) -> float:
        """Simulated seconds since the start, or since the world's last reset, as Webots'
        ``Robot.getTime`` counts them."""
        return self.time - self.last_reset.time

    def move_robot(self, x: float, y: float, yaw: float) -> None:
        """Puts the robot at a new pose at rest (a supervisor's ``setSFVec3f`` / ``setSFRotation``).

        The trajectory's latest point becomes the new pose; the move is not counted as
        distance travelled.
        """
        # Webots' physics pushes a body set into a wall out of it at the next steps.
        x, y = self.simulator.set_pose_pushed_out(x, y, yaw)
        self._at_rest(x, y, yaw)

    def request_reset(self) -> None:
        """Asks for the world to be put back as its file has it (a supervisor's
        ``simulationReset``); as in Webots, the next step applies it at its end (in a world with
        several robots, the world's process, for every robot at once): every robot at its
        start, the walls a supervisor moved where the file has them and every movable body at
        its start, all at rest, the noise streams started again from their seeds. The clock
        (:attr:`clock`) and the wheels' positions start again, the radio's packets are dropped
        and :attr:`reset_listeners` are called (the devices' own restarts); the run's counters,
        its time limit and the trajectory go on; the move is not counted as distance
        travelled."""
        if self.fleet is not None:
            self.fleet.request_reset()
        else:
            self._reset_asked = True

    def _reset_world(self) -> None:
        """The reset of a run of one robot, at the end of the step after the request."""
        self.simulator.reset_scene()
        self.radio.clear()
        if self.solids is not None:
            self.solids.forget_moves()
        if self.scene_edits is not None:  # Webots' reset takes a supervisor's imports out
            self.scene_edits.take_out_imports()
        left, right = (float(v) for v in self.simulator.wheel_turns)
        self.last_reset = WorldReset(self.last_reset.count + 1, self.time, (left, right))

    def _at_rest(self, x: float, y: float, yaw: float) -> None:
        """Notes that the robot was put at (x, y, yaw) at rest: the trajectory's latest point
        is there, the wheels' traction, velocity and sensor readings start again."""
        if self.traction is not None:
            self.traction.stop()
        self._distance = None
        self._ground = None
        self.velocity = (0.0, 0.0, 0.0)
        self.acceleration = (0.0, 0.0)
        self._yaw = yaw
        self.xs[-1] = x
        self.ys[-1] = y

    def lights_now(self) -> list[Light] | None:
        """The world's lights where they are now (:attr:`Scene.lights`): one a robot holds
        moves with it (:func:`~mazesim.webots.lights.carried`), where this robot stands, or
        another robot of a world run where the world's last step left it; a robot this run
        does not simulate holds its lights where the world file puts it. A light's fields
        are those a supervisor set, if it did (:meth:`_lights_with_edits`)."""
        changes = self._light_changes()
        lights = self._lights_with_edits(changes)
        if not lights or all(light.carrier is None for light in lights):
            return lights
        if self._lights_now is not None and self._lights_now[0] == (self.steps, changes):
            return self._lights_now[1]
        starts = {int(r["line"]): r for r in self.report.get("robots") or [] if r.get("line")}
        # A robot of a world run: the others stand where the world's process has them.
        robots = self.fleet.robots() if self.fleet is not None else []
        index_of = {int(r["line"]): int(r["index"]) for r in robots if r.get("line")}
        poses: dict[int, Any] = {}
        moved = []
        for light in lights:
            start = starts.get(light.carrier) if light.carrier is not None else None
            if start is None or light.carrier is None:
                moved.append(light)
                continue
            if light.carrier not in poses:
                if light.carrier == self.report.get("robot_line"):
                    poses[light.carrier] = self.simulator.pose
                elif self.fleet is not None and light.carrier in index_of:
                    poses[light.carrier] = self.fleet.pose(index_of[light.carrier])
                else:
                    poses[light.carrier] = start["pose"]
            moved.append(carried(light, start["pose"], poses[light.carrier]))
        self._lights_now = ((self.steps, changes), moved)
        return moved

    def _light_changes(self) -> int:
        """How many times a supervisor has set a light's field in this run (or a reset undid
        the edits): in a world run as the last step's answer told it, else as this run's
        :class:`~mazesim.webots.solids.WorldSolids` counts them."""
        if self.fleet is not None:
            return int(getattr(self.simulator, "light_changes", 0))
        return int(self.solids.light_changes) if self.solids is not None else 0

    def _lights_with_edits(self, changes: int) -> list[Light] | None:
        """The world's lights with the fields supervisors set (``changes`` edits so far; none:
        the world file's), made again only after an edit."""
        if changes == 0:
            return self.scene.lights
        if self._lights_set is None or self._lights_set[0] != changes:
            edits = world_objects(self).light_edits()
            self._lights_set = (changes, lit(self.scene.light_sources, self.scene.nue, edits))
        return self._lights_set[1]

    def wheel_angles(self) -> tuple[float, float]:
        """The left and right wheel joints' positions (rad) as they are, unrounded (what
        Webots' motors control and its position sensors round to their ``resolution``): where
        the world file left them (:attr:`Scene.wheel_positions`, 0 in a fresh world) plus the
        turns since the start or the world's last reset."""
        turns = zip(self.scene.wheel_positions, self.simulator.wheel_turns, self.last_reset.turns)
        left, right = (start + (float(turned) - before) for start, turned, before in turns)
        return left, right

    def distance_readings(self) -> npt.NDArray[np.float32]:
        """The proximity readings ps0..ps7 after the last step."""
        if self._distance is None:
            self._distance = self.simulator.distance_sensors()
        return self._distance

    def ground_readings(self) -> npt.NDArray[np.float32]:
        """The ground readings gs0..gs2 after the last step."""
        if self._ground is None:
            self._ground = self.simulator.ground_sensors()
        return self._ground


_current: RobotSimulation | None = None

#: Called before every step of every simulation with the wheel speeds of the step.
StepObserver = Callable[[RobotSimulation, float, float], None]
_observers: list[StepObserver] = []


@contextmanager
def observing_steps(observer: StepObserver) -> Iterator[None]:
    """Calls ``observer(simulation, left, right)`` before every step taken inside the block (to
    record a run or show it live)."""
    _observers.append(observer)
    try:
        yield
    finally:
        _observers.remove(observer)


def prepare(world: World, **settings: Any) -> RobotSimulation:
    """Makes the simulation that the next ``controller.Robot()`` drives, replacing any earlier
    one: ``RobotSimulation(world, **settings)`` (the settings are :class:`RobotSimulation`'s)."""
    global _current
    _current = RobotSimulation(world, **settings)
    return _current


def current() -> RobotSimulation:
    """The prepared simulation.

    Raises:
        InvalidArgumentError: No simulation was prepared.
    """
    if _current is None:
        raise InvalidArgumentError(
            "no simulation to attach the controller to: run it with "
            "'mazesim webots run CONTROLLER.py', or call "
            "mazesim.webots.prepare(world) before creating the Robot"
        )
    return _current


def release() -> None:
    """Forgets the prepared simulation."""
    global _current
    _current = None
