"""The registry of mazesim's public surface: every public function, class and method of every
module of the ``mazesim`` package (``mazesim._core`` included), and every command of the
``mazesim`` command line with its options, found by walking the package and the argument parser.
A new entry point is in the registry as soon as it exists; the tests feed each one hostile values
(``hostile.py``) through hypothesis and check how it ends (``runner.py``).

A method needs an instance to be called on: :data:`INSTANCES` says how to make one of a class when
the generic recipe (``values.sample_instance``: each required constructor parameter given a valid
value of its annotated type) cannot; a class neither can make fails ``test_public_surface``.
"""

from __future__ import annotations

import argparse
import dataclasses
import enum
import importlib
import inspect
import pkgutil
import typing
import warnings
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from typing import Any

import mazesim
from mazesim._checks import _UNIONS, annotations_of, is_public_module, public_names
from mazesim.errors import RegisteredName

#: Modules not walked: the program entry point (running it is the CLI's entries) and the parts
#: that start outside processes (ROS masters, Ray clusters, Webots controllers over a socket, the
#: template process a world's controller processes are forked from),
#: whose entry points are reached through the command line's entries instead; and the deprecated
#: ``mazesim.hrl``, whose names are ``mazesim.learn``'s own objects (importing it warns).
SKIPPED_MODULES = (
    "mazesim.__main__",
    "mazesim.hrl",
    "mazesim.ros",
    "mazesim.distributed",
    "mazesim.webots.controller",
    "mazesim.webots.process_template",
)

