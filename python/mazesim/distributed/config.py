"""Sweep configuration: a small TOML file listing a grid of training settings.

A sweep file has two tables. ``[sweep]`` says how to run it; ``[grid]`` lists the parameters of
the training runs. In ``[grid]`` a list is an axis of the grid and a single value is the same for
every setting; the settings are the product of the axes. Every parameter not given takes its
default (:data:`PARAMETERS`)::

    [sweep]
    name = "flat-rates"
    cpus_per_task = 1      # batch-engine threads (and Ray CPUs) of each task
    max_retries = 2        # times a task whose worker died is run again

    [grid]
    seed = [0, 1]
    learning_rate = [0.1, 0.3]
    epsilon = [0.05, 0.2]
    maze_size = 5          # a generated 5 x 5 maze; or world = "seed-maze" (a name or a path)
    envs = 32
    steps = 1000

The hyperparameters (``learning_rate``, ``epsilon``, ``discount``, ``collision_penalty``,
``episode_steps``, ``higher_episodes``) default to ``None``: each trainer's own default. A
parameter that the setting's trainer has no use for is refused
(:func:`mazesim.distributed.tasks.check_parameters`).

Settings are expanded in the order of :data:`PARAMETERS` (the seed varies fastest), whatever
order the file lists them in. Each setting has a stable id, ``<group>-s<seed>``, where ``group``
is a hash of its parameters other than the seed (and of the world file's text, for a world read
from a file): the same parameters always get the same id, so a sweep run again into the same
folder finds the runs it already finished.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import os
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from mazesim._core import World, builtin_world_names, generate_maze
from mazesim._paths import found_kind, read_text, unknown_name_or_file
from mazesim._toml import load_toml
from mazesim.errors import (
    InvalidArgumentError,
    WorldFormatError,
    _known_name,
    _shown,
)

__all__ = [
    "MAX_SETTINGS",
    "PARAMETERS",
    "TRAINER_DEFAULTS",
    "Parameter",
    "Setting",
    "SweepConfig",
    "load_sweep_config",
    "parse_sweep_config",
]


@dataclass(frozen=True)
class Parameter:
    """One parameter of a training setting.

    Attributes:
        name: The key in ``[grid]``.
        kind: ``int``, ``float``, ``bool`` or ``str``.
        default: The value when the file does not give one (``None``: none, or for a
            hyperparameter the trainer's own default).
        accepts: Whether a value of the right kind is in range.
        expected: What ``accepts`` wants, for error messages.
        help: What the parameter does.
    """

    name: str
    kind: type
    default: Any
    accepts: Callable[[Any], bool]
    expected: str
    help: str


def _count(low: int, high: int) -> Callable[[Any], bool]:
    return lambda value: low <= value <= high


def _defaults(name: str) -> str:
    """The help text's note of each trainer's default, read from the learning layer's configs."""
    from mazesim.distributed.hrl_trainers import FLAT_DEFAULTS, HRL_DEFAULTS

    parts = [
        f"{trainer}: {defaults[name]}"
        for trainer, defaults in (("hrl", HRL_DEFAULTS), ("baseline", FLAT_DEFAULTS))
        if name in defaults
    ]
    return f" (default {'; '.join(parts)})"


#: The parameters of a setting, in expansion order (the last varies fastest).
PARAMETERS: tuple[Parameter, ...] = (
    Parameter("trainer", str, "auto", lambda v: bool(v), "a trainer name", "who trains: "
              "'hrl' (mazesim's hierarchical navigator), 'baseline' (its flat learner; also "
              "named 'flat-q'), or 'auto' (the first installed of these)"),
    Parameter("world", str, None, lambda v: bool(v), "a world name or path",
              "a built-in world or a .toml world file (relative to the sweep file); "
              "instead of a generated maze"),
    Parameter("maze_size", int, 5, _count(2, 30), "a maze size from 2 to 30",
              "cells per side of the generated square maze"),
    Parameter("maze_seed", int, 0, _count(0, 2**63 - 1), "a seed in [0, 2^63)",
              "seed of the generated maze"),
    Parameter("loops", float, 0.0, lambda v: 0.0 <= v <= 1.0, "a share in [0, 1]",
              "share of extra openings of the generated maze (0: a perfect maze)"),
    Parameter("noise", bool, True, lambda v: True, "true or false",
              "sensor noise on (hrl and baseline train with noise only)"),
    Parameter("envs", int, 32, _count(1, 65536), "a number of envs from 1 to 65536",
              "environments stepped together in training (hrl: in its lower level)"),
    Parameter("steps", int, 1000, _count(1, 10**9), "a positive number of steps",
              "training steps of the whole batch (env-steps = envs x steps; hrl: of its "
              "lower level, in rounds of at most 500 steps)"),
    Parameter("episode_steps", int, None, _count(1, 10**7), "a positive number of steps",
              "control steps of 64 ms before an episode is cut off (in evaluation, in hrl's "
              "higher-level training and in baseline's training)" + _defaults("episode_steps")),
    Parameter("higher_episodes", int, None, _count(1, 10**7), "a positive number of episodes",
              "hrl only: episodes the higher level trains on the world"
              + _defaults("higher_episodes")),
    Parameter("learning_rate", float, None, lambda v: 0.0 < v <= 0.5, "a rate in (0, 0.5]",
              "Q-learning rate: the first rate of a state-action pair, falling with its updates "
              "(hrl: of the lower level)" + _defaults("learning_rate")),
    Parameter("epsilon", float, None, lambda v: 0.0 <= v <= 1.0, "a rate in [0, 1]",
              "exploration rate at the start, falling to 0 (hrl: of the lower level's first "
              "round)" + _defaults("epsilon")),
    Parameter("discount", float, None, lambda v: 0.0 <= v < 1.0, "a factor in [0, 1)",
              "discount factor gamma (hrl: the lower level's)" + _defaults("discount")),
    Parameter("collision_penalty", float, None, lambda v: v >= 0.0, "a number >= 0",
              "baseline only: reward subtracted per step in contact with a wall"
              + _defaults("collision_penalty")),
    Parameter("eval_episodes", int, 32, _count(1, 10**6), "a positive number of episodes",
              "greedy episodes of the evaluation after training"),
    Parameter("seed", int, 0, _count(0, 2**63 - 1), "a seed in [0, 2^63)",
              "seed of the training run (exploration, sensor noise, evaluation)"),
)  # fmt: skip
_BY_NAME = {parameter.name: parameter for parameter in PARAMETERS}
#: The parameters whose default is each trainer's own (``None`` in a setting that leaves them out).
TRAINER_DEFAULTS: tuple[str, ...] = (
    "episode_steps",
    "higher_episodes",
    "learning_rate",
    "epsilon",
    "discount",
    "collision_penalty",
)
_SWEEP_KEYS = ("name", "cpus_per_task", "max_retries")
#: The most settings a grid may expand to (each is a training run).
MAX_SETTINGS = 100_000


@dataclass(frozen=True)
class Setting:
    """One training run of a sweep: its parameters and how to name it.

    Attributes:
        id: The stable id, ``<group>-s<seed>``; also the name of its folder in the output.
        group: The hash of the parameters other than the seed; runs that differ only in their
            seed share it.
        label: The parameters that vary across the sweep, other than the seed (``"epsilon=0.2,
            learning_rate=0.1"``), or ``"all"`` when only the seed varies.
        params: Every parameter, by name (JSON values).
        world_toml: The text of the world file, for a world read from a file (workers on other
            machines need not see the file); ``None`` otherwise.
    """

    id: str
    group: str
    label: str
    params: Mapping[str, Any]
    world_toml: str | None = None

    @property
    def seed(self) -> int:
        """The setting's seed."""
        return int(self.params["seed"])

    def world(self) -> World:
        """The world the setting trains in: the named or read world, or its generated maze."""
        if self.world_toml is not None:
            return World.from_toml(self.world_toml, source=str(self.params["world"]))
        if self.params["world"] is not None:
            return World.builtin(str(self.params["world"]))
        return generate_maze(
            self.params["maze_size"],
            self.params["maze_size"],
            seed=self.params["maze_seed"],
            loops=self.params["loops"],
        )

    def to_json(self) -> dict[str, Any]:
        """The setting as a JSON object (without the world's text)."""
        return {
            "id": self.id,
            "group": self.group,
            "label": self.label,
            "params": dict(self.params),
        }


@dataclass(frozen=True)
class SweepConfig:
    """A parsed sweep file.

    Attributes:
        name: The sweep's name (``[sweep] name``, by default the file's stem).
        source: The file the sweep was read from, or ``"<string>"``.
        text: The file's text, copied into the output folder.
        cpus_per_task: CPUs (batch-engine threads) each task asks Ray for.
        max_retries: Times Ray runs a task again whose worker died.
        axes: The parameters given as lists, in expansion order.
        settings: Every setting of the grid, in expansion order.
    """

    name: str
    source: str
    text: str
    cpus_per_task: int
    max_retries: int
    axes: Mapping[str, tuple[Any, ...]]
    settings: tuple[Setting, ...]


def _check_value(parameter: Parameter, value: Any, where: str) -> Any:
    """The value converted to the parameter's kind, or an error naming ``where``."""
    kind = parameter.kind
    if kind is bool:
        right_kind = isinstance(value, bool)
    elif isinstance(value, bool):
        right_kind = False
    elif kind is float:
        right_kind = isinstance(value, (int, float))
    else:
        right_kind = isinstance(value, kind)
    if not right_kind:
        raise InvalidArgumentError(f"{where}: expected {parameter.expected}, found {_shown(value)}")
    try:
        converted = kind(value)
    except OverflowError:  # a whole number too large for a float
        converted = math.inf
    if kind is float and not math.isfinite(converted):
        raise InvalidArgumentError(f"{where}: expected {parameter.expected}, found {_shown(value)}")
    if not parameter.accepts(converted):
        raise InvalidArgumentError(f"{where}: expected {parameter.expected}, found {_shown(value)}")
    return converted


def _known_keys(source: str, table: str, given: Iterable[object], available: list[str]) -> None:
    """Refuses the first key of ``given`` (a table of the file ``source``) not ``available``."""
    for key in given:
        _known_name(key, f"a key of {table or 'the file'} in {source}", available)


def _read_grid(source: str, grid: Any) -> dict[str, tuple[Any, ...]]:
    """Each parameter's values (a 1-tuple for a single value), checked, in expansion order."""
    if not isinstance(grid, dict):
        raise InvalidArgumentError(f"{source}: expected a [grid] table, found {_shown(grid)}")
    _known_keys(source, "[grid]", grid, [p.name for p in PARAMETERS])
    values: dict[str, tuple[Any, ...]] = {}
    for parameter in PARAMETERS:
        given = grid.get(parameter.name, parameter.default)
        where = f"{source}: grid.{parameter.name}"
        if isinstance(given, list):
            if not given:
                raise InvalidArgumentError(f"{where}: expected at least one value, found []")
            checked = [_check_value(parameter, v, f"{where}[{i}]") for i, v in enumerate(given)]
            if len(set(map(json.dumps, checked))) != len(checked):
                raise InvalidArgumentError(
                    f"{where}: expected distinct values, found {_shown(given)}"
                )
            values[parameter.name] = tuple(checked)
        elif given is None:
            values[parameter.name] = (None,)
        else:
            values[parameter.name] = (_check_value(parameter, given, where),)
    if "world" in grid and "maze_size" in grid:
        raise InvalidArgumentError(
            f"{source}: grid has both 'world' and 'maze_size'; expected one: a world to load, "
            "or the size of a generated maze"
        )
    return values


def _world_text(source: str, name: str, base_dir: str) -> str | None:
    """The text of a world file (``None`` for a built-in name), checked to have a goal."""
    if name in builtin_world_names():
        world, text = World.builtin(name), None
    else:
        path = os.path.join(base_dir, name)
        if not os.path.isfile(path):
            raise unknown_name_or_file(
                name,
                "world",
                sorted(builtin_world_names()),
                "a .toml world file, relative to the sweep file's folder",
                (".toml",),
                context=f"{source}: grid.world: ",
                folder_of_names=base_dir,
            )
        text = read_text(
            path,
            f"the world of {source}'s grid.world",
            lambda message: WorldFormatError(message, source=path, field="grid.world"),
        )
        world = World.from_toml(text, source=path)
    if world.goal is None:
        raise InvalidArgumentError(
            f"{source}: grid.world: expected a world with a goal, found none in {_shown(name)}"
        )
    return text


def _hash(params: Mapping[str, Any], world_toml: str | None) -> str:
    digest = hashlib.sha256(json.dumps(dict(params), sort_keys=True).encode("utf-8"))
    if world_toml is not None:
        digest.update(world_toml.encode("utf-8"))
    return digest.hexdigest()[:10]


def _label(params: Mapping[str, Any], varying: list[str]) -> str:
    shown = [name for name in varying if name != "seed"]
    return ", ".join(f"{name}={params[name]}" for name in shown) if shown else "all"


def parse_sweep_config(
    text: str,
    source: str = "<string>",
    base_dir: str | os.PathLike[str] = ".",
    resolve_trainer: Callable[[str], str] | None = None,
) -> SweepConfig:
    """Parses the text of a sweep file and expands its grid.

    Args:
        text: The TOML text.
        source: Where the text came from, for error messages.
        base_dir: The folder world paths are relative to.
        resolve_trainer: Turns a trainer name (``"auto"`` included) into the registered name
            that runs; by default :func:`mazesim.distributed.tasks.resolve_trainer`.

    Returns:
        The sweep, with its settings.

    Raises:
        InvalidArgumentError: The text is not TOML, a value is of the wrong kind or range, or a
            parameter is set that the setting's trainer does not use.
        UnknownNameError: A key, trainer or world name is not known.
        MazesimIOError: A world file cannot be read.
        WorldFormatError: A world file is not a valid world.
    """
    from mazesim.distributed import tasks

    if resolve_trainer is None:
        resolve_trainer = tasks.resolve_trainer
    kind = found_kind(text)
    if kind is not None:  # a world file or a robot profile given as the sweep file
        raise InvalidArgumentError(
            f"{source}: expected a sweep file (a [sweep] and a [grid] table), found {kind}"
        )
    document = load_toml(text, source)
    _known_keys(source, "", document, ["sweep", "grid"])
    sweep = document.get("sweep", {})
    if not isinstance(sweep, dict):
        raise InvalidArgumentError(f"{source}: expected a [sweep] table, found {_shown(sweep)}")
    _known_keys(source, "[sweep]", sweep, list(_SWEEP_KEYS))
    stem = os.path.splitext(os.path.basename(source))[0] or "sweep"
    name = sweep.get("name", stem if source != "<string>" else "sweep")
    if not isinstance(name, str) or not name:
        raise InvalidArgumentError(f"{source}: sweep.name: expected a text, found {_shown(name)}")
    limits = {"cpus_per_task": (1, 1, 1024), "max_retries": (2, 0, 100)}
    numbers = {}
    for key, (default, low, high) in limits.items():
        value = sweep.get(key, default)
        if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
            raise InvalidArgumentError(
                f"{source}: sweep.{key}: expected a whole number from {low} to {high}, "
                f"found {_shown(value)}"
            )
        numbers[key] = value

    values = _read_grid(source, document.get("grid", {}))
    count = math.prod(len(options) for options in values.values())
    if count > MAX_SETTINGS:
        lengths = " x ".join(f"{len(v)} {k}" for k, v in values.items() if len(v) > 1)
        raise InvalidArgumentError(
            f"{source}: grid: expected at most {MAX_SETTINGS} settings, found {count} "
            f"({lengths}); split the sweep or shorten its lists"
        )
    values["trainer"] = tuple(dict.fromkeys(resolve_trainer(t) for t in values["trainer"]))
    world_texts = {
        world: _world_text(source, world, os.fspath(base_dir))
        for world in values["world"]
        if world is not None
    }
    if values["world"] != (None,):
        values["maze_size"] = values["maze_seed"] = values["loops"] = (None,)
    varying = [name for name, options in values.items() if len(options) > 1]
    settings = []
    for combination in itertools.product(*values.values()):
        params = dict(zip(values, combination))
        world_toml = world_texts.get(params["world"])
        tasks.check_parameters(params, f"{source}: grid")
        group = _hash({k: v for k, v in params.items() if k != "seed"}, world_toml)
        settings.append(
            Setting(
                id=f"{group}-s{params['seed']}",
                group=group,
                label=_label(params, varying),
                params=params,
                world_toml=world_toml,
            )
        )
    return SweepConfig(
        name=name,
        source=source,
        text=text,
        cpus_per_task=numbers["cpus_per_task"],
        max_retries=numbers["max_retries"],
        axes={name: values[name] for name in varying},
        settings=tuple(settings),
    )


def load_sweep_config(path: str | os.PathLike[str]) -> SweepConfig:
    """Reads and parses a sweep file (see :func:`parse_sweep_config`); world paths in it are
    relative to its folder.

    Raises:
        MazesimIOError: The file cannot be read.
    """
    source = os.fspath(path)
    text = read_text(source, "the sweep file")
    return parse_sweep_config(text, source, base_dir=os.path.dirname(os.path.abspath(source)))
