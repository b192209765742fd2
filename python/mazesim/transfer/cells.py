"""Running the cells of a transfer study in batches.

A cell is a :class:`~mazesim.transfer.axes.Setting` driven for a number of episodes. The cells of
one robot profile run side by side in one :class:`mazesim.episodes.EpisodeBatch`: each cell has
its own entry in the batch's world list (the same world, repeated) and its own robots, each robot
its own (perturbed) profile; the navigator of all of them is the plain one wrapped per robot
(:class:`~mazesim.transfer.readings.SeedReadingsNavigator` on another profile,
:class:`~mazesim.transfer.control_timing.DelayedNavigator`,
:class:`~mazesim.transfer.control_timing.LinkedNavigator`).

Every cell drives the same episodes: episode ``k`` of every cell starts from the same jittered
pose with the same noise seed (common random numbers), so the difference between a cell and the
baseline is the perturbation's and not the draw's, and a cell's result does not depend on which
other cells share its batch.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._core import DrivePerturbation, RobotProfile, SensingPerturbation, World
from mazesim._seeding import stream_seeds
from mazesim._sizes import index_array, whole_array
from mazesim.batch import cruise_step_length
from mazesim.episodes import (
    MAX_STEPS,
    EpisodeBatch,
    run_episodes,
    shortest_path_steps,
)
from mazesim.errors import InvalidArgumentError, _shown
from mazesim.learn.higher import HigherLevel
from mazesim.learn.policy import HierarchicalPolicy
from mazesim.learn.summary import Summary, summarise
from mazesim.transfer.axes import Setting
from mazesim.transfer.control_timing import DelayedNavigator, LinkedNavigator
from mazesim.transfer.odometry import EncoderOdometryNavigator
from mazesim.transfer.readings import SeedReadingsNavigator

__all__ = ["BATCH_ENVS", "CellRun", "profile_changes", "profile_of", "run_cells"]

#: Robots stepped side by side in one batch (at most).
BATCH_ENVS = 500
#: The robot the navigator learned on.
SEED_ROBOT = "seed"


#: The changes of :func:`profile_changes` that perturb the drive (a
#: :class:`mazesim.DrivePerturbation`); the others perturb the senses.
_DRIVE_CHANGES = ("wheel_radius_scale", "axle_length_scale", "motor_gains", "slip_on_contact")


def profile_changes(setting: Setting) -> dict[str, Any]:
    """The perturbations a setting asks for, by the name of their parameter of
    :class:`mazesim.DrivePerturbation` or :class:`mazesim.SensingPerturbation` (none: the
    profile as it is)."""
    changes: dict[str, Any] = {}
    scales = {
        "wheel_radius": "wheel_radius_scale",
        "axle_length": "axle_length_scale",
        "noise_scale": "noise_scale",
        "wall_reflectance": "wall_reflectance",
        "ground_drift": "ground_gain",
        "slip": "slip_on_contact",
    }
    for axis, keyword in scales.items():
        if axis in setting.axes:
            changes[keyword] = float(setting.get(axis))
    if "motor_mismatch" in setting.axes:
        mismatch = float(setting.get("motor_mismatch"))
        changes["motor_gains"] = (1.0 + min(mismatch, 0.0), 1.0 - max(mismatch, 0.0))
    if "ir_angle" in setting.axes:
        changes["ir_angle_error"] = math.radians(float(setting.get("ir_angle")))
    if "ir_offset" in setting.axes:
        changes["ir_offset_error"] = float(setting.get("ir_offset")) / 1000.0
    return changes


@functools.cache
def _builtin(name: str) -> RobotProfile:
    """The built-in profile ``name``, parsed once: a profile is immutable, so every setting on
    that robot may share it (a randomised run draws thousands of robots a round)."""
    return RobotProfile.builtin(name)


def profile_of(setting: Setting) -> RobotProfile:
    """The robot profile a setting drives: its ``robot`` level, perturbed by its other axes."""
    base = _builtin(str(setting.get("robot")))
    changes = profile_changes(setting)
    if not changes:
        return base
    perturbed = getattr(base, "perturbed", None)
    if perturbed is None:
        raise InvalidArgumentError(
            f"the setting {_shown(setting.label())} needs RobotProfile.perturbed, which this "
            "build of "
            "mazesim lacks; study the axes robot, latency and link only"
        )
    drive = DrivePerturbation(**{k: v for k, v in changes.items() if k in _DRIVE_CHANGES})
    sensing = SensingPerturbation(**{k: v for k, v in changes.items() if k not in _DRIVE_CHANGES})
    profile: RobotProfile = perturbed(drive, sensing)
    return profile


class _CellEpisodes(EpisodeBatch):
    """An episode batch whose worlds are cells: episode ``k`` of every cell draws the start
    jitter and noise seed of episode ``k`` (common random numbers)."""

    episodes_per_cell = 1

    def start(self, envs: npt.ArrayLike, episodes: npt.ArrayLike) -> None:
        robots = index_array(envs, "envs", self.num_envs).ravel()
        numbers = whole_array(episodes, "episodes", low=0).ravel()
        super().start(robots, numbers % self.episodes_per_cell)
        self.episode[robots] = numbers


@dataclass(frozen=True)
class CellRun:
    """What every cell of a study shares: the navigator, its world and how episodes run.

    Attributes:
        world: The world (the one the higher level learned).
        lower_q: The navigator's lower-level tables.
        higher: Its higher level, for ``world``.
        episodes: Episodes per cell.
        seed: Seed of the episodes' start jitter and noise, and of the link's wake-ups.
        events: Checkpoint events from ``"truth"`` or the ``"robust"`` decoder.
        max_steps: Control steps after which an episode fails.
        threads: Worker threads of the batch.
        hold_heading: The navigator holds its heading where blind
            (:attr:`mazesim.learn.tables.TrainedPolicy.hold_heading`).
        odometry: The navigator's odometry: the simulator's poses (``"truth"``) or each robot's
            wheel encoders with its profile's nominal numbers (``"encoders"``,
            :mod:`mazesim.transfer.odometry`).
    """

    world: World
    lower_q: npt.NDArray[np.float64]
    higher: HigherLevel
    episodes: int
    seed: int = 0
    events: str = "robust"
    max_steps: int = MAX_STEPS
    threads: int = 0
    hold_heading: bool = False
    odometry: str = "truth"

    def batch(self, robot: str, settings: Sequence[Setting]) -> _CellEpisodes:
        """The episode batch of cells of one robot profile, as many robots each as fit."""
        envs_per_cell = max(1, min(self.episodes, BATCH_ENVS // len(settings)))
        world_of_env = np.repeat(np.arange(len(settings)), envs_per_cell)
        options: dict[str, Any] = {}
        if any(profile_changes(setting) for setting in settings):
            profiles = [profile_of(setting) for setting in settings]
            options["robot"] = [profiles[cell] for cell in world_of_env]
        elif robot != SEED_ROBOT:
            options["robot"] = robot
        batch = _CellEpisodes(
            [self.world] * len(settings),
            world_of_env,
            seed=self.seed,
            stream="transfer/episode",
            max_steps=self.max_steps,
            events=self.events,
            threads=self.threads,
            **options,
        )
        batch.episodes_per_cell = self.episodes
        return batch

    def navigator(self, robot: str, settings: Sequence[Setting], nav: EpisodeBatch) -> Any:
        """The navigator of a batch's robots, wrapped per robot as its cell's setting asks."""
        cell_of_env = nav.world_of_env
        navigator: Any = HierarchicalPolicy(
            self.lower_q,
            self.higher,
            np.zeros(len(cell_of_env), dtype=np.int64),
            hold_heading=self.hold_heading,
        )
        nominal = RobotProfile.builtin(robot)
        if self.odometry == "encoders":
            navigator = EncoderOdometryNavigator(
                navigator, nav.batch.simulator.encoders, nominal.wheel_radius, nominal.axle_length
            )
        if robot != SEED_ROBOT:
            navigator = SeedReadingsNavigator(navigator, nominal)
        delays = np.array([int(float(setting.get("latency"))) for setting in settings])
        navigator = DelayedNavigator(navigator, delays[cell_of_env])
        linked = np.array([setting.get("link") == "ros" for setting in settings])
        if linked.any():
            link_seed = int(stream_seeds(self.seed, "transfer/link", 1)[0])
            navigator = LinkedNavigator(navigator, linked[cell_of_env], link_seed)
        return navigator

    def shortest_steps(self, robot: str) -> float:
        """Control steps of the world's shortest path at the cruise speed of ``robot``."""
        ratio = cruise_step_length(RobotProfile.builtin(SEED_ROBOT)) / cruise_step_length(
            RobotProfile.builtin(robot)
        )
        return shortest_path_steps(self.world) * ratio