#: How to make an instance of each public class whose methods are entry points: Python source
#: evaluated by the runner (``world`` is seed-maze, ``tmp`` a scratch folder).
INSTANCES: dict[str, str] = {
    "mazesim._core.World": "world",
    "mazesim._core.Simulator": "mazesim.Simulator(world)",
    "mazesim._core.BatchSimulator": "mazesim.BatchSimulator(world, num_envs=2)",
    "mazesim._core.RobotProfile": "mazesim.RobotProfile.builtin('e-puck')",
    # A recorded episode of two frames whose walls changed at its second (walls_at).
    "mazesim.replay.run.RecordedEpisode": (
        "(lambda np: mazesim.replay.run.RecordedEpisode(0, np.zeros((2, 3)), np.zeros((2, 11)),"
        " np.zeros((2, 8)), np.zeros(2, bool), np.zeros(2, np.int64),"
        " walls=[(1, np.zeros((0, 5)))]))(__import__('numpy'))"
    ),
    "mazesim._core.TaskFeatures": (
        "(lambda np: mazesim._core.TaskFeatures(2, 'plan', False, np.ones(11),"
        " np.zeros(26, 'float32'), np.ones(26, 'float32')))(__import__('numpy'))"
    ),
    # The settings of BatchSimulator.run and Simulator.step_task: frozen values, checked when
    # made (a Q-table of the shape the tabular controller reads; the e-puck's eleven readings).
    "mazesim._core.EpisodeLimits": "mazesim.EpisodeLimits(max_steps=50, end_at_goal=True)",
    "mazesim._core.AvoidCollisionSettings": "mazesim.AvoidCollisionSettings(threshold=70.0)",
    "mazesim._core.TabularSettings": (
        "mazesim.TabularSettings(__import__('numpy').zeros((4096, 12)), epsilon=0.1)"
    ),
    "mazesim._core.RunSettings": "mazesim.RunSettings(mazesim.EpisodeLimits(), seeds=3)",
    "mazesim._core.MazeLayout": "mazesim.MazeLayout(cell_size=0.3, checkpoints=False)",
    "mazesim._core.DrivePerturbation": "mazesim.DrivePerturbation(wheel_radius_scale=1.05)",
    "mazesim._core.SensingPerturbation": "mazesim.SensingPerturbation(noise_scale=2.0)",
    # The settings of the lower level's training rounds: its numbers, one world, two robots.
    "mazesim._core.LowerRoundSettings": (
        "(lambda np: mazesim._core.LowerRoundSettings(dict.fromkeys(('gamma', 'epsilon',"
        " 'rate_initial', 'rate_floor', 'rate_power', 'progress_reward', 'collision_penalty',"
        " 'corridor_step_reward', 'door_step_reward', 'heading_reward', 'door_success_reward',"
        " 'door_failure_reward', 'door_path_exit', 'success_past_centre', 'success_across'), 0.5)"
        " | {'decision_steps': 10, 'corridor_episode_steps': 350}, [world],"
        " np.zeros(2, np.int64), np.ones((4, 12), bool)))(__import__('numpy'))"
    ),
    "mazesim._core.StepBounds": (
        "(lambda np: mazesim._core.StepBounds(np.zeros(11, 'float32'),"
        " np.full(11, 5000.0, 'float32'), 6.28))(__import__('numpy'))"
    ),
    "mazesim._core.Navigator": (
        "(lambda np: mazesim._core.Navigator(np.zeros((4, 3 * 4096, 12)), 2))(__import__('numpy'))"
    ),
    # Optional tables that its kind makes required: the shipped navigator's.
    "mazesim.learn.episode_ranges.NavigatorEpisodes": (
        "(lambda p, m: m.NavigatorEpisodes('hierarchical', (world.to_toml(),), 1, 0, 'truth', 50,"
        " (tuple(p.checkpoint_ids),), lower_q=p.lower_q, higher_q=p.higher_q[None]))("
        "__import__('mazesim.learn', fromlist=['x']).load_policy(),"
        " __import__('mazesim.learn.episode_ranges', fromlist=['x']))"
    ),
    # A token of a world's text.
    "mazesim.webots.proto.syntax.Token": (
        "__import__('mazesim.webots.proto.syntax', fromlist=['x']).Token('word', 'TRUE', 0, 4)"
    ),
    # The link to a C controller: a socket whose other end is closed, and the robot it drives.
    "mazesim.webots.native_link.RobotLink": (
        "(lambda s, w: w.native_link.RobotLink(s.socketpair()[0],"
        " (w.simulation.prepare(world), w.robot.Robot())[1], ('e-puck', 'c', 'test')))("
        "__import__('socket'), __import__('mazesim.webots.robot', fromlist=['x']) and"
        " __import__('mazesim.webots', fromlist=['native_link', 'simulation', 'robot']))"
    ),
    # A compiled controller's calls, served by a supervisor robot of a prepared world.
    "mazesim.webots.native_calls.NativeCalls": (
        "(lambda w: w.native_calls.NativeCalls("
        "(w.simulation.prepare(world), w.supervisor.Supervisor())[1], []))("
        "__import__('mazesim.webots.supervisor', fromlist=['x']) and"
        " __import__('mazesim.webots', fromlist=['native_calls', 'simulation', 'supervisor']))"
    ),
    # The DifferentialWheels drive of the robot of a prepared world (Webots 8's EPuck fields).
    "mazesim.webots.differential_drive.DifferentialDrive": (
        "(lambda w: (w.simulation.prepare(world), w.robot.Robot())[1]"
        "._equipment.differential_drive)(__import__('mazesim.webots.robot', fromlist=['x']) and"
        " __import__('mazesim.webots', fromlist=['robot', 'simulation']))"
    ),
    # The walls and bodies a supervisor moves, in a world's simulator.
    "mazesim.webots.solids.WorldSolids": (
        "__import__('mazesim.webots.solids', fromlist=['x']).WorldSolids("
        "[mazesim.Simulator(world)], {})"
    ),
    # A robot a supervisor removed, as it was in a world's simulator.
    "mazesim.webots.robots_changed.RemovedRobot": (
        "__import__('mazesim.webots.robots_changed', fromlist=['x']).RemovedRobot("
        "mazesim.Simulator(world))"
    ),
    # The changes a supervisor makes to the running world of a world file.
    "mazesim.webots.scene_edits.SceneEdits": (
        "(lambda w: w.scene_edits.SceneEdits(w.simulation.prepare(world,"
        " report={'path': 'tests/data/webots-worlds/e-puck.R2023b.wbt'})))("
        "__import__('mazesim.webots', fromlist=['scene_edits', 'simulation']))"
    ),
    # A lidar and a range finder on the robot of a prepared world, with their nodes' defaults.
    "mazesim.webots.scanners.RayLidar": (
        "(lambda w: w.scanners.RayLidar('lidar', w.simulation.prepare(world),"
        " w.sensors.DeviceMount(), {}))("
        "__import__('mazesim.webots', fromlist=['scanners', 'sensors', 'simulation']))"
    ),
    "mazesim.webots.scanners.RayRangeFinder": (
        "(lambda w: w.scanners.RayRangeFinder('range-finder', w.simulation.prepare(world),"
        " w.sensors.DeviceMount(), {}))("
        "__import__('mazesim.webots', fromlist=['scanners', 'sensors', 'simulation']))"
    ),
    # The movie of a supervisor of a prepared world, not recording.
    "mazesim.webots.movie.MovieRecorder": (
        "(lambda w: w.movie.MovieRecorder(w.simulation.prepare(world)))("
        "__import__('mazesim.webots', fromlist=['movie', 'simulation']))"
    ),
    # A recogniser of a camera with Webots' default Recognition node, over no object.
    "mazesim.webots.recognition.Recogniser": (
        "__import__('mazesim.webots.recognition', fromlist=['x']).Recogniser("
        "{'robot_line': 1, 'camera': 'camera', 'max_range': 100.0, 'max_objects': -1, "
        "'occlusion': 1, 'frame_color': [1.0, 0.0, 0.0], 'frame_thickness': 1, "
        "'segmentation': False}, [], {})"
    ),
    # The curriculum wraps a native vector env of an unseen-maze task.
    "mazesim.envs.curriculum.MazeSizeCurriculumWrapper": (
        "(lambda c: c.MazeSizeCurriculumWrapper(__import__('gymnasium').make_vec("
        "'mazesim/UnseenMazeExplore-v0', num_envs=2), c.MazeSizeCurriculum(((3, 3), (4, 4)))))("
        "__import__('mazesim.envs.curriculum', fromlist=['x']))"
    ),
    # The hand-written baselines read a task's observation names.
    **{
        f"mazesim.envs.baselines.{name}": (
            f"getattr(__import__('mazesim.envs.baselines', fromlist=['x']), {name!r})("
            "__import__('gymnasium').make("
            "'mazesim/UnseenMazeExplore-v0').unwrapped.observation_names)"
        )
        for name in ("CellAgent", "FrontierExplorer", "WallFollower")
    },
    # SB3's VecEnv over the native vector env, made as its own make_vec_env makes it.
    "mazesim.integrations.sb3.MazesimVecEnv": (
        "__import__('mazesim.integrations.sb3', fromlist=['x']).make_vec_env("
        "'mazesim/MazeFixed-v1', n_envs=2, monitor=False)"
    ),
    # The multi-robot tasks, their batch, env and renderer: maze_goals_v0's three robots.
    "mazesim.marl.tasks.MultiRobotTask": (
        "__import__('mazesim.marl.maze_goals_v0', fromlist=['x']).task()"
    ),
    "mazesim.marl.batch.MultiRobotBatch": (
        "__import__('mazesim.marl.maze_goals_v0', fromlist=['x']).batch_env(2)"
    ),
    "mazesim.marl.parallel.MultiRobotParallelEnv": (
        "__import__('mazesim.marl.maze_goals_v0', fromlist=['x']).parallel_env()"
    ),
    "mazesim.marl.render.SwarmRenderer": (
        "__import__('mazesim.marl.render', fromlist=['x']).SwarmRenderer(world,"
        " mazesim.RobotProfile.builtin('e-puck'), __import__('numpy').zeros((2, 3)))"
    ),
}


