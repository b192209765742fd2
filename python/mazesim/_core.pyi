"""Type stubs for the compiled core of mazesim (``mazesim._core``)."""

import os
from collections.abc import Sequence
from typing import Any, ClassVar, Literal, final

import numpy as np
import numpy.typing as npt

__all__ = [
    "EPUCK_DEFAULT_CONTROLLER",
    "ROBOT_REFLECTANCE",
    "AvoidCollisionSettings",
    "BatchSimulator",
    "DrivePerturbation",
    "EpisodeLimits",
    "LowerRoundSettings",
    "MazeLayout",
    "Navigator",
    "RobotProfile",
    "RunSettings",
    "SensingPerturbation",
    "Simulator",
    "StepBounds",
    "TabularSettings",
    "TaskFeatures",
    "World",
    "__version__",
    "_panic_for_tests",
    "_temporary_writing",
    "builtin_world_names",
    "default_codes",
    "file_kind",
    "generate_maze",
    "import_wbt",
    "import_wbt_text",
    "lower_level_states",
    "q_batch_update",
    "robot_profile_names",
    "sharp_distances",
    "sharp_volts_to_cm",
    "train_lower_round",
    "validate_codes",
]
__version__: str
#: The controller the E-puck PROTO runs when its node leaves ``controller`` out (its declared
#: default from Webots V8.5 to R2025a).
EPUCK_DEFAULT_CONTROLLER: str
#: The infra-red reflection factor of another robot's body as a robot's rays meet it (0.38: the
#: E-puck PROTO's shell through Webots' infra-red model).
ROBOT_REFLECTANCE: float

def builtin_world_names() -> list[str]:
    """Names of the worlds embedded in the package."""

def robot_profile_names() -> list[str]:
    """Names of the robot profiles embedded in the package."""

def sharp_volts_to_cm(volts: float) -> float:
    """Converts a Sharp GP2Y0A41SK0F reading in volts to a distance in cm (inverted table); NaN,
    infinite or negative volts raise InvalidArgumentError."""

def train_lower_round(
    crews: Sequence[dict[str, Any]],
    settings: LowerRoundSettings,
    starts: dict[str, npt.NDArray[Any]],
    explore: npt.NDArray[np.float64],
    random_action: npt.NDArray[np.int64],
    q: npt.NDArray[np.float64],
    visits: npt.NDArray[np.int64],
) -> dict[str, Any]:
    """One round of the lower level's Q-learning in the core, as
    ``mazesim.learn.lower.LowerTrainer`` runs it. Its N robots are in ``crews``, each a dict of a
    ``BatchSimulator`` (``simulator``) of one robot per environment, its four buffers
    (``observations``, ``poses``, ``colliding``, ``crossings``), its ``world_of_env``, the
    (12, 2) float32 ``wheel_speeds`` of the actions, its robots' numbers in the round
    (``members``, int64, increasing) and, for robots that do not read the seed robot's six volts,
    ``readings``: the map into them as data (``mazesim.transfer.readings.SeedReadings.tables``).
    ``explore`` ((steps, N) uniforms) and ``random_action`` ((steps, N)) are the exploration
    draws, ``starts`` each robot's (N, K) queue of episode starts (``world``, ``pose``
    (N, K, 3), ``seed`` uint64, ``path`` (N, K, 9)); ``q`` and ``visits`` ((4, 12288, 12), or
    (4, 73728, 12) with ``settings["phases"] == "heading_and_distance"``) and each crew's
    ``world_of_env`` are updated in place; each decision and its left-right mirror image (the
    core's) teach them. The rest of the round (its worlds, each robot's sub-task, the learning's
    numbers) is ``settings``'s; its numbers may name the door sub-tasks' ``phases``
    (``"heading"``, the default, or ``"heading_and_distance"``) and the ``blind`` rule of
    Corridors and Corners where no sensor sees a wall (``"table"``, the default, ``"forward"`` or
    ``"hold_heading"``). Returns the round's counts (``success``,
    ``failure``, ``cut`` per sub-task, ``corridor_metres``, ``contact_steps``). The GIL is
    released while it runs."""

def q_batch_update(
    q: npt.NDArray[np.float64],
    visits: npt.NDArray[np.int64],
    transitions: dict[str, npt.NDArray[Any]],
    allowed: npt.NDArray[np.bool_],
    rate: tuple[float, float, float],
) -> None:
    """N Q-learning updates of one (states, actions) table in place
    (``mazesim.learn.qlearning.batch_update``): ``transitions`` holds the N ``states``,
    ``actions``, ``rewards`` (float64), ``next_states`` and ``bootstrap`` factors (float64);
    targets read the table before the call, the updates apply in order, each at
    ``max(floor, initial * (visits + 1) ** -power)`` with ``rate = (initial, floor, power)``."""

def lower_level_states(observations: npt.NDArray[np.float32]) -> npt.NDArray[np.int64]:
    """The lower level's state (Table 4.1 levels of the first six distance readings, in volts)
    of each row of an (N, W >= 6) float32 array: what ``BatchSimulator.run``'s tabular
    controller acts on (``mazesim.learn.discretise.observation_states`` calls it). A reading below
    0 V is refused with :class:`~mazesim.InvalidArgumentError`."""

