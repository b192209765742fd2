"""The hostile values fed to the public surface, by key: huge lengths, nesting, non-finite and
extreme numbers, wrong types, special files. The keys are what hypothesis draws (plans are plain
data that cross into the runner's process); :func:`make` builds the value in that process.

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
    return {
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
    "folder": None,
    "missing_path": None,
    "garbage_file": None,
    "empty_file": None,
    "symlink_loop": None,
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
}


def make(key: str, tmp: Path) -> Any:
    """The value of ``key``, built now (files in ``tmp``)."""
    builder = BUILDERS[key]
    if builder is None:
        return _files(tmp)[key]
    return builder()


def word(key: str, tmp: Path) -> str:
    """The command-line word of ``key`` (files in ``tmp``)."""
    text = ARGUMENT_WORDS[key]
    return _files(tmp)[text[1:]] if text.startswith("@") else text


#: Valid values of the annotations a constructor's required parameters have, by type name, for
#: the generic instance recipe (``world`` is seed-maze, ``tmp`` the scratch folder).
def _samples(world: Any, tmp: Path) -> dict[Any, Any]:
    import mazesim
    from mazesim.webots import simulation

    return {
        simulation.RobotSimulation: lambda: simulation.prepare(world),
        mazesim.World: world,
        mazesim.Simulator: lambda: mazesim.Simulator(world),
        mazesim.BatchSimulator: lambda: mazesim.BatchSimulator(world, num_envs=2),
        mazesim.RobotProfile: lambda: mazesim.RobotProfile.builtin("e-puck"),
        int: 1,
        float: 1.0,
        bool: False,
        str: "seed-maze",
        bytes: b"",
        Path: tmp / "sample",
    }


def sample_instance(cls: type, world: Any, tmp: Path, depth: int = 0) -> Any:
    """An instance of ``cls`` made from its constructor's annotations: each required parameter
    is given a valid value of its annotated type (the package's classes made the same way, a
    level deeper). Raises when a parameter's type has no sample."""
    import inspect
    import typing

    samples = _samples(world, tmp)

    def value_of(hint: Any) -> Any:
        if hint in samples:
            sample = samples[hint]
            return sample() if callable(sample) and not isinstance(sample, type) else sample
        origin, args = typing.get_origin(hint), typing.get_args(hint)
        if origin is typing.Union or str(origin) == "<class 'types.UnionType'>":
            if type(None) in args:
                return None
            return value_of(args[0])
        if origin in (list, tuple) or str(origin).startswith("<class 'collections.abc"):
            return [value_of(args[0])] if args and args[0] is not Ellipsis else []
        if origin is dict:
            return {}
        if isinstance(hint, type) and hint.__module__.startswith("mazesim") and depth < 3:
            return sample_instance(hint, world, tmp, depth + 1)
        raise TypeError(f"no sample of {hint!r}")

    init = inspect.unwrap(cls.__init__)  # type: ignore[misc]
    hints = typing.get_type_hints(init, vars(inspect.getmodule(cls)))
    arguments = {}
    for p in list(inspect.signature(init).parameters.values())[1:]:
        if p.default is p.empty and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
            arguments[p.name] = value_of(hints.get(p.name, Any))
    return cls(**arguments)