@dataclass(frozen=True)
class MustRefuse:
    """Values an entry point must refuse: each of ``absurd[name]`` given to the parameter
    ``name`` (keys of ``values.ABSURD`` or ``values.BUILDERS``), the other parameters given
    ``valid`` ones (keys of ``values.VALID``). A call that returns is a failure of the walk,
    however quietly it went: an absurd value accepted is a bug, not a handled input."""

    valid: dict[str, str]
    absurd: dict[str, tuple[str, ...]]


#: The entry points whose absurd values are known, and which must be refused. A class of
#: silent acceptance, once found, is declared here so that the walk keeps it closed.
MUST_REFUSE: dict[str, tuple[MustRefuse, ...]] = {
    # Every number of a robot profile has its range (one table in the core).
    "mazesim._core:RobotProfile.from_toml": (MustRefuse({}, {"text": ("profile_heading_1e300",)}),),
    # A grid's walls are thinner than its cells, as a generated maze's are.
    "mazesim._core:World.from_toml": (
        MustRefuse(
            {}, {"text": ("grid_wall_as_thick_as_its_cell", "grid_wall_thicker_than_its_cell")}
        ),
    ),
    # A cell is at most as big as the coordinates every maze lies in, so no layout is accepted
    # that no maze can be made of.
    "mazesim._core:MazeLayout": (
        MustRefuse({}, {"wall_thickness": ("max_float", "nan", "minus_one")}),
        MustRefuse({}, {"cell_size": ("max_float", "inf", "nan")}),
    ),
    # A point a query is asked about is a coordinate of the world: finite and bounded.
    "mazesim._core:World.floor_reflectance": (
        MustRefuse({"y": "quarter"}, {"x": ("nan", "inf", "max_float", "complex_number")}),
        MustRefuse({"x": "quarter"}, {"y": ("minus_inf", "min_float")}),
    ),
    # Every template engine runs under one budget, and Ctrl-C (the walk's watchdog presses it)
    # stops a template of either language: a Lua one through its hook, a JavaScript one (whose
    # regular expressions heed no time limit) by ending the child process it runs in.
    "mazesim.webots.proto.templates:evaluate_template": (
        MustRefuse(
            {"language": "lua", "fields": "no_fields", "context": "no_fields", "origin": "origin"},
            {"body": ("endless_lua_template",)},
        ),
        MustRefuse(
            {
                "language": "javascript",
                "fields": "no_fields",
                "context": "no_fields",
                "origin": "origin",
            },
            {"body": ("endless_javascript_template", "redos_javascript_template")},
        ),
    ),
    # A controller's step is a whole number of ms that fits Webots' C int, as its periods are.
    "mazesim.webots.robot:Robot.step": (
        MustRefuse({}, {"time_step": ("period_2_40", "nan", "minus_one")}),
    ),
    # A packet an emitter can never queue (beyond the bound of Webots' unlimited bufferSize) is
    # refused before it is built.
    "mazesim.webots.radio_devices:Emitter.send": (
        MustRefuse({}, {"message": ("huge_range", "packet_over_bound")}),
    ),
    "mazesim._core:Simulator.set_goal": (
        MustRefuse(
            {"x": "quarter", "y": "quarter"}, {"radius": ("nan", "inf", "max_float", "minus_one")}
        ),
    ),
    # A complex number is no real one: refused where numpy's would convert with a warning.
    "mazesim._core:SensingPerturbation": (
        MustRefuse({}, {"noise_scale": ("max_float", "nan", "complex_number")}),
    ),
    "mazesim._core:sharp_volts_to_cm": (
        MustRefuse({}, {"volts": ("nan", "inf", "minus_one", "min_float", "complex_number")}),
    ),
    # A masked array's mask is not dropped: its masked entries are no numbers to drive by.
    "mazesim._core:Simulator.step_robots": (MustRefuse({}, {"commands": ("masked_commands",)}),),
    # A path object whose own code fails names no path: refused, its error not escaping.
    "mazesim:load_world": (MustRefuse({}, {"name_or_path": ("raising_path",)}),),
    # The vector discretisers refuse what the scalar one refuses, NaN first of all (a NaN
    # reading compares false with every bound: one check, ``not (0 <= v < inf)``, in both).
    "mazesim._core:lower_level_states": (
        MustRefuse({}, {"observations": ("nan_observations", "inf_observations")}),
    ),
    "mazesim._core:sharp_distances": (MustRefuse({}, {"readings": ("nan_array",)}),),
    "mazesim.learn.discretise:distances_and_levels": (
        MustRefuse({}, {"volts": ("nan", "inf", "nan_array", "nan_observations")}),
    ),
    "mazesim.learn.discretise:volts_to_cm": (
        MustRefuse({}, {"volts": ("nan", "inf", "nan_array", "nan_observations")}),
    ),
    "mazesim.learn.discretise:observation_states": (
        MustRefuse({}, {"observations": ("nan_observations", "inf_observations")}),
    ),
    "mazesim.learn.discretise:distance_levels": (
        MustRefuse({}, {"distances_cm": ("nan", "nan_array", "minus_one")}),
    ),
}

