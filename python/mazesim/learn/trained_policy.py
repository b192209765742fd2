"""A trained navigator as one object: its tables, the world it learned, and a driver for one
robot (:meth:`TrainedPolicy.act`); and where the shipped navigators are.

:mod:`mazesim.learn.tables` writes a :class:`TrainedPolicy` to a folder and reads it back.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._core import World
from mazesim._sizes import number_array
from mazesim.actions import ACTION_CODES
from mazesim.errors import PolicyFormatError, RegisteredName, UnknownNameError, _known_name, _shown
from mazesim.learn.subtasks import CONTROL_STEP_MS
from mazesim.maze import world_hash

__all__ = [
    "SHIPPED_NAVIGATORS",
    "TrainedPolicy",
    "navigator_folder",
    "shipped_policy_dir",
]


def shipped_policy_dir(world_name: RegisteredName = "seed-maze") -> Path:
    """The folder of the navigator shipped in the package for a built-in world.

    Raises:
        UnknownNameError: No navigator is shipped for ``world_name`` (the message lists those
            that are).
    """
    data = resources.files("mazesim.learn").joinpath("data")
    shipped = sorted(each.name for each in data.iterdir() if each.is_dir())
    return Path(str(data.joinpath(_known_name(world_name, "world_name", shipped))))


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
        :attr:`training` ``["lower"]``; the core's ``navigator::heading_hold``). Every runner of the
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
                f"the navigator{where} learned world {_shown(self.world_name)} from "
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
                f"the navigator{where} learned world {_shown(self.world_name)} "
                f"(sha256 {self.world_sha256[:12]}...), "
                f"not {_shown(world.name)} (sha256 {digest[:12]}...)"
            )


class _FlatDriver:
    """The flat baseline driving one robot from distances in cm (see :meth:`TrainedPolicy.act`)."""

    def __init__(self, navigator: Any) -> None:
        self.navigator = navigator
        self.navigator.reset([0], None)

    def act(self, distances_cm: npt.ArrayLike, checkpoint: int) -> str:
        from mazesim.learn.discretise import distance_levels

        levels = distance_levels(
            number_array(distances_cm, "distances_cm", inf_means="nothing in range").reshape(1, 6)
        )
        state = self.navigator.states_from_levels(levels, np.array([int(checkpoint)]))
        return ACTION_CODES[int(np.argmax(self.navigator.q[state[0]]))]
