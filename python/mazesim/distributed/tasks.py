"""A sweep's task: train one setting, evaluate it, and hand back its result and its files.

A task is a function ``task(setting, threads) -> TaskOutput``. It runs in a Ray worker, or in the
calling process for the sequential runner, and writes nothing itself: its files (tables, curves,
metadata) come back as bytes and the driver writes them into the sweep's output folder
(:func:`mazesim.distributed.output.write_run_folder`), so workers on other machines need no
shared file system.

The default task, :func:`train_and_evaluate`, runs the setting's trainer. Trainers are looked up
by name in :data:`TRAINERS`; ``"auto"`` picks the first of :data:`AUTO_ORDER` that this
installation has. A trainer is a function ``trainer(setting, threads) -> dict`` returning
``tables`` (name -> array), ``curves`` (name -> equal-length 1-D array), ``evaluation``
(``success_rate``, ``mean_collisions``, ``mean_steps``), ``env_steps``, ``eval_env_steps``,
``training_seconds`` and ``evaluation_seconds``. ``hrl`` and ``baseline`` (also named
``flat-q``; :mod:`mazesim.distributed.hrl_trainers`) train mazesim's hierarchical navigator and
its one flat learner, both from :mod:`mazesim.learn`.
"""

from __future__ import annotations

import csv
import importlib
import io
import json
import math
import socket
import zipfile
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from mazesim._core import __version__
from mazesim.errors import (
    InvalidArgumentError,
    RegisteredName,
    UnknownNameError,
    _known_name,
    _shown,
)

if TYPE_CHECKING:
    from mazesim.distributed.config import Setting

__all__ = [
    "AUTO_ORDER",
    "CURVES_FILE",
    "RUN_FILE",
    "TABLES_FILE",
    "TRAINERS",
    "UNUSED_PARAMETERS",
    "Task",
    "TaskOutput",
    "check_parameters",
    "curves_csv",
    "execute_task",
    "npz_bytes",
    "resolve_trainer",
    "train_and_evaluate",
]

#: Trainers by name: where each one's function lives, ``"module:function"``.
TRAINERS: dict[str, str] = {
    "hrl": "mazesim.distributed.hrl_trainers:train_hrl",
    "baseline": "mazesim.distributed.hrl_trainers:train_baseline",
    # The former name of the flat learner's trainer: the package has one flat learner.
    "flat-q": "mazesim.distributed.hrl_trainers:train_baseline",
}
#: What ``trainer = "auto"`` picks: the first of these that is installed.
AUTO_ORDER: tuple[str, ...] = ("hrl", "baseline")

#: Parameters a trainer has no use for: a setting of that trainer must leave them out (``None``).
UNUSED_PARAMETERS: dict[str, tuple[str, ...]] = {
    "hrl": ("collision_penalty",),
    "baseline": ("higher_episodes",),
    "flat-q": ("higher_episodes",),
}
#: Values a trainer cannot run without.
_REQUIRED_VALUES: dict[str, dict[str, Any]] = {
    "hrl": {"noise": True},
    "baseline": {"noise": True},
    "flat-q": {"noise": True},
}

#: The trained tables of a run, an ``.npz`` archive (no pickled objects).
TABLES_FILE = "tables.npz"
#: The training curve of a run, a CSV table.
CURVES_FILE = "curves.csv"
#: The setting and result of a run, JSON.
RUN_FILE = "run.json"
#: Version of the run folder's layout, written into :data:`RUN_FILE`.
RUN_FORMAT = 1


@dataclass(frozen=True)
class TaskOutput:
    """What a task hands back to the driver.

    Attributes:
        result: JSON values: ``success_rate``, ``mean_collisions``, ``mean_steps``,
            ``env_steps``, ``eval_env_steps``, ``training_seconds``, ``evaluation_seconds``,
            ``trainer``, ``threads`` and ``host``.
        files: The run's files by name (no folders), written into its folder by the driver.
    """

    result: dict[str, Any]
    files: dict[str, bytes]

    def __repr__(self) -> str:
        """The result in full and each file by its name and size (a run's tables are megabytes
        of bytes, which a printed output would otherwise pour onto the screen)."""
        files = ", ".join(f"{name!r}: <{len(data):,} bytes>" for name, data in self.files.items())
        return f"TaskOutput(result={self.result!r}, files={{{files}}})"


Task = Callable[["Setting", int], TaskOutput]


def _trainer_function(name: str) -> Callable[[Setting, int], dict[str, Any]] | None:
    """The function registered as ``name``, or ``None`` if its module is not installed."""
    module_name, _, function_name = TRAINERS[name].partition(":")
    try:
        module = importlib.import_module(module_name)
    except ModuleNotFoundError:
        return None
    function = getattr(module, function_name, None)
    return function if callable(function) else None