#: Absurd values every entry point refuses for a parameter of this name, whatever its class:
#: every Webots ``enable(samplingPeriod)`` (a sensor's, the keyboard's, a motor's feedback, a
#: device added later) takes a period that fits Webots' C ``int``, through one check.
MUST_REFUSE_BY_PARAMETER: dict[str, tuple[str, ...]] = {
    "samplingPeriod": ("period_2_40", "nan", "inf"),
}

#: What a parameter annotated :data:`mazesim.errors.RegisteredName` (alone, or in a union with
#: None) is given: a name no registry holds, which must be refused with a message that lists the
#: known names (``UnknownNameError``, or a message saying "expected one of"). The parameters are
#: found by their annotation, not by their names (``task``, ``events`` or ``controller`` are
#: names in some signatures, objects, indices or arrays in others), so that a new function's
#: name parameter is walked as soon as it is annotated as one.
REGISTERED_NAME_VALUES = ("unknown_name",)


def _is_registered_name(hint: Any) -> bool:
    """Whether ``hint`` is :data:`mazesim.errors.RegisteredName`, alone or in a union."""
    if hint == RegisteredName:
        return True
    return typing.get_origin(hint) in _UNIONS and any(
        _is_registered_name(arg) for arg in typing.get_args(hint)
    )