def sharp_distances(
    readings: npt.NDArray[np.float64], in_cm: bool = False
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
    """The distances in cm and the Table 4.1 levels of an (N,) float64 array of Sharp readings
    in volts (or, with ``in_cm``, of distances in cm), by the core's discretiser
    (``mazesim.learn.discretise.distances_and_levels`` calls it). A reading below 0 V, infinite
    or not a number (a distance below 0 cm or not a number) is refused with
    :class:`~mazesim.InvalidArgumentError`."""

def _panic_for_tests(message: str, on_helper_thread: bool = False) -> None:
    """Panics inside the core (only the tests of the panic guard call it)."""

def _temporary_writing(name: str, writing: bool | None = None) -> bool:
    """Whether this process is writing the temporary file ``name`` (a file name) now, after
    marking it as being written or no longer when ``writing`` is given: the one set of writes in
    progress of ``mazesim._atomic``'s writer and the core's."""

def generate_maze(
    width: int = 5,
    height: int = 5,
    seed: int = 0,
    *,
    loops: float = 0.0,
    junction: bool = True,
    layout: MazeLayout | None = None,
) -> World:
    """A seeded maze: perfect (loops=0) or with a share of extra openings, a barcode checkpoint on
    every way into its junctions (while the 12 codes last), the goal in the cell farthest from
    the start. A draw that is one single corridor (no junction, so no checkpoint) is replaced by
    the next draw of the seed, so every maze larger than 2 x 2 has checkpoints; junction=False
    keeps the first draw (the mazes the shipped navigator trained and was measured on). The
    cells' and walls' sizes, the floor and the barcodes are ``layout``'s (the defaults of
    :class:`MazeLayout` when None)."""

def default_codes() -> list[str]:
    """The default five-bit barcode book (12 codes)."""

def validate_codes(codes: list[str]) -> None:
    """Raises InvalidArgumentError for a palindrome, a duplicate or a reverse clash."""

def file_kind(text: str) -> tuple[str, str] | None:
    """What kind of mazesim file ``text`` is, from its first lines: its name with its article
    (``"a mazesim world file"``) and where such a file is taken, or None when it is none of
    mazesim's kinds."""

def import_wbt(
    path: str | os.PathLike[str],
    floor_images: dict[str, npt.NDArray[np.float64]] | None = None,
    controller: str | None = None,
    robot_line: int | None = None,
    wall_colours: dict[str, tuple[float, float, float]] | None = None,
) -> tuple[World, dict[str, Any]]:
    """Imports a Webots .wbt file: the mazesim World and the import report (obstacles, robot,
    basic_time_step_ms, warnings, one_controller_warnings (those of a run of one controller
    only), robot_model, robot_line, robot_profile, robots (every robot:
    pose, model, profile, controller, name, def_name, line, y_up, node_type, model_field),
    extension_devices,
    missing_devices (the e-puck's own devices the robot's node lacks), floor_textures,
    wall_textures (urls, owner, red, colour, roughness, candidates),
    floor_paint). `floor_images` maps texture files to (height, width) grey levels in [0, 1];
    `wall_colours` maps wall texture files to their images' mean (red, green, blue) in [0, 1];
    of several e-pucks, the first whose `controller` field is `controller` is the robot;
    `robot_line` picks the robot (an e-puck or not) on that line of the file."""

def import_wbt_text(
    text: str,
    source: str = "<string>",
    floor_images: dict[str, npt.NDArray[np.float64]] | None = None,
    controller: str | None = None,
    robot_line: int | None = None,
    imported_from: int | None = None,
    wall_colours: dict[str, tuple[float, float, float]] | None = None,
) -> tuple[World, dict[str, Any]]:
    """Imports the text of a .wbt file; `source` names it in error messages and names the world,
    and floor textures are looked for beside it."""

@final
class World:
    """A maze world: walls, floor paint, checkpoints, goal and start pose."""

    @staticmethod
    def builtin(name: str) -> World: ...
    @staticmethod
    def load(path: str) -> World: ...
    @staticmethod
    def from_toml(text: str, source: str = "<string>") -> World: ...
    def to_toml(self) -> str: ...
    def save(self, path: str) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def basic_time_step_ms(self) -> float: ...
    @property
    def bounds(self) -> tuple[float, float, float, float]:
        """(xmin, ymin, xmax, ymax) of walls, paint and start."""
    @property
    def start(self) -> tuple[float, float, float]: ...
    @property
    def robots(self) -> list[dict[str, Any]]:
        """The robots the world places, in order: dicts of "name", "start" (x, y, yaw) and
        "profile" (a built-in profile's name, or None for the simulator's)."""
    @property
    def goal(self) -> tuple[float, float, float] | None:
        """(x, y, radius) of the goal disc, or None."""
    def wall_boxes(self) -> npt.NDArray[np.float64]:
        """(N, 6) array: cx, cy, sx, sy, yaw, reflectance of every wall box (the sensed-only
        walls are ``sensed_wall_boxes``)."""
    def wall_colours(self) -> npt.NDArray[np.float64]:
        """(N, 3) array: red, green, blue in [0, 1] of every wall box as a camera sees it, in
        the order of ``wall_boxes``; NaN for a wall that gives no colour (drawn in the grey of
        its reflectance)."""
    def wall_tops(self) -> npt.NDArray[np.float64]:
        """(N,) array: how high the top of every wall box stands above the floor (m), in the
        order of ``wall_boxes``; inf for a wall that gives no height (higher than any sensor's
        ray)."""
    def sensed_wall_tops(self) -> npt.NDArray[np.float64]:
        """(N,) array as ``wall_tops`` of the sensed-only walls, in the order of
        ``sensed_wall_boxes``."""
    def sensed_wall_boxes(self) -> npt.NDArray[np.float64]:
        """(N, 6) array as ``wall_boxes`` of the sensed-only walls (``sensed_only = true``: seen
        by infra-red rays and cameras, met by nothing else), in ``[[walls]]`` order; (0, 6) when
        none."""
    def sensed_wall_colours(self) -> npt.NDArray[np.float64]:
        """(N, 3) array as ``wall_colours`` of the sensed-only walls, in the order of
        ``sensed_wall_boxes``."""
    def paint_regions(self) -> list[dict[str, object]]:
        """Floor paint in drawing order; each a dict with "shape" ("rect" | "circle" | "capsule"),
        its geometry ("center", "size", "yaw" | "center", "radius" | "a", "b", "radius"),
        "reflectance" and "colour" ((red, green, blue) in [0, 1] as a camera sees it, or None
        for the grey of its reflectance). Barcode bars are included as rects."""
    def bodies(self) -> list[dict[str, object]]:
        """Each movable body at its start pose as a dict: "shape" ("box" with "size" and
        "yaw", or "circle" with "radius"), "center", "mass", "friction", "reflectance"."""
    def checkpoints(self) -> list[dict[str, object]]:
        """Each checkpoint as a dict: "id", "code", "center", "yaw", "width"."""
    def junction_checkpoints(self) -> str:
        """The [[checkpoints]] tables generate_maze would place on this world's [grid] maze, one
        on every way into every junction, as world-file text to paste into a maze drawn by hand
        (after the grey [floor] of generated mazes when the world has no [floor]); "" when the
        world has no grid or its maze no junction."""
    def cell_maze(self) -> dict[str, object] | None:
        """The cell maze of a [grid] world: rows, cols, cell_size, origin, horizontal
        ((rows + 1, cols) bool), vertical ((rows, cols + 1) bool), start and goal cells."""
    def distance_targets(self, goal_cell: int) -> npt.NDArray[np.float64]:
        """(rows * cols, 5): the goal-distance table's interpolation targets of every cell
        towards the cell ``goal_cell`` (its row-major index)."""
    def connected_cells(self) -> npt.NDArray[np.int64]:
        """(n, 2): the (row, column) cells of the largest set of cells joined by open sides."""
    @property
    def floor_background(self) -> float:
        """Background floor reflectance (where nothing is painted)."""
    @property
    def floor_colour(self) -> tuple[float, float, float] | None:
        """The bare floor's colour as a camera sees it, (red, green, blue) in [0, 1], or None
        (the grey of its reflectance)."""
    def floor_reflectance(self, x: float, y: float) -> float: ...
    def with_paint_moved(
        self, paint: Sequence[int], from_pose: Sequence[float], to_pose: Sequence[float]
    ) -> World:
        """This world with the ``[[paint]]`` entries ``paint`` moved by the rigid motion taking
        ``from_pose`` (x, y, yaw) to ``to_pose``, as a supervisor moves a floor mark's node.

        Raises:
            InvalidArgumentError: An index past the paint, or paint moved beyond the limits.
        """
    def __reduce__(self) -> tuple[Any, tuple[str, str]]:
        """Pickles as its world file text and source name."""
    def __copy__(self) -> World:
        """A world is immutable: a copy is the world itself."""
    def __deepcopy__(self, memo: dict[int, Any], /) -> World: ...
    def __eq__(self, other: object, /) -> bool: ...
    __hash__: ClassVar[None]  # type: ignore[assignment]

@final
class RobotProfile:
    """A robot's body, wheels and sensors, loaded from the embedded profile files or TOML text,
    and how one real robot may differ from them (see ``docs/perturbations.md``)."""

    @staticmethod
    def builtin(name: str) -> RobotProfile: ...
    @staticmethod
    def load(name_or_path: str | os.PathLike[str]) -> RobotProfile:
        """A built-in profile by name, or a profile file by path (a copy of a built-in profile's
        `to_toml()` text, edited); the `robot` argument of the simulators and environments, and
        the `--robot` option of the commands, take the same."""
    @staticmethod
    def from_toml(text: str, source: str = "<string>") -> RobotProfile:
        """Parses a profile file's text; ``source`` names it in error messages."""
    def to_toml(self) -> str:
        """The profile as the TOML text of a profile file (``from_toml`` reads it back)."""
    def with_infrared_elevation(self, elevation: float) -> RobotProfile:
        """A copy of the profile whose distance sensors' rays rise `elevation` radians above the
        floor's plane (0 to pi/3): a wall at horizontal distance `h` reads as `h / cos(elevation)`
        away, and a ray reaches `cos(elevation)` of its length across the floor. Webots' E-puck
        PROTO tilts its proximity sensors by 0.16 rad."""
    def distance_sensor_elevations(self) -> list[float]:
        """Each distance sensor's ray elevation above the floor's plane, radians (0: level)."""
    def perturbed(
        self,
        drive: DrivePerturbation | None = None,
        sensing: SensingPerturbation | None = None,
    ) -> RobotProfile:
        """A copy of the profile as a real robot may differ from it, named ``"<name>~perturbed"``:
        its drive perturbed as ``drive`` says and its senses as ``sensing`` says (neutral when
        None). Neutral perturbations simulate exactly as this profile. An ``ir_offset_error``
        beyond this profile's body radius raises InvalidArgumentError naming it.
        """
    @property
    def name(self) -> str: ...
    @property
    def description(self) -> str: ...
    def __reduce__(self) -> tuple[Any, tuple[str, ...]]:
        """Pickles as its built-in name when it is that built-in profile, otherwise as its TOML
        text."""
    def __copy__(self) -> RobotProfile:
        """A profile is immutable: a copy is the profile itself."""
    def __deepcopy__(self, memo: dict[int, Any], /) -> RobotProfile: ...
    def __eq__(self, other: object, /) -> bool:
        """Equal when they hold the same values, wherever they were loaded from."""
    def __hash__(self) -> int: ...
    @property
    def body_radius(self) -> float: ...
    @property
    def wheel_radius(self) -> float: ...
    @property
    def axle_length(self) -> float: ...
    @property
    def max_wheel_speed(self) -> float: ...
    @property
    def encoder_resolution(self) -> float: ...
    @property
    def motor_gains(self) -> tuple[float, float]:
        """Gains (left, right) of the motors: each wheel turns at its gain times the command."""
    @property
    def noise_scale(self) -> float:
        """Multiplies every sensor model's relative noise."""
    @property
    def wall_reflectance(self) -> float:
        """Reflection factor of the walls as the infra-red sensors see them (1 = as the world has
        them)."""
    @property
    def ground_gain(self) -> float:
        """Multiplies every ground sensor reading."""
    @property
    def slip_on_contact(self) -> float:
        """Fraction of the wheels' motion lost while the body touches a wall."""
    @property
    def distance_sensor_names(self) -> list[str]: ...
    @property
    def distance_sensor_unit(self) -> str:
        """Unit of the readings: "raw" (e-puck counts) or "volts" (Sharp)."""
    @property
    def distance_sensor_max(self) -> float:
        """Largest noise-free reading of any distance sensor (its table's largest output)."""
    @property
    def distance_sensor_range(self) -> float:
        """Range of the distance sensors in metres (the longest table's last input)."""
    @property
    def ground_sensor_max(self) -> float:
        """Largest noise-free reading of any ground sensor (its table's largest output)."""
    @property
    def ground_sensor_names(self) -> list[str]: ...
    def distance_sensor_poses(self) -> npt.NDArray[np.float64]:
        """(N, 3) array: x, y, heading of each distance sensor in the robot frame."""
    def distance_sensor_limits(self) -> npt.NDArray[np.float64]:
        """(N, 2) array: nearest and farthest distance in metres of each distance sensor's table."""
    def distance_sensor_table(self, index: int) -> npt.NDArray[np.float64]:
        """(K, 3) array: distance sensor ``index``'s table, rows of distance in metres, noise-free
        reading off a white wall and relative noise."""
    def distance_from_reading(self, index: int, reading: float) -> float:
        """Distance in metres at which distance sensor ``index`` reads ``reading`` off a white
        wall (its table inverted, clamped to the table's distances)."""
    def ground_reading(self, index: int, reflectance: float) -> float:
        """Noise-free reading of ground sensor ``index`` over a floor of reflectance factor f."""
    def ground_sensor_positions(self) -> npt.NDArray[np.float64]:
        """(N, 2) array: x, y of each ground sensor in the robot frame."""

@final
class Simulator:
    """The robots of one world (one in most worlds), stepped in control steps. Per-robot calls
    take a robot index, robot 0 by default; properties are robot 0's (see `robot_state`)."""

    def __new__(
        cls,
        world: World,
        robot: str | RobotProfile = "e-puck",
        seed: int = 0,
        noise: bool = True,
        control_step_ms: float | None = None,
        *,
        robot_profiles: Sequence[str | RobotProfile | None] | None = None,
    ) -> Simulator: ...
    def reset(self, seed: int | None = None) -> None: ...
    def step(self, left: float, right: float) -> None:
        """Advances one control step with robot 0's wheel speeds in rad/s (clamped to the motor
        limit); the other robots keep their wheel commands."""
    def step_robots(self, commands: npt.NDArray[np.float64]) -> None:
        """Advances one control step with every robot's wheel speeds: an (R, 2) float64 array."""
    def set_wheel_speeds(self, left: float, right: float, robot_index: int = 0) -> None:
        """Sets robot `robot_index`'s wheel speeds (rad/s) for the next steps, as a Webots
        controller sets its motors' velocities."""
    @property
    def num_robots(self) -> int:
        """Number of robots in the world."""
    @property
    def robot_names(self) -> list[str]:
        """The robots' names, in world order."""
    def poses(self) -> npt.NDArray[np.float32]:
        """Every robot's pose, an (R, 3) float32 array of x, y, yaw."""
    def robot_state(self, robot_index: int = 0) -> dict[str, Any]:
        """Robot `robot`'s state as a dict: pose, colliding, touching_robot, collisions,
        distance_travelled, wheel_speeds, encoders, wheel_turns, wall_clearance, last_crossing,
        goal."""
    def step_observe(
        self,
        left: float,
        right: float,
        low: npt.NDArray[np.float32],
        high: npt.NDArray[np.float32],
    ) -> tuple[npt.NDArray[np.float32], npt.NDArray[np.float32], bool, int, int]:
        """`step`, then what a gym step returns, in one call: the readings (float32, the distance
        sensors then the ground sensors) clamped to [`low`, `high`] (float32 arrays of that
        width), the pose (float32 x, y, yaw), whether the body touches a wall, the signed
        checkpoint crossed in this step (0: none) and the collisions so far (as `collisions`)."""
    def step_task(
        self,
        features: TaskFeatures,
        bounds: StepBounds,
        left: float,
        right: float,
        observe: bool = True,
    ) -> tuple[npt.NDArray[np.float32], npt.NDArray[np.float32], bool, int, int, float, bool]:
        """`step_observe`, then the task observation of environment 0 of `features` (a
        `TaskFeatures` of this robot's sensors) in the same call: the observation from the
        readings clamped to `bounds` (a `StepBounds` of this robot's width), the pose and the
        previous action (`left` and `right` over the bounds' `max_speed`, in float32), in place
        of the readings; then the pose, whether the body touches a wall, the signed checkpoint
        crossed (0: none), the collisions so far, the distance in metres to the features' goal
        and whether the pose is in the goal disc. The same values as `step_observe` followed by
        `features.observe_env(0, ...)`. With `observe=False` the first value is the clamped
        readings themselves, and the features only give the goal's distance (their explored map
        is left as it is)."""
    def set_start(self, x: float, y: float, yaw: float, robot_index: int = 0) -> None:
        """Sets the pose every later reset starts robot `robot_index` from (instead of the
        world's)."""
    def set_goal(self, x: float, y: float, radius: float, robot_index: int = 0) -> None:
        """Sets robot `robot_index`'s goal disc, centre (x, y) and radius in metres, instead of
        the world's."""
    @property
    def goal(self) -> tuple[float, float, float] | None:
        """The goal disc (x, y, radius) the episodes end at (`set_goal`'s, else the world's)."""
    def set_pose(
        self, x: float, y: float, yaw: float, robot_index: int = 0, overlap_robots: bool = False
    ) -> None: ...
    def set_pose_pushed_out(
        self, x: float, y: float, yaw: float, robot_index: int = 0, overlap_robots: bool = False
    ) -> tuple[float, float]:
        """Moves robot ``robot_index`` as :meth:`set_pose` does or, when its body would lie in
        a wall there, to the nearest pose within 5 cm that :meth:`set_pose` accepts, as Webots'
        physics pushes a body out of a wall.

        Returns:
            The (x, y) the robot stands at.

        Raises:
            InvalidArgumentError: The pose is refused and none within 5 cm is clear.
        """
    def distance_sensors(self, robot_index: int = 0) -> npt.NDArray[np.float32]: ...
    def ground_sensors(self, robot_index: int = 0) -> npt.NDArray[np.float32]: ...
    def body_poses(self) -> list[tuple[float, float, float]]:
        """Current poses (x, y, yaw) of the world's movable bodies, in world order."""
    def body_velocities(self) -> list[tuple[float, float, float]]:
        """Current velocities (vx, vy, turn rate) of the world's movable bodies, in world
        order."""
    def move_solid(
        self,
        walls: Sequence[int],
        bodies: Sequence[int],
        from_pose: Sequence[float],
        to_pose: Sequence[float],
        paint: Sequence[int] | None = None,
    ) -> None:
        """Moves the ``[[walls]]`` entries ``walls``, the movable bodies ``bodies`` and the
        ``[[paint]]`` entries ``paint`` (floor marks) by the rigid motion taking ``from_pose``
        (x, y, yaw) to ``to_pose``, bodies at rest; the ground sensors read the paint there.

        Raises:
            InvalidArgumentError: An index past the walls, bodies or paint, or a pose beyond
                the limits; nothing moved.
        """
    def change_world(
        self,
        world: World,
        kept_robots: Sequence[int | None] | None = None,
        robot_profiles: Sequence[str | RobotProfile | None] | None = None,
    ) -> None:
        """Runs on in ``world`` from the next step on, as a Webots supervisor imports nodes into
        the running world or removes some: its walls are met and sensed, every robot keeping its
        pose, velocities, encoders, noise stream, clock and counters; a movable body both worlds
        hold goes on where it is, a new one starts at rest. ``world`` is what ``reset_scene``
        puts back.

        ``kept_robots``, when given, holds one entry per robot of ``world``: the index of the
        running robot it is (which goes on as above), or None for a robot imported now, which
        starts at rest at its world pose on the running clock, with no wheel command, fresh
        counters and a noise stream of its own derived from the seed and its name. The running
        robots it does not name are taken out.

        ``robot_profiles``, given with ``kept_robots``, holds one entry per robot of ``world``:
        a new robot's own profile (a robot node's own sensors, as the constructor's
        ``robot_profiles`` takes them) or None (its placement's profile); a kept robot keeps
        its own, so its entry is None.

        Raises:
            InvalidArgumentError: Without ``kept_robots``, ``world`` holds another number of
                robots, or ``robot_profiles`` is given; with it, an entry per robot of ``world``
                is expected, each running robot at most once, and a profile for new robots
                only; nothing changed.
        """
    def reset_scene(self) -> None:
        """Puts the scene back as the world was made, as a Webots supervisor's
        ``simulationReset`` does: every robot at its start, the walls ``move_solid`` moved where
        the world has them and every movable body at its start, all at rest, and every robot's
        noise stream started again from its seed, as Webots' reset restarts its random seeds.
        Time, counters and wheel commands go on (``reset`` zeroes them)."""
    def set_body_velocity(self, index: int, vx: float, vy: float, turn_rate: float) -> None:
        """Sets the velocity of movable body ``index`` (world order): ``vx``, ``vy`` in m/s and
        ``turn_rate`` in rad/s, as a Webots supervisor's ``Node.setVelocity`` does; the floor's
        friction slows it from the next step on.

        Raises:
            InvalidArgumentError: An index past the bodies, or a speed beyond 10 m/s (a turn
                rate beyond 10,000 rad/s); nothing changed.
        """
    @property
    def pose(self) -> tuple[float, float, float]: ...
    @property
    def time(self) -> float: ...
    @property
    def steps(self) -> int: ...
    @property
    def collisions(self) -> int: ...
    @property
    def colliding(self) -> bool: ...
    @property
    def distance_travelled(self) -> float: ...
    @property
    def wheel_speeds(self) -> tuple[float, float]: ...
    @property
    def encoders(self) -> tuple[float, float]: ...
    @property
    def wheel_turns(self) -> tuple[float, float]:
        """The wheels' rotation (rad) unquantised: ``encoders`` before its rounding to the
        profile's ``encoder_resolution``."""
    @property
    def wall_clearance(self) -> float:
        """Signed gap between the body and the nearest wall in metres (negative: penetration)."""
    @property
    def last_crossing(self) -> int:
        """Barcode crossed in the last step: +id arriving (along its yaw), -id departing, 0 none."""
    def crossings(self, robot_index: int = 0) -> list[dict[str, object]]:
        """Robot `robot`'s crossings since reset: dicts of "checkpoint", "direction", "step",
        "time"."""
    @property
    def control_step_ms(self) -> float: ...
    @property
    def robot(self) -> RobotProfile: ...
    def robot_profile(self, robot_index: int = 0) -> RobotProfile:
        """Robot `robot_index`'s profile itself: a built-in one or the one a profile file gave,
        so a multi-robot world's robots travel with their own profiles, not with a name."""
    @property
    def world(self) -> World: ...
    def snapshot(self) -> bytes:
        """The whole state as bytes, for `restore` (pose, velocities, rapier's contact state, noise
        stream, time, counters, barcode tracker, readings), of every robot of the world with
        their wheel commands."""
    def restore(self, snapshot: bytes) -> None:
        """Puts the simulator in the state of a `snapshot` of a simulator of the same world, robot
        profiles, control step and noise setting; it then goes on exactly as that one would. The
        snapshot is checked against the API's limits; a refused one changes nothing."""
    def __copy__(self) -> Simulator:
        """An independent simulator in the same state, sharing the (immutable) world."""
    def __deepcopy__(self, memo: dict[int, Any], /) -> Simulator: ...
    def __reduce__(self) -> tuple[type[Simulator], tuple[Any, ...], bytes]:
        """Pickles as the constructor's arguments and a snapshot."""
    def __setstate__(self, state: bytes, /) -> None: ...

@final
class BatchSimulator:
    """N independent environments stepped in parallel into caller-owned numpy buffers.

    ``robot`` is a profile name or a RobotProfile for every environment, or a sequence of them,
    one per environment (domain randomisation; every profile with the sensors of the first).
    """

    def __new__(
        cls,
        worlds: World | Sequence[World],
        num_envs: int | None = None,
        robot: str | RobotProfile | Sequence[str | RobotProfile] = "e-puck",
        seeds: int | Sequence[int] | None = None,
        noise: bool = True,
        control_step_ms: float | None = None,
        threads: int = 0,
    ) -> BatchSimulator: ...
    @property
    def num_envs(self) -> int: ...
    @property
    def robots_per_env(self) -> int:
        """Robots per environment: 1, but in a batch of worlds of several robots, whose buffers
        then have a robot axis ((N, R, width), (N, R, 3), (N, R), (N, R); actions (N, R, 2))."""
    @property
    def observation_width(self) -> int: ...
    @property
    def distance_width(self) -> int: ...
    @property
    def ground_width(self) -> int: ...
    def bytes_per_env(self) -> int:
        """Bytes the batch holds per environment: each env's own state, plus each distinct world
        (envs of equal worlds share one copy) and each distinct robot profile's sensing set-up
        counted once."""
    def output_buffers(
        self,
    ) -> tuple[
        npt.NDArray[np.float32],
        npt.NDArray[np.float32],
        npt.NDArray[np.bool_],
        npt.NDArray[np.int32],
    ]:
        """New zeroed output buffers of the shapes and dtypes every call checks, for the caller
        to hold: observations (N, observation_width) float32, poses (N, 3) float32, colliding
        (N,) bool and crossings (N,) int32; with R robots per env, (N, R, ...) each."""
    def step(
        self,
        actions: npt.NDArray[np.float32],
        observations: npt.NDArray[np.float32],
        poses: npt.NDArray[np.float32],
        colliding: npt.NDArray[np.bool_],
        crossings: npt.NDArray[np.int32],
    ) -> None: ...
    def run(
        self,
        steps: int,
        controller: Literal["braitenberg", "avoid-collision", "random"]
        | AvoidCollisionSettings
        | TabularSettings,
        observations: npt.NDArray[np.float32],
        poses: npt.NDArray[np.float32],
        colliding: npt.NDArray[np.bool_],
        crossings: npt.NDArray[np.int32],
        *,
        settings: RunSettings | None = None,
    ) -> dict[str, npt.NDArray[np.uint64]]:
        """Runs ``steps`` control steps of every env in one call, the GIL released, each env's
        wheel speeds chosen in the core by a built-in controller.

        Controllers (each equal, bit for bit, to its Python counterpart on the same readings):
        ``"braitenberg"`` (:func:`mazesim.benchmark.braitenberg` on ps0-7), ``"avoid-collision"``
        or an :class:`AvoidCollisionSettings` (:class:`mazesim.controllers.AvoidCollision` with
        its ``threshold`` and ``max_speed``), a :class:`TabularSettings` (the tabular
        controller over its Q-tables) and ``"random"`` (wheel speeds uniform within the motor
        limit). Env ``i`` draws its random numbers from its own stream seeded with
        ``settings.seeds[i]`` (an int ``s`` gives ``s + i``; ``0..N`` by default).

        An episode ends as ``settings.limits`` (an :class:`EpisodeLimits`) says: after its step
        limit, at the goal, at a crossing; with ``autoreset`` an env is reset at once with the
        seed that follows its last one (SplitMix64); without, it stands still until reset
        (stopped by a crossing: for the rest of the call only).

        The keywords ``run`` took before its settings objects (``seeds``,
        ``max_episode_steps``, ``end_at_goal``, ``end_at_crossing``, ``autoreset``, ``trace``,
        ``table``, ``allowed_actions``, ``table_index``, ``epsilon``, ``threshold``,
        ``max_speed``, ``active``, ``hold_spins``, ``hold_heading``, ``wheel_speed_limit``,
        ``subtasks``) are still read for one release, with a :class:`DeprecationWarning`.

        Args:
            steps: Control steps of every env.
            controller: The built-in controller: its name, or its settings.
            observations: (N, observation_width) float32, the final observations.
            poses: (N, 3) float32, the final poses.
            colliding: (N,) bool, the final step's contact flags.
            crossings: (N,) int32, the final step's barcode crossings.
            settings: The call's episode limits, seeds, active envs, sub-tasks and trace
                (:class:`RunSettings`; its defaults when None).

        Returns:
            (N,) uint64 counters of the call: ``steps``, ``steps_in_contact``,
            ``episodes_finished``, ``goals_reached`` and, with ``settings.subtasks``, the door
            sub-tasks that reached their end (``subtasks_done``) or gave up
            (``subtasks_given_up``).
        """
    def reset(
        self,
        observations: npt.NDArray[np.float32],
        poses: npt.NDArray[np.float32],
        colliding: npt.NDArray[np.bool_],
        crossings: npt.NDArray[np.int32],
        mask: npt.NDArray[np.bool_] | None = None,
        seeds: npt.NDArray[np.uint64] | None = None,
    ) -> None: ...
    def observe(
        self,
        observations: npt.NDArray[np.float32],
        poses: npt.NDArray[np.float32],
        colliding: npt.NDArray[np.bool_],
        crossings: npt.NDArray[np.int32],
    ) -> None: ...
    def snapshot_env(self, index: int) -> bytes:
        """The whole state of environment `index` as bytes (as `Simulator.snapshot`), for
        `restore_env`: what pickling a vector env keeps of each environment; with R robots per
        env, every robot's (as a simulator of the world saves them, wheel commands zero)."""
    def restore_env(self, index: int, snapshot: bytes) -> None:
        """Puts environment `index` in the state of a `snapshot_env` (or `Simulator.snapshot`) of an
        environment of the same world, robot profile, control step and noise setting; with R
        robots per env every robot's (a simulator's kept wheel commands are left)."""
    def set_world(self, index: int, world: World, seed: int) -> None:
        """Puts environment ``index`` into ``world``, reset to its start with ``seed``; its rows of
        the buffers change at the next observe, step or reset. In a batch of worlds of several
        robots the world must place as many robots; each robot keeps its profile."""
    def set_starts(self, starts: npt.NDArray[np.float64]) -> None:
        """Start poses ((N, 3) float64 x, y, yaw) of each env for its later resets; (N, R, 3)
        with R robots per env."""
    def set_starts_at(self, envs: npt.NDArray[np.int64], starts: npt.NDArray[np.float64]) -> None:
        """Start poses ((M, 3) float64 x, y, yaw) of envs ``envs`` for their later resets;
        (M, R, 3) with R robots per env."""
    def set_goals_at(self, envs: npt.NDArray[np.int64], goals: npt.NDArray[np.float64]) -> None:
        """Goal discs ((M, 3) float64 x, y, radius) of envs ``envs``, instead of their worlds';
        (M, R, 3) with R robots per env."""
    def goals(self) -> npt.NDArray[np.float64]:
        """(N, 3) goal disc (x, y, radius) of each env; NaN rows for none; (N, R, 3) with R
        robots per env."""
    def encoders(self) -> npt.NDArray[np.float64]:
        """(N, 2) wheel positions in radians (left, right); (N, R, 2) with R robots per env."""
    def times(self) -> npt.NDArray[np.float64]:
        """(N,) simulated seconds of each env since its reset; (N, R) with R robots per env."""
    def steps(self) -> npt.NDArray[np.uint64]:
        """(N,) control steps of each env since its reset; (N, R) with R robots per env."""
    def collisions(self) -> npt.NDArray[np.uint64]:
        """(N,) bumps of each env since its reset; (N, R) with R robots per env."""
    def distances_travelled(self) -> npt.NDArray[np.float64]:
        """(N,) path length of each env since its reset, metres; (N, R) with R robots per env."""
    def __len__(self) -> int: ...

@final
class EpisodeLimits:
    """How the episodes of a :meth:`BatchSimulator.run` call end, and what follows the end.

    An episode ends after ``max_steps`` control steps since its reset (0: no limit) or, with
    ``end_at_goal``, on the step the robot's centre enters the goal disc, or, with
    ``end_at_crossing``, on a step that crosses a barcode. With ``autoreset`` an ended episode
    is reset at once; without, the env stands still until reset.

    Raises:
        InvalidArgumentError: ``max_steps`` is not an int in ``0..2**64``, or a flag not a bool.
    """

    def __new__(
        cls,
        max_steps: int = 0,
        end_at_goal: bool = False,
        end_at_crossing: bool = False,
        autoreset: bool = True,
    ) -> EpisodeLimits: ...
    @property
    def max_steps(self) -> int:
        """Control steps after which an episode ends (0: no limit)."""
    @property
    def end_at_goal(self) -> bool:
        """Whether an episode ends on the step the robot's centre enters its goal disc."""
    @property
    def end_at_crossing(self) -> bool:
        """Whether an episode ends on a step that crosses a barcode."""
    @property
    def autoreset(self) -> bool:
        """Whether an ended episode is reset at once (else the env stands still until reset)."""
    def __eq__(self, value: object, /) -> bool: ...
    def __hash__(self) -> int: ...

@final
class LowerRoundSettings:
    """What stays the same from round to round of :func:`train_lower_round` but for the
    exploration rate: ``learning``, the learning's numbers (``gamma``, ``epsilon``,
    ``decision_steps``, ``corridor_episode_steps``, ``rate_initial``, ``rate_floor``,
    ``rate_power``, the rewards ``progress_reward``, ``collision_penalty``,
    ``corridor_step_reward``, ``door_step_reward``, ``heading_reward``, ``door_success_reward``,
    ``door_failure_reward``, the door sub-tasks' bounds ``door_path_exit``,
    ``success_past_centre``, ``success_across``, and perhaps their ``phases`` (``"heading"``,
    the default, or ``"heading_and_distance"``) and the ``blind`` rule of Corridors and Corners
    where no sensor sees a wall (``"table"``, the default, ``"forward"`` or ``"hold_heading"``));
    the ``worlds`` the robots' starts index; each robot's sub-task (``role``, (N,) int64) and the
    ``allowed`` actions of each sub-task ((4, 12) bool). The arrays are the
    caller's own, checked when made and again by each round.

    Raises:
        InvalidArgumentError: a number missing, unknown or out of range, a world that is not a
            ``World``, or an array of another shape or type, naming it.
    """

    def __new__(
        cls,
        learning: dict[str, float | str],
        worlds: Sequence[World],
        role: npt.NDArray[np.int64],
        allowed: npt.NDArray[np.bool_],
    ) -> LowerRoundSettings: ...
    @property
    def learning(self) -> dict[str, float | str]:
        """The learning's numbers, as given."""
    @property
    def worlds(self) -> Sequence[World]:
        """The worlds the robots' starts index."""
    @property
    def role(self) -> npt.NDArray[np.int64]:
        """(N,) int64, each robot's sub-task."""
    @property
    def allowed(self) -> npt.NDArray[np.bool_]:
        """(4, 12) bool, the actions each sub-task may take."""

@final
class MazeLayout:
    """How :func:`generate_maze` builds a maze: the side of its cells and the thickness of its
    walls (metres), whether barcode checkpoints are painted on the ways into its junctions, and
    its floor's reflectance (grey, so that codes show their ends).

    Raises:
        InvalidArgumentError: not ``0 < wall_thickness < cell_size`` (finite), a reflectance
            outside (0, 1], or ``checkpoints`` not a bool.
    """

    def __new__(
        cls,
        cell_size: float = 0.25,
        wall_thickness: float = 0.01,
        checkpoints: bool = True,
        floor_reflectance: float = 0.36,
    ) -> MazeLayout: ...
    @property
    def cell_size(self) -> float:
        """Side of a cell, metres."""
    @property
    def wall_thickness(self) -> float:
        """Thickness of a wall, metres (less than the cell's side)."""
    @property
    def checkpoints(self) -> bool:
        """Whether barcode checkpoints are painted on the ways into junctions."""
    @property
    def floor_reflectance(self) -> float:
        """Reflectance of the floor, in (0, 1] (grey, so that codes show their ends)."""
    def __eq__(self, value: object, /) -> bool: ...
    def __hash__(self) -> int: ...

@final
class DrivePerturbation:
    """How a real robot's drive may differ from its profile (:meth:`RobotProfile.perturbed`):
    the wheel radius and the effective wheel distance scaled, the motors' gains (left, right)
    and the share of the wheels' motion lost while the body touches a wall. Scales and gains
    multiply the profile's own; the neutral values change nothing.

    Raises:
        InvalidArgumentError: a scale or gain outside (0, 10] or a slip outside [0, 1) (each
            finite), naming it.
    """

    def __new__(
        cls,
        wheel_radius_scale: float = 1.0,
        axle_length_scale: float = 1.0,
        motor_gains: tuple[float, float] | Sequence[float] = (1.0, 1.0),
        slip_on_contact: float = 0.0,
    ) -> DrivePerturbation: ...
    @property
    def wheel_radius_scale(self) -> float:
        """Multiplies the wheel radius, in (0, 10]."""
    @property
    def axle_length_scale(self) -> float:
        """Multiplies the effective wheel distance, in (0, 10]."""
    @property
    def motor_gains(self) -> tuple[float, float]:
        """Multiply the (left, right) motor gains, each in (0, 10]."""
    @property
    def slip_on_contact(self) -> float:
        """Fraction of the wheels' motion lost while the body touches a wall, in [0, 1)."""
    def __eq__(self, value: object, /) -> bool: ...
    def __hash__(self) -> int: ...

@final
class SensingPerturbation:
    """How a real robot's senses may differ from its profile (:meth:`RobotProfile.perturbed`):
    every sensor's noise scaled, each infra-red sensor turned outward by ``ir_angle_error``
    (radians) and moved along its heading by ``ir_offset_error`` (metres), the walls'
    reflection factor as those sensors see it and every ground reading's gain. The neutral
    values change nothing.

    Raises:
        InvalidArgumentError: a noise scale outside [0, 100], an angle beyond pi either way, a
            reflectance outside (0, 1], a ground gain outside (0, 10] or a value not finite,
            naming it (the offset's bound, the body radius, is checked by ``perturbed``).
    """

    def __new__(
        cls,
        noise_scale: float = 1.0,
        ir_angle_error: float = 0.0,
        ir_offset_error: float = 0.0,
        wall_reflectance: float = 1.0,
        ground_gain: float = 1.0,
    ) -> SensingPerturbation: ...
    @property
    def noise_scale(self) -> float:
        """Multiplies every sensor model's relative noise, in [0, 100]."""
    @property
    def ir_angle_error(self) -> float:
        """Turns every infra-red sensor outward by this many radians (negative: inward)."""
    @property
    def ir_offset_error(self) -> float:
        """Moves every infra-red sensor along its heading by this many metres (negative:
        inward); at most the body radius of the profile it perturbs either way."""
    @property
    def wall_reflectance(self) -> float:
        """Multiplies the walls' reflection factor, in (0, 1]."""
    @property
    def ground_gain(self) -> float:
        """Multiplies every ground sensor reading, in (0, 10]."""
    def __eq__(self, value: object, /) -> bool: ...
    def __hash__(self) -> int: ...

@final
class AvoidCollisionSettings:
    """The avoid-collision controller of the report's Algorithm 1, as
    :meth:`BatchSimulator.run`'s controller: a sensor above ``threshold`` (raw reading) sees an
    obstacle, the wheels turn at fractions of ``max_speed`` (rad/s).

    Raises:
        InvalidArgumentError: ``threshold`` or ``max_speed`` is not a finite real number.
    """

    def __new__(
        cls, threshold: float = 80.0, max_speed: float = 6.28
    ) -> AvoidCollisionSettings: ...
    @property
    def threshold(self) -> float:
        """The raw proximity reading above which a sensor sees an obstacle."""
    @property
    def max_speed(self) -> float:
        """The wheel speed the rule scales, rad/s."""

@final
class TabularSettings:
    """The tabular controller, as :meth:`BatchSimulator.run`'s controller: greedy over
    ``table``, a float64 ``(4096, 12)`` Q-table or ``(tables, 4096, 12)`` tables with env ``i``
    acting from ``table[table_index[i]]``, on the Table 4.1 state of the first six distance
    sensors; ties go to the first maximum; only ``allowed_actions`` (``(12,)`` or
    ``(tables, 12)`` bool) are taken; with probability ``epsilon`` a uniformly random allowed
    action. The tables are copied when the settings are made.

    With ``RunSettings.subtasks`` it takes ``table`` as the 12 stacked tables of the
    sub-tasks' phases ``(12, 4096, 12)`` (no ``table_index``) and acts from table
    ``3 * subtask + phase``, or as the 72 of a tracker that counts the distance
    (``door_distance``, ``(72, 4096, 12)``) and acts from table ``18 * subtask + phase``.

    Args:
        table: The Q-table(s).
        allowed_actions: The actions the controller may take (all when None).
        table_index: (N,) int64, the table of each env (table 0 for all when None).
        epsilon: The exploration rate in [0, 1].
        hold_spins: Keep turning on the spot the way an env's last step turned (action ``aa``
            or ``bb``, read from its wheel speeds) rather than turn back
            (as :class:`Navigator` does); with sub-tasks, in Corridors and Corners
            only.
        hold_heading: With sub-tasks, Corridors and Corners in the blind state (no sensor sees
            a wall) holds its heading on the grid as :class:`Navigator` does (the last step's
            turn on the spot read from its wheel speeds), after ``hold_spins``.
        wheel_speed_limit: Drive every env at the fractions of this motor limit (rad/s,
            clamped to each robot's own by its step), as
            :meth:`mazesim.batch.RobotBatch.speeds_of` does for a batch; each robot's own limit
            when None.

    Raises:
        InvalidArgumentError: A table of another shape or dtype or with a value that is not
            finite, allowed actions of another shape or allowing none, a table index out of
            range, an epsilon outside [0, 1], a limit not above 0.
    """

    def __new__(
        cls,
        table: npt.NDArray[np.float64],
        allowed_actions: npt.NDArray[np.bool_] | None = None,
        table_index: npt.NDArray[np.int64] | None = None,
        epsilon: float = 0.0,
        hold_spins: bool = False,
        hold_heading: bool = False,
        wheel_speed_limit: float | None = None,
    ) -> TabularSettings: ...
    @property
    def tables(self) -> int:
        """How many Q-tables the controller acts from."""
    @property
    def epsilon(self) -> float:
        """The rate of uniformly random allowed actions, in [0, 1]."""
    @property
    def hold_spins(self) -> bool:
        """Whether a spin on the spot goes on the way the last step turned."""
    @property
    def hold_heading(self) -> bool:
        """Whether Corridors and Corners holds its heading where no sensor sees a wall."""
    @property
    def wheel_speed_limit(self) -> float | None:
        """The motor limit whose fractions every robot drives at (each robot's own when None)."""

@final
class RunSettings:
    """The per-env inputs and outputs of one :meth:`BatchSimulator.run` call beside its
    controller. The arrays are the caller's own, read (and written) by the call and checked
    against the batch when it runs.

    Args:
        limits: How the call's episodes end (``EpisodeLimits()`` when None).
        seeds: Seeds of the envs' controller streams: one per env, or an int ``s`` (env ``i``
            gets ``s + i``); ``0..N`` when None.
        active: (N,) bool, the envs that step; the others stand still for the whole call (as
            an env whose episode ended does, its stream untouched). All when None.
        subtasks: The navigator's running sub-task of each env, the arrays of
            :meth:`Navigator.subtask_arrays` by key (``subtask``, ``steps`` and
            ``phase`` (N,) int64, ``start`` (N, 3), ``previous_yaw`` and ``heading_change``
            (N,), ``turn_point`` (N, 2) float64), read and written in place, for the tabular
            controller: it follows the odometry after every step as
            :meth:`Navigator.decide` does; a door sub-task that
            ends (or gives up) hands over to Corridors and Corners there. The states are taken
            as left after following the last step and left with the call's last step not yet
            followed (as :meth:`mazesim.learn.policy.HierarchicalPolicy.act` follows it); an env
            reset by ``autoreset`` begins Corridors and Corners.
        trace: Per-step outputs to fill, by key: ``observations`` (steps, N, width) float32,
            ``poses`` (steps, N, 3) float32, ``colliding`` and ``episode_ends`` (steps, N)
            bool, ``crossings`` and ``actions`` (steps, N) int32, ``wheel_speeds``
            (steps, N, 2) float32; with ``subtasks``, ``subtasks`` and ``phases`` (steps, N)
            int32 (the sub-task and phase each step's action was chosen in, -1 for an env that
            stood still) and ``subtask_ends`` (steps, N) bool (a door sub-task ended or gave up
            before the step's action was chosen).

    Raises:
        InvalidArgumentError: ``limits`` is not an EpisodeLimits, or ``subtasks`` or ``trace``
            not a dict.
    """

    def __new__(
        cls,
        limits: EpisodeLimits | None = None,
        seeds: int | Sequence[int] | npt.NDArray[np.uint64] | None = None,
        active: npt.NDArray[np.bool_] | None = None,
        subtasks: dict[str, npt.NDArray[Any]] | None = None,
        trace: dict[str, npt.NDArray[Any]] | None = None,
    ) -> RunSettings: ...
    @property
    def limits(self) -> EpisodeLimits:
        """How the episodes of the call end."""
    @property
    def seeds(self) -> int | Sequence[int] | npt.NDArray[np.uint64] | None:
        """The seeds of the envs' controller streams (an int ``s`` gives env ``i`` ``s + i``)."""
    @property
    def active(self) -> npt.NDArray[np.bool_] | None:
        """(N,) bool, the envs that step (all when None)."""
    @property
    def subtasks(self) -> dict[str, npt.NDArray[Any]] | None:
        """The navigator's running sub-task of each env, arrays by key, read and written in
        place."""
    @property
    def trace(self) -> dict[str, npt.NDArray[Any]] | None:
        """The per-step outputs to fill, arrays by key."""

@final
class StepBounds:
    """What a single env's task step (:meth:`Simulator.step_task`) keeps for the whole
    episode: the float32 bounds ``low`` and ``high`` its readings are clamped to (the distance
    sensors then the ground ones) and the motor limit ``max_speed`` (rad/s) its previous action
    is scaled by.

    Raises:
        InvalidArgumentError: ``low`` or ``high`` is not a float32 vector (of one width), or
            ``max_speed`` not above 0.
    """

    def __new__(
        cls, low: npt.NDArray[np.float32], high: npt.NDArray[np.float32], max_speed: float
    ) -> StepBounds: ...
    @property
    def low(self) -> npt.NDArray[np.float32]:
        """The lower bounds of the readings (float32, the distance sensors then the ground
        ones)."""
    @property
    def high(self) -> npt.NDArray[np.float32]:
        """The upper bounds of the readings."""
    @property
    def max_speed(self) -> float:
        """The motor limit (rad/s) the previous action's wheel speeds are divided by."""

@final
class TaskFeatures:
    """The navigation features (goal, explored map, waypoint, pose, previous action) of N
    environments, computed per step in the core."""

    def __new__(
        cls,
        num_envs: int,
        observation: str,
        include_pose: bool,
        sensor_scale: npt.NDArray[np.float64],
        feature_low: npt.NDArray[np.float32],
        feature_high: npt.NDArray[np.float32],
    ) -> TaskFeatures: ...
    @property
    def width(self) -> int:
        """Values of one observation."""
    def state(self) -> bytes:
        """The state of every environment as bytes, for `restore` (pickling, copies)."""
    def restore(self, state: bytes) -> None:
        """Puts every environment in the `state` of TaskFeatures of the same kind and number of
        environments."""
    def set_env(
        self,
        env: int,
        place: npt.NDArray[np.float64],
        rows: int,
        cols: int,
        waypoints: npt.NDArray[np.float64],
        open_sides: npt.NDArray[np.float64] | None,
        goal_cell: int | None,
    ) -> None:
        """Puts environment `env` into a world: `place` (float64: goal x, y, the world's larger
        side, its south-west corner x, y, the cell size, the grid's south-west corner x, y), its
        grid of `rows` x `cols` cells, the next `waypoints` of its cells ((n, 2) float64), the
        true `open_sides` of its cells ((rows * cols, 4) float64, 1.0 open) or None, and the
        `goal_cell` (row-major) to plan towards or None. Restarts the episode's map."""
    def set_goal(
        self,
        env: int,
        mode: str,
        goal: npt.NDArray[np.float64],
        cell_size: float,
        origin: npt.NDArray[np.float64],
        shape: tuple[int, int],
        targets: npt.NDArray[np.float64],
    ) -> None:
        """Sets the distance table of environment `env`'s goal: `mode` (`"maze"`, `"straight"` or
        `"none"`), the `goal` disc (float64 x, y, radius), the grid's `cell_size`, south-west
        `origin` (float64 x, y), its `shape` (rows, cols), and the (rows * cols, 5) float64
        `targets` of its cells (east, north, west, south, goal; NaN where none)."""
    def restart(self, env: int) -> None:
        """Forgets the explored map's visits of environment `env` (a new episode)."""
    def observe(
        self,
        readings: npt.NDArray[np.float32],
        poses: npt.NDArray[np.float32],
        previous: npt.NDArray[np.float32],
    ) -> npt.NDArray[np.float32]:
        """The (N, width) float32 observations of every environment from their (N, sensors)
        float32 raw `readings`, (N, 3) float32 `poses` and (N, 2) float32 `previous` actions
        (wheel speed fractions)."""
    def observe_env(
        self,
        env: int,
        readings: npt.NDArray[np.float32],
        pose: npt.NDArray[np.float32],
        left: float,
        right: float,
        max_speed: float,
    ) -> tuple[npt.NDArray[np.float32], float, bool]:
        """The (width,) float32 observation of environment `env` from its float32 raw `readings`
        and `pose`, the previous action being the wheel speeds `left` and `right` (rad/s, float32
        values) over `max_speed` in float32; then the distance in metres from the pose to the
        goal (`set_goal`) and whether the pose is in the goal disc."""

@final
class Navigator:
    """The lower level of the report's navigator for N robots, stepped in the core: Table 4.1
    levels of six distances, each robot's running sub-task with the odometry its phase and end
    read, and the action from the sub-task's table (``mazesim.learn.policy.HierarchicalPolicy``
    runs it below the higher level)."""

    def __new__(
        cls, lower_q: npt.NDArray[np.float64], num_envs: int, hold_heading: bool = False
    ) -> Navigator: ...
    @property
    def num_envs(self) -> int:
        """Number of robots."""
    def reset(self, envs: npt.NDArray[np.int64], odometry: npt.NDArray[np.float64]) -> None:
        """Starts the robots ``envs`` (int64) afresh in Corridors and Corners at their rows of the
        (N, 3) float64 ``odometry`` (x, y, yaw)."""
    def decide(
        self,
        distances_cm: npt.NDArray[np.float64],
        odometry: npt.NDArray[np.float64],
        chosen: npt.NDArray[np.int64],
    ) -> dict[str, npt.NDArray[Any]]:
        """One step of every robot: the (N, 6) float64 ``distances_cm`` (front, back, left,
        right, left-front, right-front), the (N, 3) float64 ``odometry`` after the last step and
        the (N,) int64 sub-task the higher level ``chosen`` for each robot (-1: none). Returns a
        dict of arrays: ``action``, ``state``, ``subtask``, ``phase`` (int64, (N,)), ``levels``
        (int64, (N, 6)) and ``ended`` (bool, (N,): a door sub-task ended)."""
    def subtask_arrays(self) -> dict[str, npt.NDArray[Any]]:
        """Each robot's running sub-task as the arrays ``BatchSimulator.run`` takes as
        ``subtasks`` (copies: hand them back with ``set_subtask_arrays`` after the run)."""
    def set_subtask_arrays(self, subtasks: dict[str, npt.NDArray[Any]]) -> None:
        """Sets each robot's running sub-task from arrays of ``subtask_arrays``' layout (after
        ``BatchSimulator.run`` followed the sub-tasks); the robots' last actions stay."""
