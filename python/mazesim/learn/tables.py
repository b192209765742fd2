"""Saving and loading navigators: Q-tables as ``.npz`` (no pickle) plus JSON metadata.

A saved navigator is a folder with two files:

- ``tables.npz``: the Q-tables as float64 arrays, written with :func:`numpy.savez_compressed` and
  read with ``allow_pickle=False``. A hierarchical navigator holds ``corridor`` (4096 x 12),
  ``right``, ``left`` and ``forward`` (12288 x 12: 4096 distance states times 3 phases) and
  ``higher`` (states x 4, the rows of :func:`mazesim.learn.higher.event_state_names`); the flat
  baseline holds ``flat`` ((1 + 2 * checkpoints) * 4096 x 12).
- ``policy.json``: what the tables mean, checked on loading. ``format`` (``"mazesim-policy"``)
  and ``version`` (:data:`FORMAT_VERSION`); ``kind`` (``"hierarchical"`` or ``"flat"``);
  ``state_encoding`` (sensor order, Table 4.1 level edges in cm, the base-4 formula, the Sharp
  table the volts are inverted with); ``actions`` (codes and wheel speeds as fractions of the motor
  limit); ``control_step_ms``; ``subtasks`` (name, short code, phases and phase rule, table name);
  ``world`` (name, sha256 of :meth:`mazesim.World.to_toml`, checkpoint ids, the higher level's
  state names); ``training`` (the settings and measurements of the run); ``tables`` (each array's
  shape, and the size and sha256 of ``tables.npz``).

Both files are written atomically, the metadata last (:mod:`mazesim.learn.bundle`).
:func:`load_policy` checks the metadata against a schema (:func:`policy_schema`) before it reads
the tables, and the tables' headers against the shapes the metadata allows before it reads their
data, so no file decides how much memory is used. It raises
:class:`mazesim.errors.PolicyFormatError` naming the file, the field and the reason when a file is
missing, truncated, corrupt (its sha256 differs), malformed, of another format or version, made
for another state or action encoding, or has tables of the wrong shape or non-finite values.
:meth:`TrainedPolicy.check_world` refuses a world other than the one the higher level learned.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._core import World
from mazesim.actions import ACTION_CODES, WHEEL_SPEED_FRACTIONS
from mazesim.errors import InvalidArgumentError, PolicyFormatError, UnknownNameError
from mazesim.learn.archive import ArraySpec
from mazesim.learn.bundle import (
    FORMAT_VERSION,
    HEX_DIGITS,
    read_bundle,
    tables_schema,
    write_bundle,
)
from mazesim.learn.discretise import LEVEL_EDGES_CM, NUM_STATES, SENSOR_ORDER, SHARP_TABLE
from mazesim.learn.higher import event_state_names
from mazesim.learn.lower import lower_table_shape
from mazesim.learn.schema import AnyJson, ListOf, Record, Text, Whole, differing
from mazesim.learn.subtasks import (
    CONTROL_STEP_MS,
    DISTANCE_EDGES,
    DISTANCE_PHASES,
    FORWARD_PHASE_ANGLE,
    SUBTASK_ACTIONS,
    SUBTASK_CODES,
    SUBTASK_NAMES,
    TURN_PHASE_ANGLES,
    door_distance_of,
    phase_counts,
)
from mazesim.maze import world_hash

__all__ = [
    "FORMAT",
    "FORMAT_VERSION",
    "METADATA_FILE",
    "SHIPPED_NAVIGATORS",
    "TABLES_FILE",
    "TrainedPolicy",
    "encoding_metadata",
    "load_policy",
    "navigator_folder",
    "policy_arrays",
    "policy_schema",
    "read_bundle",
    "save_policy",
    "shipped_policy_dir",
    "write_bundle",
]

FORMAT = "mazesim-policy"
METADATA_FILE = "policy.json"
TABLES_FILE = "tables.npz"
#: The lower-level table of each sub-task, by number.
SUBTASK_TABLES = ("corridor", "right", "left", "forward")
KINDS = ("hierarchical", "flat")


def encoding_metadata(door_distance: bool = False) -> dict[str, Any]:
    """The state and action encoding this version of mazesim uses, as saved and checked; with
    ``door_distance`` the door sub-tasks' phases count the distance driven too
    (:data:`mazesim.learn.subtasks.DISTANCE_PHASES`)."""
    phase_rules = [
        "none",
        f"heading turned towards the side: < {np.degrees(TURN_PHASE_ANGLES[0]):.0f} deg -> 0, "
        f"< {np.degrees(TURN_PHASE_ANGLES[1]):.0f} deg -> 1, else 2",
        f"heading turned towards the side: < {np.degrees(TURN_PHASE_ANGLES[0]):.0f} deg -> 0, "
        f"< {np.degrees(TURN_PHASE_ANGLES[1]):.0f} deg -> 1, else 2",
        f"heading change: < -{np.degrees(FORWARD_PHASE_ANGLE):.0f} deg -> 0, "
        f"> {np.degrees(FORWARD_PHASE_ANGLE):.0f} deg -> 2, else 1",
    ]
    if door_distance:
        edges = ", ".join(
            f"< {100 * edge:.0f} cm -> {place}" for place, edge in enumerate(DISTANCE_EDGES)
        )
        phase_rules[1:] = [
            f"({rule}) + 3 * (metres ahead of the start along its heading: {edges}, "
            f"else {len(DISTANCE_EDGES)})"
            for rule in phase_rules[1:]
        ]
    phases = phase_counts(door_distance)
    return {
        "state_encoding": {
            "sensors": list(SENSOR_ORDER),
            "level_edges_cm": list(LEVEL_EDGES_CM),
            "levels": len(LEVEL_EDGES_CM) + 1,
            "formula": "state = sum(level[i] * 4**i), i = place in sensors",
            "states": NUM_STATES,
            "volts_to_cm": "inverse of sharp_table, piecewise linear, clamped",
            "sharp_table": [list(row) for row in SHARP_TABLE],
        },
        "actions": [
            {"code": code, "left": float(left), "right": float(right)}
            for code, (left, right) in zip(ACTION_CODES, WHEEL_SPEED_FRACTIONS)
        ],
        "control_step_ms": CONTROL_STEP_MS,
        "subtasks": [
            {
                "number": number,
                "name": SUBTASK_NAMES[number],
                "code": SUBTASK_CODES[number],
                "phases": phases[number],
                "phase_rule": phase_rules[number],
                "table": SUBTASK_TABLES[number],
                "state": "distance_state + 4096 * phase",
                "actions": [
                    code for code, allowed in zip(ACTION_CODES, SUBTASK_ACTIONS[number]) if allowed
                ],
            }
            for number in range(len(SUBTASK_NAMES))
        ],
    }


def shipped_policy_dir(world_name: str = "seed-maze") -> Path:
    """The folder of the navigator shipped in the package for a built-in world."""
    return Path(str(resources.files("mazesim.learn").joinpath("data", world_name)))


#: Navigators shipped beside the default one, by the name ``load_policy`` (and ``--policy``)
#: takes for them when no folder of that name exists: their folders in the package's data.
SHIPPED_NAVIGATORS = {"randomised": "seed-maze-randomised"}


def navigator_folder(folder: str | os.PathLike[str] | None = None) -> Path:
    """The folder of a navigator: ``folder`` itself, the shipped seed-maze navigator's for None,
    or a shipped navigator's for its name in :data:`SHIPPED_NAVIGATORS` (``"randomised"``)
    when no folder of that name exists."""
    if folder is None:
        return shipped_policy_dir()
    path = Path(folder)
    name = os.fspath(folder)
    if name in SHIPPED_NAVIGATORS and not path.exists():
        return shipped_policy_dir(SHIPPED_NAVIGATORS[name])
    return path


@dataclass
class TrainedPolicy:
    """A navigator loaded from (or about to be saved to) a folder.

    Attributes:
        kind: ``"hierarchical"`` or ``"flat"``.
        lower_q: The stacked lower-level tables (hierarchical), shape
            :func:`mazesim.learn.lower.lower_table_shape`.
        higher_q: The higher level's table for its world, ``(2 * checkpoints, 4)``.
        flat_q: The flat baseline's table.
        world_name: The world the higher level (or the flat table) learned.
        world_sha256: That world's sha256 (see :func:`mazesim.maze.world_hash`).
        world_file: The absolute path of the world file it learned, or None for a built-in world
            (navigators saved before mazesim kept it have none either).
        checkpoint_ids: That world's checkpoint ids, in table order.
        training: The training settings and measurements.
        source: The folder it was loaded from, if any.
    """

    kind: str
    world_name: str
    world_sha256: str
    checkpoint_ids: list[int]
    world_file: str | None = None
    lower_q: npt.NDArray[np.float64] | None = None
    higher_q: npt.NDArray[np.float64] | None = None
    flat_q: npt.NDArray[np.float64] | None = None
    training: dict[str, Any] = field(default_factory=dict)
    source: str | None = None
    _driver: Any = field(default=None, repr=False, compare=False)

    @property
    def hold_heading(self) -> bool:
        """Whether its "Corridors and Corners" holds the heading on the grid where no sensor
        sees a wall, as it was trained to (``mazesim train --hold-heading``, recorded in
        :attr:`training` ``["lower"]``; :mod:`mazesim.learn.heading_hold`). Every runner of the
        navigator in mazesim applies the rule when this is true."""
        lower = self.training.get("lower")
        return isinstance(lower, dict) and lower.get("hold_heading") is True

    def reset(self, control_step_ms: float = CONTROL_STEP_MS) -> None:
        """Starts an episode of :meth:`act`: one robot driven step by step (the hook of the ROS
        perform-learning node, :mod:`mazesim.ros.perform_learning`).

        Args:
            control_step_ms: How long each action runs on the robot; the sub-tasks' odometry is
                dead-reckoned from the actions with it.
        """
        if self.kind == "flat":
            from mazesim.learn.baseline import FlatNavigator

            assert self.flat_q is not None
            self._driver = _FlatDriver(FlatNavigator(self.flat_q, self.checkpoint_ids, 1))
            return
        from mazesim.learn.higher import HigherLevel
        from mazesim.learn.policy import DeadReckoningNavigator

        assert self.lower_q is not None and self.higher_q is not None
        level = HigherLevel([self.checkpoint_ids], q=self.higher_q[None])
        self._driver = DeadReckoningNavigator(
            self.lower_q, level, control_step_ms, hold_heading=self.hold_heading
        )

    def act(self, distances_cm: npt.ArrayLike, checkpoint: int) -> str:
        """The action code for one robot's six distances in cm (front, back, left, right,
        left-front, right-front) and the checkpoint event of its last step (+id, -id or 0)."""
        if self._driver is None:
            self.reset()
        return str(self._driver.act(distances_cm, checkpoint))

    def learned_world(self) -> World:
        """The world it learned: the built-in world of its name, or the world file it was trained
        on (:attr:`world_file`).

        Raises:
            UnknownNameError: Neither is there (the file was moved or deleted); the message says
                where it was and how to name the world instead.
            WorldFormatError: The file is no longer a valid world.
        """
        from mazesim import load_world
        from mazesim._core import builtin_world_names

        if self.world_name in builtin_world_names() or self.world_file is None:
            return load_world(self.world_name)
        if not os.path.isfile(self.world_file):
            where = f" {self.source}" if self.source else ""
            raise UnknownNameError(
                f"the navigator{where} learned world {self.world_name!r} from "
                f"{self.world_file}, which is no longer there: put the file back, or name the "
                "world with --world FILE"
            )
        return load_world(self.world_file)

    def check_world(self, world: World) -> None:
        """Raises :class:`PolicyFormatError` unless ``world`` is the world it learned."""
        digest = world_hash(world)
        if digest != self.world_sha256:
            where = f" ({self.source})" if self.source else ""
            raise PolicyFormatError(
                f"the navigator{where} learned world {self.world_name!r} "
                f"(sha256 {self.world_sha256[:12]}...), "
                f"not {world.name!r} (sha256 {digest[:12]}...)"
            )


class _FlatDriver:
    """The flat baseline driving one robot from distances in cm (see :meth:`TrainedPolicy.act`)."""

    def __init__(self, navigator: Any) -> None:
        self.navigator = navigator
        self.navigator.reset([0], None)

    def act(self, distances_cm: npt.ArrayLike, checkpoint: int) -> str:
        from mazesim.learn.discretise import distance_levels

        levels = distance_levels(np.asarray(distances_cm, dtype=np.float64).reshape(1, 6))
        state = self.navigator.states_from_levels(levels, np.array([int(checkpoint)]))
        return ACTION_CODES[int(np.argmax(self.navigator.q[state[0]]))]


def save_policy(policy: TrainedPolicy, folder: str | os.PathLike[str]) -> None:
    """Writes a navigator into ``folder`` as ``tables.npz`` and ``policy.json``."""
    arrays: dict[str, npt.NDArray[Any]] = {}
    door_distance = False
    if policy.kind == "hierarchical":
        if policy.lower_q is None or policy.higher_q is None:
            raise PolicyFormatError("a hierarchical navigator needs lower and higher tables")
        try:
            door_distance = door_distance_of(int(policy.lower_q.shape[1]))
        except InvalidArgumentError as error:
            raise PolicyFormatError(str(error)) from None
        for number, name in enumerate(SUBTASK_TABLES):
            rows = phase_counts(door_distance)[number] * NUM_STATES
            arrays[name] = np.ascontiguousarray(policy.lower_q[number, :rows], dtype=np.float64)
        arrays["higher"] = np.asarray(policy.higher_q, dtype=np.float64)
    elif policy.kind == "flat":
        if policy.flat_q is None:
            raise PolicyFormatError("a flat navigator needs its table")
        arrays["flat"] = np.asarray(policy.flat_q, dtype=np.float64)
    else:
        raise PolicyFormatError(f"expected a kind in {KINDS}, found {policy.kind!r}")
    metadata: dict[str, Any] = {"format": FORMAT, "version": FORMAT_VERSION, "kind": policy.kind}
    metadata.update(encoding_metadata(door_distance))
    metadata["world"] = {
        "name": policy.world_name,
        "sha256": policy.world_sha256,
        "checkpoints": list(policy.checkpoint_ids),
        "higher_states": event_state_names(policy.checkpoint_ids),
    }
    if policy.world_file is not None:
        metadata["world"]["file"] = policy.world_file
    metadata["training"] = policy.training
    write_bundle(folder, TABLES_FILE, METADATA_FILE, arrays, metadata)


#: The most checkpoints a navigator's world may have, and the largest checkpoint id.
MAX_CHECKPOINTS = 1024
MAX_CHECKPOINT_ID = 65535


def policy_schema() -> Record:
    """The schema of ``policy.json`` (the encoding entries are compared with this mazesim's)."""
    return Record(
        {
            "format": Text(choices=(FORMAT,)),
            "version": Whole(FORMAT_VERSION, FORMAT_VERSION),
            "kind": Text(choices=KINDS),
            "state_encoding": AnyJson(),
            "actions": AnyJson(),
            "control_step_ms": AnyJson(),
            "subtasks": AnyJson(),
            "world": Record(
                {
                    "name": Text(max_length=256),
                    "sha256": Text(length=64, alphabet=HEX_DIGITS),
                    "checkpoints": ListOf(Whole(1, MAX_CHECKPOINT_ID), 0, MAX_CHECKPOINTS),
                    "higher_states": ListOf(Text(max_length=16), 0, 2 * MAX_CHECKPOINTS),
                    "file": Text(max_length=4096),
                },
                optional=frozenset({"file"}),
            ),
            "training": Record({}, open=True, others=AnyJson()),
            "tables": tables_schema(TABLES_FILE),
        }
    )


def _encoding_keys(metadata: dict[str, Any], expected: dict[str, Any]) -> str | None:
    """The first encoding entry of ``metadata`` that differs from ``expected``, if any."""
    for key in ("state_encoding", "actions", "control_step_ms", "subtasks"):
        if metadata.get(key) != expected[key]:
            return key
    return None


def _check_encoding(metadata: dict[str, Any], where: Path) -> bool:
    """Checks the encoding against this mazesim's, with heading phases or with the distance;
    returns whether the tables count the distance (``door_distance``)."""
    plain = encoding_metadata()
    if _encoding_keys(metadata, encoding_metadata(True)) is None:
        return True
    key = _encoding_keys(metadata, plain)
    if key is not None:
        raise PolicyFormatError(
            f"{where}: made for another {key.replace('_', ' ')} than this mazesim uses "
            f"({differing(json.dumps(plain[key]), json.dumps(metadata.get(key)))})"
        )
    return False


def _check_world(world: dict[str, Any], where: Path) -> None:
    checkpoints = world["checkpoints"]
    if len(set(checkpoints)) != len(checkpoints):
        raise PolicyFormatError(
            f"{where}: world.checkpoints: expected distinct ids, found {checkpoints[:20]}"
        )
    if world["higher_states"] != event_state_names(checkpoints):
        expected, found = event_state_names(checkpoints), world["higher_states"]
        raise PolicyFormatError(
            f"{where}: world.higher_states: {differing(json.dumps(expected), json.dumps(found))}"
        )


def policy_arrays(metadata: dict[str, Any]) -> dict[str, ArraySpec]:
    """The tables a navigator's archive must hold, from its checked metadata."""
    actions = len(ACTION_CODES)
    checkpoints = len(metadata["world"]["checkpoints"])
    if metadata["kind"] == "flat":
        return {"flat": ArraySpec(((1 + 2 * checkpoints) * NUM_STATES, actions), "float64")}
    phases = [int(subtask["phases"]) for subtask in metadata["subtasks"]]
    arrays = {
        name: ArraySpec((phases[number] * NUM_STATES, actions), "float64")
        for number, name in enumerate(SUBTASK_TABLES)
    }
    arrays["higher"] = ArraySpec((2 * checkpoints, 4), "float64")
    return arrays


def _checked_policy_arrays(where: Path) -> Any:
    """:func:`policy_arrays` after the checks that need this mazesim's encoding and world rules."""

    def arrays_of(metadata: dict[str, Any]) -> dict[str, ArraySpec]:
        _check_encoding(metadata, where)
        _check_world(metadata["world"], where)
        return policy_arrays(metadata)

    return arrays_of


def load_policy(folder: str | os.PathLike[str] | None = None) -> TrainedPolicy:
    """Loads a navigator saved by :func:`save_policy` (by default the one shipped for seed-maze;
    ``"randomised"``: the one trained with domain randomisation, see :func:`navigator_folder`).

    Raises:
        PolicyFormatError: The folder does not hold a usable navigator (the message says why).
    """
    path = navigator_folder(folder)
    meta_path = path / METADATA_FILE
    arrays, metadata = read_bundle(
        path,
        TABLES_FILE,
        METADATA_FILE,
        FORMAT,
        schema=policy_schema(),
        arrays_of=_checked_policy_arrays(meta_path),
    )
    kind = metadata["kind"]
    world = metadata["world"]
    checkpoints = [int(c) for c in world["checkpoints"]]
    policy = TrainedPolicy(
        kind=str(kind),
        world_name=str(world["name"]),
        world_sha256=str(world["sha256"]),
        checkpoint_ids=checkpoints,
        world_file=str(world["file"]) if "file" in world else None,
        training=dict(metadata["training"]),
        source=str(path),
    )
    npz_path = path / TABLES_FILE
    lower_settings = policy.training.get("lower")
    if isinstance(lower_settings, dict) and "hold_heading" in lower_settings:
        if not isinstance(lower_settings["hold_heading"], bool):
            raise PolicyFormatError(
                f"{meta_path}: expected training.lower.hold_heading to be true or false, "
                f"found {lower_settings['hold_heading']!r}"
            )
    if kind == "hierarchical":
        # The encoding was checked against both (``arrays_of``): its phases say which it is.
        door_distance = tuple(s["phases"] for s in metadata["subtasks"]) == DISTANCE_PHASES
        lower = np.zeros(lower_table_shape(door_distance))
        for number, name in enumerate(SUBTASK_TABLES):
            expected = (phase_counts(door_distance)[number] * NUM_STATES, len(ACTION_CODES))
            table = _table(arrays, name, expected, npz_path)
            lower[number, : expected[0]] = table
        policy.lower_q = lower
        policy.higher_q = _table(arrays, "higher", (2 * len(checkpoints), 4), npz_path)
    else:
        rows = (1 + 2 * len(checkpoints)) * NUM_STATES
        policy.flat_q = _table(arrays, "flat", (rows, len(ACTION_CODES)), npz_path)
    return policy


def _table(
    arrays: dict[str, npt.NDArray[Any]], name: str, shape: tuple[int, int], where: Path
) -> npt.NDArray[np.float64]:
    if name not in arrays:
        raise PolicyFormatError(f"{where}: the table {name!r} is missing")
    table = arrays[name]
    if table.shape != shape or table.dtype != np.float64:
        raise PolicyFormatError(
            f"{where}: expected table {name!r} of shape {shape} float64, "
            f"found {table.shape} {table.dtype}"
        )
    if not np.all(np.isfinite(table)):
        raise PolicyFormatError(f"{where}: table {name!r} holds NaN or infinite values")
    return np.array(table, dtype=np.float64)