def registered_name_parameters(target: Callable[..., Any]) -> tuple[str, ...]:
    """The parameters of ``target`` (a class: of its constructor) annotated as names a registry
    holds."""
    if inspect.isclass(target):
        target = getattr(target, "__init__", target)
    return tuple(
        name
        for name, hint in annotations_of(target).items()
        if name != "return" and _is_registered_name(hint)
    )


#: What a parameter annotated as a number is given: NaN, which no comparison catches and every
#: sum carries on, and, unless it is annotated :data:`mazesim.errors.MaybeInfinite`, an
#: infinity; one annotated as a list or tuple of numbers is given a list holding both. The
#: surface check (``mazesim._checks``) refuses them unless the class is Webots' API
#: (``_takes_nan``: it answers NaN as Webots does). Found by annotation, so that a new
#: function's number parameter is walked with them by construction.
NUMBER_VALUES = ("nan", "inf")
UNBOUNDED_NUMBER_VALUES = ("nan",)
NUMBER_LIST_VALUES = ("non_finite_list",)


def number_parameters(target: Callable[..., Any]) -> tuple[tuple[str, ...], ...]:
    """The parameters of ``target`` (a class: of its constructor) annotated as finite numbers,
    as numbers that may be infinite, and as lists or tuples of numbers; none for Webots' API."""
    from mazesim._checks import _item_depth, _may_be_infinite, _takes_float

    if getattr(target, "_takes_nan", False) or getattr(
        getattr(target, "__self__", None), "_takes_nan", False
    ):
        return (), (), ()
    if inspect.isclass(target):
        target = getattr(target, "__init__", target)
    hints = {n: h for n, h in annotations_of(target).items() if n != "return"}
    numbers = [name for name, hint in hints.items() if _takes_float(hint)]
    unbounded = tuple(name for name in numbers if _may_be_infinite(hints[name]))
    finite = tuple(name for name in numbers if name not in unbounded)
    lists = tuple(name for name, hint in hints.items() if _item_depth(hint, float))
    return finite, unbounded, lists


def refusals_of(entry: EntryPoint) -> tuple[MustRefuse, ...]:
    """The refusals ``entry`` must make: its own in :data:`MUST_REFUSE`, and one for each of its
    parameters named in :data:`MUST_REFUSE_BY_PARAMETER` or annotated as a registered name
    (when it has no other required one, and is a Python entry point: a command's words are
    drawn by the walk of the command line)."""
    declared = {
        **{
            name: keys
            for name, keys in MUST_REFUSE_BY_PARAMETER.items()
            if name in entry.parameters
        },
        **dict.fromkeys(entry.named, REGISTERED_NAME_VALUES),
        **dict.fromkeys(entry.numbers, NUMBER_VALUES),
        **dict.fromkeys(entry.unbounded_numbers, UNBOUNDED_NUMBER_VALUES),
        **dict.fromkeys(entry.number_lists, NUMBER_LIST_VALUES),
    }
    by_name = tuple(
        MustRefuse({}, {name: keys})
        for name, keys in declared.items()
        if set(entry.required) <= {name} and not entry.path.startswith("cli:")
    )
    return MUST_REFUSE.get(entry.path, ()) + by_name