def resolve_trainer(name: RegisteredName) -> str:
    """The registered trainer that ``name`` stands for (``"auto"``: see :data:`AUTO_ORDER`).

    Raises:
        UnknownNameError: No trainer has that name, or it is not installed.
    """
    if name == "auto":
        for candidate in AUTO_ORDER:
            if candidate in TRAINERS and _trainer_function(candidate) is not None:
                return candidate
    available = [n for n in TRAINERS if _trainer_function(n) is not None]
    return _known_name(name, "a trainer", ("auto", *available)) if name != "auto" else name


def check_parameters(params: Mapping[str, Any], where: str = "grid") -> None:
    """Refuses a setting that sets a parameter its trainer has no use for, or a value it cannot
    run with (see :data:`UNUSED_PARAMETERS`); trainers not listed there take any setting.

    Raises:
        InvalidArgumentError: Naming the parameter and the trainer.
    """
    trainer = str(params.get("trainer"))
    for name in UNUSED_PARAMETERS.get(trainer, ()):
        if params.get(name) is not None:
            raise InvalidArgumentError(
                f"{where}.{name}: trainer {_shown(trainer)} does not use it; expected it left out, "
                f"found {_shown(params[name])}"
            )
    for name, value in _REQUIRED_VALUES.get(trainer, {}).items():
        if params.get(name) != value:
            raise InvalidArgumentError(
                f"{where}.{name}: trainer {_shown(trainer)} runs with {name} = "
                f"{json.dumps(value)} only, found {json.dumps(params.get(name))}"
            )


def npz_bytes(arrays: Mapping[str, npt.ArrayLike]) -> bytes:
    """An ``.npz`` archive of the arrays, stored uncompressed, the same bytes for the same arrays
    (:func:`mazesim.learn.tables.write_archive`); :func:`numpy.load` reads it."""
    from mazesim.learn.tables import write_archive

    return write_archive(arrays, compression=zipfile.ZIP_STORED)


def curves_csv(curves: Mapping[str, npt.ArrayLike]) -> bytes:
    """A CSV table of equal-length columns (floats written to round-trip exactly)."""
    columns = {name: np.asarray(values).ravel() for name, values in curves.items()}
    lengths = {values.size for values in columns.values()}
    if len(lengths) > 1:
        raise InvalidArgumentError(f"expected curves of one length, found lengths {lengths}")
    text = io.StringIO()
    writer = csv.writer(text, lineterminator="\n")
    writer.writerow(columns)
    for row in zip(*columns.values()):
        writer.writerow([value.item() for value in row])
    return text.getvalue().encode("utf-8")


def _json_number(value: float) -> float | None:
    return None if not math.isfinite(value) else value


def train_and_evaluate(setting: Setting, threads: int = 1) -> TaskOutput:
    """The default task: trains the setting with its trainer and evaluates the greedy policy.

    Args:
        setting: The setting to run.
        threads: Batch-engine threads.

    Returns:
        The result and the files ``tables.npz``, ``curves.csv`` and ``run.json``.
    """
    name = str(setting.params["trainer"])
    trainer = _trainer_function(name) if name in TRAINERS else None
    if trainer is None:
        raise UnknownNameError(f"trainer {_shown(name)} is not installed on {socket.gethostname()}")
    check_parameters(setting.params, f"setting {setting.id}")
    run = trainer(setting, threads)
    evaluation = run["evaluation"]
    result = {
        "success_rate": _json_number(float(evaluation["success_rate"])),
        "mean_collisions": _json_number(float(evaluation["mean_collisions"])),
        "mean_steps": _json_number(float(evaluation["mean_steps"])),
        "env_steps": int(run["env_steps"]),
        "eval_env_steps": int(run["eval_env_steps"]),
        "training_seconds": float(run["training_seconds"]),
        "evaluation_seconds": float(run["evaluation_seconds"]),
        "trainer": name,
        "threads": threads,
        "host": socket.gethostname(),
    }
    metadata = {
        "format": RUN_FORMAT,
        "mazesim_version": __version__,
        "setting": setting.to_json(),
        "tables": {key: list(np.shape(value)) for key, value in run["tables"].items()},
        "result": result,
    }
    files = {
        TABLES_FILE: npz_bytes(run["tables"]),
        CURVES_FILE: curves_csv(run["curves"]),
        RUN_FILE: (json.dumps(metadata, indent=2) + "\n").encode("utf-8"),
    }
    return TaskOutput(result=result, files=files)


def execute_task(task: Task, setting: Setting, threads: int) -> TaskOutput:
    """The body of a sweep's Ray task: runs ``task`` in the worker (a module-level function, so
    that workers import only this module and what the task needs)."""
    return task(setting, threads)