def run_cells(
    settings: Sequence[Setting],
    run: CellRun,
    progress: Callable[[int], None] | None = None,
) -> list[Summary]:
    """Drives ``run.episodes`` greedy episodes of the navigator in each setting.

    The cells of one robot profile share a batch (up to :data:`BATCH_ENVS` cells a batch).

    Args:
        settings: The cells' settings.
        run: The navigator, world and episode settings.
        progress: Called with the number of episodes that just ended.

    Returns:
        What each cell's episodes measured (:func:`mazesim.learn.summary.summarise`, the
        evaluator's own), in the order of ``settings``.
    """
    measures: dict[int, Summary] = {}
    groups: dict[str, list[int]] = {}
    for index, setting in enumerate(settings):
        groups.setdefault(str(setting.get("robot")), []).append(index)

    for robot, members in groups.items():
        for first in range(0, len(members), BATCH_ENVS - 1):
            chunk = members[first : first + BATCH_ENVS - 1]
            chosen = [settings[index] for index in chunk]
            # The batch's first robot sets what every robot's decoder believes of its wheels (and
            # the action table): an unperturbed robot of the profile, as on a real robot whose
            # controller knows only the nominal numbers. A reference cell leads when none does.
            lead = 0
            if profile_changes(chosen[0]):
                chosen.insert(0, Setting() if robot == SEED_ROBOT else Setting.of({"robot": robot}))
                lead = 1
            nav = run.batch(robot, chosen)
            navigator = run.navigator(robot, chosen, nav)
            studied = nav.world_of_env >= lead

            def ended(robots: npt.NDArray[np.int64], arrived: npt.NDArray[np.bool_]) -> None:
                if progress is not None:
                    progress(int(np.count_nonzero(studied[robots])))  # noqa: B023

            results = run_episodes(nav, navigator, run.episodes, on_end=ended)
            shortest = [run.shortest_steps(robot)]
            for place, index in enumerate(chunk, start=lead):
                # A cell is world ``place`` of the batch and the one world of its summary.
                own = [replace(result, world=0) for result in results if result.world == place]
                measures[index] = summarise(own, shortest, run.events)
    return [measures[index] for index in range(len(settings))]