@dataclass(frozen=True)
class EntryPoint:
    """One public entry point: ``path`` says how the runner reaches it (``module:qualname``, or
    ``cli:command``); ``parameters`` are the names hostile values may be given to, ``required``
    those without a default (given a value in every call)."""

    path: str
    parameters: tuple[str, ...]
    required: tuple[str, ...] = field(default=())
    #: Those that cannot be given by keyword.
    positional: tuple[str, ...] = field(default=())
    #: For a command: the value each option takes ("" for a flag).
    options: tuple[tuple[str, bool], ...] = field(default=())
    #: Those that can be given by position, in order.
    ordered: tuple[str, ...] = field(default=())
    #: Whether it takes any number of positional (``*args``) and keyword (``**kwargs``) values.
    any_positional: bool = False
    any_keyword: bool = False
    #: Those annotated :data:`mazesim.errors.RegisteredName`.
    named: tuple[str, ...] = field(default=())
    #: Those annotated as finite numbers, as numbers that may be infinite, and as lists of
    #: numbers (:func:`number_parameters`).
    numbers: tuple[str, ...] = field(default=())
    unbounded_numbers: tuple[str, ...] = field(default=())
    number_lists: tuple[str, ...] = field(default=())


def _modules() -> Iterator[Any]:
    yield importlib.import_module("mazesim._core")
    yield mazesim
    # The walk imports every package to look inside it, the deprecated ``mazesim.hrl`` too.
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", "mazesim.hrl is deprecated", DeprecationWarning)
        found = list(pkgutil.walk_packages(mazesim.__path__, "mazesim."))
    for info in found:
        if info.name.startswith(SKIPPED_MODULES) or not is_public_module(info.name):
            continue  # mazesim._core came first; private modules are helpers, not the surface
        try:
            yield importlib.import_module(info.name)
        except mazesim.errors.MissingDependencyError:
            continue  # an optional extra that is not installed


#: The private entry points of the compiled module not walked: the one that panics on purpose
#: (its panic must come out as an InternalError, which a test of the panic guard checks).
PRIVATE_NOT_WALKED = ("_panic_for_tests",)


def _private_compiled(module: Any) -> list[str]:
    """The compiled module's private functions (``_temporary_writing``): called by the package
    only, with arguments of plain types that pyo3 converts, but reachable, so walked too."""
    if module.__name__ != "mazesim._core":
        return []
    return [
        name
        for name in dir(module)
        if name.startswith("_")
        and not name.startswith("__")
        and name not in PRIVATE_NOT_WALKED
        and inspect.isbuiltin(getattr(module, name))
    ]


def _public(module: Any) -> Iterator[tuple[str, Any]]:
    """The module's public functions and classes, as mazesim._checks defines them (exceptions,
    protocols and enums are types to catch or to match, not to call; an abstract class's methods
    are called on one of its implementations), and the compiled module's private functions."""
    for name in [*public_names(module), *_private_compiled(module)]:
        obj = getattr(module, name)
        if inspect.isclass(obj) and (
            issubclass(obj, (BaseException, enum.Enum)) or getattr(obj, "_is_protocol", False)
        ):
            continue
        yield name, obj


def _signature(
    target: Callable[..., Any], skip_first: bool, owner: Any = None
) -> EntryPoint | None:
    """``target``'s entry point (no path yet); ``owner`` is its class or module, whose
    ``_takes_nan`` says that it answers NaN and infinities itself."""
    try:
        params = list(inspect.signature(target).parameters.values())
    except (TypeError, ValueError):
        return None
    if skip_first and params and params[0].name in ("self", "cls"):
        params = params[1:]
    usable = [p for p in params if p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]
    names = {p.name for p in usable}
    none: tuple[tuple[str, ...], ...] = ((), (), ())
    numbers, unbounded, lists = (
        none if getattr(owner, "_takes_nan", False) else number_parameters(target)
    )
    return EntryPoint(
        "",
        tuple(p.name for p in usable),
        tuple(p.name for p in usable if p.default is p.empty),
        positional=tuple(p.name for p in usable if p.kind is p.POSITIONAL_ONLY),
        ordered=tuple(
            p.name for p in usable if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)
        ),
        any_positional=any(p.kind is p.VAR_POSITIONAL for p in params),
        any_keyword=any(p.kind is p.VAR_KEYWORD for p in params),
        named=tuple(name for name in registered_name_parameters(target) if name in names),
        numbers=tuple(name for name in numbers if name in names),
        unbounded_numbers=tuple(name for name in unbounded if name in names),
        number_lists=tuple(name for name in lists if name in names),
    )


