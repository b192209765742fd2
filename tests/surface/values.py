"""The hostile values fed to the public surface, by key: huge lengths, nesting, non-finite and
extreme numbers, wrong types, special files, a path object giving bytes, a file of another kind
(a world file where a run, a navigator or a sweep is read). The keys are what hypothesis draws
(plans are plain data that cross into the runner's process); :func:`make` builds the value in
that process.

Special files here are the ones that cannot harm the machine when a call writes to them (a folder,
a missing path, a symlink loop, garbage, all inside a scratch folder): device nodes and FIFOs are
left to the tests of outputs and inputs, which run them under their own guards.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

import numpy as np


class WrongType:
    """A value of a type no argument takes."""

    def __repr__(self) -> str:
        return "WrongType()"


class HugeTuple(tuple[int, ...]):
    """A tuple that says it holds a billion items (it holds two)."""

    def __len__(self) -> int:
        return 10**9


class HugeShape:
    """An array-like whose ``shape`` is a billion entries long."""

    shape = range(10**9)
    dtype = "float32"

    def __len__(self) -> int:
        return 10**9


class BytesPath:
    """A path object whose ``__fspath__`` gives bytes, which no path argument takes."""

    def __init__(self, path: Path) -> None:
        self.path = path

    def __fspath__(self) -> bytes:
        return os.fsencode(self.path)

    def __repr__(self) -> str:
        return f"BytesPath({self.path!r})"


class RaisingPath:
    """A path object whose ``__fspath__`` raises (a user's path class with a bug)."""

    def __fspath__(self) -> str:
        raise RuntimeError("this path object cannot say its path")

    def __repr__(self) -> str:
        return "RaisingPath()"


class HugeMapping(dict[str, int]):
    """A mapping that says it holds a billion items (it holds one)."""

    def __init__(self) -> None:
        super().__init__(a=1)

    def __len__(self) -> int:
        return 10**9


def _nested_list(depth: int) -> list[Any]:
    value: list[Any] = []
    for _ in range(depth):
        value = [value]
    return value


def _nested_dict(depth: int) -> dict[str, Any]:
    value: dict[str, Any] = {}
    for _ in range(depth):
        value = {"a": value}
    return value


def _files(tmp: Path) -> dict[str, Any]:
    (tmp / "folder").mkdir(exist_ok=True)
    garbage = tmp / "garbage.toml"
    garbage.write_bytes(bytes(range(256)) * 4)
    empty = tmp / "empty.toml"
    empty.write_bytes(b"")
    loop = tmp / "loop.toml"
    if not loop.is_symlink():
        os.symlink(loop, loop)
    # A file of another kind than the one a reader expects: a world file given as a run, a
    # navigator, a sweep, a profile...
    world = tmp / "a-world.toml"
    world.write_text('format = "mazesim-world"\nversion = 1\n', encoding="utf-8")
    return {
        "world_file": str(world),
        "bytes_path": BytesPath(world),
        "folder": str(tmp / "folder"),
        "missing_path": str(tmp / "missing" / "x.toml"),
        "garbage_file": str(garbage),
        "empty_file": str(empty),
        "symlink_loop": str(loop),
    }


#: Every key and how to build its value (those of files need the scratch folder).
BUILDERS: dict[str, Any] = {
    "huge_range": lambda: range(10**9),
    "huge_tuple": lambda: HugeTuple((1, 2)),
    "huge_shape": HugeShape,
    "huge_mapping": HugeMapping,
    "non_finite_pose": lambda: (math.nan, math.inf, -math.inf),
    "non_finite_list": lambda: [math.nan, math.inf, 1.0, -math.inf],
    "nested_list": lambda: _nested_list(100_000),
    "nested_dict": lambda: _nested_dict(100_000),
    "nan": lambda: math.nan,
    "inf": lambda: math.inf,
    "minus_inf": lambda: -math.inf,
    "max_float": lambda: 1.7976931348623157e308,
    "min_float": lambda: -1.7976931348623157e308,
    "tiny_float": lambda: 5e-324,
    "big_int": lambda: 2**70,
    "minus_big_int": lambda: -(2**70),
    "minus_one": lambda: -1,
    "zero": lambda: 0,
    "true": lambda: True,
    "none": lambda: None,
    "empty_str": lambda: "",
    "long_str": lambda: "x" * 100_000,
    "nul_str": lambda: "seed\x00maze",
    "bytes": lambda: b"\x00\xff",
    "wrong_type": WrongType,
    "nan_array": lambda: np.full(4, np.nan),
    "empty_array": lambda: np.zeros((0,)),
    "big_array_shape": lambda: np.zeros((1, 1 << 20), np.float32),
    # Numbers and arrays of unusual kinds: a complex number (numpy's converts to a float with
    # a warning only), a masked array (whose mask a borrowed slice drops), numpy scalars of
    # other dtypes, a 0-d array, a path object whose __fspath__ raises.
    "complex_number": lambda: np.complex128(0.25 + 1j),
    "complex_array": lambda: np.zeros((2, 2), np.complex128),
    "masked_array": lambda: np.ma.masked_array(np.zeros((2, 2)), mask=True),
    "float16": lambda: np.float16(0.25),
    "datetime": lambda: np.datetime64("2020-01-01"),
    "zero_d_array": lambda: np.array(0.25),
    "memoryview": lambda: memoryview(bytes(16)),
    "raising_path": RaisingPath,
    "folder": None,
    "missing_path": None,
    "garbage_file": None,
    "empty_file": None,
    "symlink_loop": None,
    "world_file": None,
    "bytes_path": None,
}

#: The strings a command line option is given.
ARGUMENT_WORDS: dict[str, str] = {
    "nan": "nan",
    "inf": "inf",
    "minus_inf": "-inf",
    "max_float": "1e308",
    "over_float": "1e999",
    "big_int": str(2**70),
    "minus_one": "-1",
    "zero": "0",
    "empty_str": "",
    "long_str": "x" * 5000,
    "nul_free_odd": "\udcff",
    "folder": "@folder",
    "missing_path": "@missing_path",
    "garbage_file": "@garbage_file",
    "empty_file": "@empty_file",
    "symlink_loop": "@symlink_loop",
    "world_file": "@world_file",
}


def _absurd_profile() -> str:
    """The e-puck's profile with one sensor heading 1e300 rad: TOML holds it, no robot has it."""
    import re

    import mazesim

    text = mazesim.RobotProfile.builtin("e-puck").to_toml()
    return re.sub(r"heading = [^\n]*", "heading = 1e300", text, count=1)


_GRID = (
    'format = "mazesim-world"\nversion = 1\nname = "thick"\n[grid]\ncell_size = 0.25\n'
    'wall_thickness = {thickness}\nmap = """\n+--+--+\n|S  G |\n+--+--+\n"""\n'
)

#: Values an entry point must refuse (see ``registry.MUST_REFUSE``): absurd, but of the type its
#: parameter takes, so only a check of the value itself refuses them. They are never drawn for
#: the random calls (those draw from :data:`BUILDERS`), so adding one changes no other call.
ABSURD: dict[str, Any] = {
    "profile_heading_1e300": _absurd_profile,
    "grid_wall_as_thick_as_its_cell": lambda: _GRID.format(thickness="0.25"),
    "grid_wall_thicker_than_its_cell": lambda: _GRID.format(thickness="1e300"),
    "endless_lua_template": lambda: "%{ while true do end }%",
    "endless_javascript_template": lambda: "%< while (true) {} >%",
    # A regular expression that backtracks for hours (QuickJS's time limit is not looked at
    # inside its regular expressions).
    "redos_javascript_template": lambda: "%< /^(a+)+$/.test('a'.repeat(40) + 'b') >%",
    "period_2_40": lambda: 2**40,
    # Observations of two robots whose Sharp readings are not numbers, or infinite.
    "nan_observations": lambda: np.full((2, 6), np.nan, np.float32),
    "inf_observations": lambda: np.full((2, 6), np.inf, np.float32),
    "packet_over_bound": lambda: b"x" * (16 * 1024 * 1024 + 1),
    # A name no registry of mazesim holds (of an env, task, world, controller, robot...).
    "unknown_name": lambda: "no-such-name-zz",
    # The one robot's wheel speeds of seed-maze, all masked: no speed is given.
    "masked_commands": lambda: np.ma.masked_array(np.zeros((1, 2)), mask=True),
}

#: Valid values the other parameters of a must-refuse call are given.
VALID: dict[str, Any] = {
    "lua": lambda: "lua",
    "javascript": lambda: "javascript",
    "no_fields": dict,
    "origin": lambda: "hostile.proto",
    "quarter": lambda: 0.25,
    "one": lambda: 1.0,
}


def make(key: str, tmp: Path) -> Any:
    """The value of ``key``, built now (files in ``tmp``)."""
    for table in (ABSURD, VALID):
        if key in table:
            return table[key]()
    builder = BUILDERS[key]
    if builder is None:
        return _files(tmp)[key]
    return builder()


def word(key: str, tmp: Path) -> str:
    """The command-line word of ``key`` (files in ``tmp``)."""
    text = ARGUMENT_WORDS[key]
    return _files(tmp)[text[1:]] if text.startswith("@") else text


#: Valid values of the annotations a constructor's required parameters have, by type (``world``
#: is seed-maze, ``tmp`` the scratch folder).
def _samples(world: Any, tmp: Path) -> dict[Any, Any]:
    import argparse

    import mazesim
    from mazesim.webots import simulation

    return {
        simulation.RobotSimulation: lambda: simulation.prepare(world),
        mazesim.World: world,
        mazesim.Simulator: lambda: mazesim.Simulator(world),
        mazesim.BatchSimulator: lambda: mazesim.BatchSimulator(world, num_envs=2),
        mazesim.RobotProfile: lambda: mazesim.RobotProfile.builtin("seed"),
        argparse.Namespace: lambda: argparse.Namespace(),
        int: 1,
        float: 1.0,
        bool: False,
        str: "seed-maze",
        bytes: b"",
        Path: tmp / "sample",
    }


def _shipped() -> Any:
    from mazesim.learn import load_policy

    return load_policy()


def _navigator() -> Any:
    """The shipped navigator driving two robots of seed-maze."""
    from mazesim.learn.higher import HigherLevel
    from mazesim.learn.policy import HierarchicalPolicy

    policy = _shipped()
    higher = HigherLevel([policy.checkpoint_ids], q=policy.higher_q[None])
    return HierarchicalPolicy(policy.lower_q, higher, np.zeros(2, np.int64))


#: Valid values by parameter name, for parameters whose annotation cannot say what fits (an
#: array's shape, a navigator typed ``Any``): the shipped navigator's tables, two robots of
#: seed-maze. A name is the domain's word for its value, the same in every signature.
BY_NAME: dict[str, Any] = {
    "lower_q": lambda: _shipped().lower_q,
    "higher_q": lambda: _shipped().higher_q,
    "q": lambda: _shipped().higher_q,
    "flat_q": lambda: np.zeros((14, 4)),
    "navigator": lambda: _navigator(),
    "group": lambda: np.zeros(2, np.int64),
    "profiles": lambda: [__import__("mazesim").RobotProfile.builtin("seed")] * 2,
    "readings": lambda: [None],
    "checkpoint_ids": lambda: list(_shipped().checkpoint_ids),
    "world_of_env": lambda: np.zeros(2, np.int64),
    "num_envs": lambda: 2,
    "episodes": lambda: 1,
    "episodes_per_world": lambda: 1,
    "delays": lambda: np.zeros(2, np.int64),
    "linked": lambda: np.zeros(2, bool),
    "codes": lambda: ["10110", "11010"],
    "kind": lambda: "hierarchical",
    "worlds": lambda: [__import__("mazesim").World.builtin("seed-maze")],
    "world_tomls": lambda: (__import__("mazesim").World.builtin("seed-maze").to_toml(),),
    "events": lambda: "truth",
    "stall_seconds": lambda: 1.0,
    "stop": lambda: KeyboardInterrupt,
    "read_encoders": lambda: lambda: np.zeros(2),
    "wheel_radius": lambda: 0.02,
    "axle_length": lambda: 0.05685,
    "ray_length": lambda: 0.07,
    "control_step_ms": lambda: 64.0,
    "controller": lambda: "braitenberg",
    "robots": lambda: [{"name": "e-puck"}],
    "simulators": lambda: [
        __import__("mazesim").Simulator(__import__("mazesim").World.builtin("seed-maze"))
    ],
}


def _public_classes() -> list[type]:
    """The public classes of the modules of the package imported so far."""
    import inspect
    import sys

    from mazesim._checks import is_public_module, public_names

    found = []
    for name, module in list(sys.modules.items()):
        if module is None or not is_public_module(name):
            continue
        for member in public_names(module):
            obj = getattr(module, member, None)
            if inspect.isclass(obj) and not inspect.isabstract(obj):
                found.append(obj)
    return found


def _implementations(hint: type) -> list[type]:
    """The package's concrete classes that are, or structurally fit, the class ``hint`` (an
    abstract base class or a protocol)."""
    if getattr(hint, "_is_protocol", False):
        wanted = [n for n in vars(hint) if not n.startswith("_")]
        return [c for c in _public_classes() if all(callable(getattr(c, n, None)) for n in wanted)]
    return [c for c in _public_classes() if issubclass(c, hint) and c is not hint]


_FACTORIES: dict[Any, list[Any]] = {}


def _factories(hint: type) -> list[Any]:
    """The package's public functions, static and class methods whose result is a ``hint``
    (every public module imported first, so the answer is the same in every process)."""
    import inspect
    import sys

    from mazesim._checks import is_public_module, public_names

    if not _FACTORIES:
        from surface.registry import python_entry_points

        python_entry_points()  # imports every public module
        found = []
        for cls in _public_classes():
            for member in vars(cls).values():
                if isinstance(member, (staticmethod, classmethod)):
                    found.append(getattr(cls, member.__func__.__name__))
        for name, module in list(sys.modules.items()):
            if module is not None and is_public_module(name):
                found += [getattr(module, n) for n in public_names(module)]
        for f in found:
            if inspect.isroutine(f):
                _FACTORIES.setdefault(_hints(f).get("return"), []).append(f)
        _FACTORIES.setdefault(None, [])
    return _FACTORIES.get(hint, [])


def _sampled_arguments(function: Any, value_of: Any) -> dict[str, Any]:
    """Valid values of ``function``'s required parameters: by name (:data:`BY_NAME`), else by
    annotation (``value_of``)."""
    import inspect

    from mazesim._checks import refusal

    hints = _hints(function)
    arguments = {}
    for p in inspect.signature(function).parameters.values():
        if p.name in ("self", "cls"):
            continue
        if p.default is p.empty and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
            hint = hints.get(p.name, Any)
            named = BY_NAME[p.name]() if p.name in BY_NAME else None
            fits = p.name in BY_NAME and refusal(named, hint) is None
            arguments[p.name] = named if fits else value_of(hint)
    return arguments


def _hints(function: Any) -> dict[str, Any]:
    from mazesim._checks import annotations_of

    return annotations_of(function)


def sample_instance(cls: type, world: Any, tmp: Path, depth: int = 0) -> Any:
    """An instance of ``cls`` made from its constructor's annotations: each required parameter
    is given a valid value, by its name (:data:`BY_NAME`), else by its annotated type (the
    package's classes made the same way, a level deeper; an abstract class or a protocol by one
    of the package's classes that implements it). Raises when a parameter has no sample."""
    import inspect

    value_of = _value_maker(world, tmp, depth)
    if inspect.isabstract(cls) or getattr(cls, "_is_protocol", False):
        return value_of(cls)  # one of its implementations
    init = inspect.unwrap(cls.__init__)  # type: ignore[misc]
    try:
        return cls(**_sampled_arguments(init, value_of))
    except Exception:
        for factory in _factories(cls):  # else the package's own functions that make one
            try:
                return factory(**_sampled_arguments(factory, value_of))
            except Exception:  # noqa: BLE001, S112 - try the next factory
                continue
        raise


def sample_arguments(function: Any, world: Any, tmp: Path) -> dict[str, Any]:
    """Valid values of ``function``'s required parameters, as :func:`sample_instance` gives a
    constructor's. Raises when a parameter has no sample."""
    return _sampled_arguments(function, _value_maker(world, tmp, 0))


def _value_maker(world: Any, tmp: Path, depth: int) -> Any:
    """The function that makes a valid value of an annotation (see :func:`sample_instance`)."""
    import inspect
    import typing

    samples = _samples(world, tmp)

    def value_of(hint: Any) -> Any:
        if hint in samples:
            sample = samples[hint]
            return sample() if callable(sample) and not isinstance(sample, type) else sample
        origin, args = typing.get_origin(hint), typing.get_args(hint)
        if origin is typing.Annotated:  # a registered name is a str
            return value_of(args[0])
        if origin is typing.Union or str(origin) == "<class 'types.UnionType'>":
            if type(None) in args:
                return None
            return value_of(args[0])
        if origin in (list, tuple) or str(origin).startswith("<class 'collections.abc"):
            return [value_of(args[0])] if args and args[0] is not Ellipsis else []
        if origin is dict:
            return {}
        if origin is type:
            return args[0] if args and isinstance(args[0], type) else object
        if isinstance(hint, type) and hint.__module__.startswith("mazesim") and depth < 4:
            if inspect.isabstract(hint) or getattr(hint, "_is_protocol", False):
                for concrete in _implementations(hint):
                    try:
                        return sample_instance(concrete, world, tmp, depth + 1)
                    except Exception:  # noqa: BLE001, S112 - try the next implementation
                        continue
                raise TypeError(f"no implementation of {hint!r} could be made")
            return sample_instance(hint, world, tmp, depth + 1)
        raise TypeError(f"no sample of {hint!r}")

    return value_of