def _with_path(entry: EntryPoint | None, path: str) -> EntryPoint:
    if entry is None:  # a signature Python cannot read: called with no arguments
        return EntryPoint(path, (), any_positional=True, any_keyword=True)
    return dataclasses.replace(entry, path=path)


def python_entry_points() -> list[EntryPoint]:
    """Every public function, class (its constructor) and method of the package."""
    found: dict[str, EntryPoint] = {}
    for module in _modules():
        for name, obj in _public(module):
            path = f"{module.__name__}:{name}"
            if not inspect.isclass(obj):
                found[path] = _with_path(_signature(obj, False, module), path)
                continue
            if not inspect.isabstract(obj):
                found[path] = _with_path(_signature(obj, False), path)
            for member, value in sorted(vars(obj).items()):
                if member.startswith("_") or isinstance(value, property):
                    continue
                if isinstance(value, (staticmethod, classmethod)):
                    target = getattr(obj, member)
                    entry = _signature(target, False, obj)
                elif inspect.isfunction(value) or inspect.ismethoddescriptor(value):
                    entry = _signature(value, True, obj)
                else:
                    continue
                method = f"{path}.{member}"
                found[method] = _with_path(entry, method)
    return sorted(found.values(), key=lambda e: e.path)


def instance_recipe(owner: str) -> str:
    """How the runner makes an instance of the class ``owner`` (``module.Class``): its entry in
    :data:`INSTANCES`, else ``auto:`` and the generic recipe."""
    return INSTANCES.get(owner, f"auto:{owner}")


def can_make(owner: str, world: Any, tmp: Any) -> bool:
    """Whether the generic recipe makes an instance of ``owner`` (True for those in INSTANCES)."""
    if owner in INSTANCES:
        return True
    from surface.values import sample_instance

    module, _, name = owner.rpartition(".")
    try:
        sample_instance(getattr(importlib.import_module(module), name), world, tmp)
    except Exception:  # noqa: BLE001 - any failure means the class needs a recipe
        return False
    return True


def needs_instance(entry: EntryPoint) -> str | None:
    """The class an entry point is a method of (``module:Class``), when it needs an instance."""
    module, _, qualname = entry.path.partition(":")
    if "." not in qualname or entry.path.startswith("cli:"):
        return None
    cls_name, member = qualname.split(".", 1)
    cls = getattr(importlib.import_module(module), cls_name)
    raw = vars(cls).get(member)
    if isinstance(raw, (staticmethod, classmethod)):
        return None
    return f"{module}.{cls_name}"


def cli_entry_points() -> list[EntryPoint]:
    """Every command of the ``mazesim`` command line (sub-commands included) with its options."""
    from mazesim.cli import build_parser

    found: list[EntryPoint] = []

    def walk(parser: argparse.ArgumentParser, words: tuple[str, ...]) -> None:
        options: list[tuple[str, bool]] = []
        positionals: list[str] = []
        for action in parser._actions:  # noqa: SLF001 - argparse offers no public walk
            if isinstance(action, argparse._SubParsersAction):  # noqa: SLF001
                for word, sub in action.choices.items():
                    walk(sub, (*words, word))
                continue
            if isinstance(action, (argparse._HelpAction, argparse._VersionAction)):  # noqa: SLF001
                continue
            if action.option_strings:
                options.append((action.option_strings[-1], action.nargs != 0))
            else:
                positionals.append(action.dest)
        if words:
            found.append(
                EntryPoint(
                    f"cli:{' '.join(words)}",
                    tuple(positionals),
                    tuple(positionals),
                    options=tuple(options),
                )
            )

    walk(build_parser(), ())
    return found
