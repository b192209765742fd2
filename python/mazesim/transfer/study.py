"""The transfer study: a navigator on a grid of perturbations, one axis at a time and in pairs.

:func:`run_study` drives the navigator's greedy episodes in its own world (the one its higher level
learned) with the unperturbed robot (the baseline), at each level of each axis (the single-axis
cells), then for each pair of axes at their harshest levels (the pairwise cells; an axis's
harshest level is the one where its single-axis success was lowest; on a tie, the one with the
most contacts, then the longest paths, then the last listed, since levels go from mild to
harsh). Every cell runs the same episodes (:mod:`mazesim.transfer.cells`), so the study is
deterministic under its seed whatever the thread count.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from mazesim._core import World
from mazesim._settings import MAX_COUNT, MAX_SEED, bounded, check_settings
from mazesim.episodes import EVENT_SOURCES
from mazesim.errors import InvalidArgumentError, RegisteredName, _known_name
from mazesim.learn.evaluate import navigator_for
from mazesim.learn.tables import TrainedPolicy
from mazesim.transfer.axes import AXES, Axis, Level, Setting
from mazesim.transfer.cells import CellRun, run_cells
from mazesim.transfer.odometry import ODOMETRY_SOURCES
from mazesim.transfer.result import Cell, StudyResult

__all__ = ["DEFAULT_EPISODES", "DEFAULT_MAX_STEPS", "StudyOptions", "run_study", "study_size"]

#: Episodes per cell of a default study.
DEFAULT_EPISODES = 200
#: Control steps (64 ms) after which a study's episode fails: about 2 minutes, several times
#: the shipped navigator's usual episode in seed-maze.
DEFAULT_MAX_STEPS = 2000


@dataclass(frozen=True)
class StudyOptions:
    """How a transfer study runs.

    Attributes:
        axes: The axes studied (by default all).
        episodes: Episodes per cell.
        pairs: Whether to run the pairwise cells.
        seed: Seed of the episodes' start jitter and sensor noise, and of the link's wake-ups.
        events: Checkpoint events from the simulator's ``"truth"`` or the ``"robust"`` barcode
            decoder reading the ground sensor (only then does ``ground_drift`` matter).
        max_steps: Control steps after which an episode fails.
        threads: Worker threads of the batch (0: one per core); results do not depend on it.
        odometry: The navigator's odometry: each robot's wheel encoders read with its profile's
            nominal wheel radius and axle length (``"encoders"``, as on a real robot) or the
            simulator's poses (``"truth"``); see :mod:`mazesim.transfer.odometry`.
    """

    axes: tuple[Axis, ...] = AXES
    episodes: int = bounded(DEFAULT_EPISODES, least=1, most=MAX_COUNT)
    pairs: bool = True
    seed: int = bounded(0, least=0, most=MAX_SEED)
    events: RegisteredName = "robust"
    max_steps: int = bounded(DEFAULT_MAX_STEPS, least=1, most=MAX_COUNT)
    threads: int = bounded(0, least=0, most=MAX_COUNT)
    odometry: RegisteredName = "encoders"

    def __post_init__(self) -> None:
        _known_name(self.events, "events", EVENT_SOURCES)
        _known_name(self.odometry, "odometry", ODOMETRY_SOURCES)
        check_settings(self)

    def check(self) -> None:
        """Raises :class:`InvalidArgumentError` when no axis is studied (an unknown source of
        events or odometry, and a count out of its range, are refused when the options are
        made)."""
        if not self.axes:
            raise InvalidArgumentError("expected at least one axis, found none")


def _harshness(place: int, cell: Cell) -> tuple[float, float, float, int]:
    """Orders an axis's cells harshest first: the lowest success, then the most contacts, then
    the longest paths, then the later level (levels are listed from mild to harsh)."""
    measure = cell.measure
    path = math.inf if measure.mean_path_ratio is None else measure.mean_path_ratio
    return (measure.success_rate, -measure.mean_collisions, -path, -place)


def single_settings(axes: Sequence[Axis]) -> list[Setting]:
    """One setting per level of each axis, in order."""
    return [Setting.of({axis.name: level}) for axis in axes for level in axis.levels]


def study_size(options: StudyOptions) -> tuple[int, int]:
    """``(cells, episodes)`` of a study: the baseline, the single-axis and the pairwise cells."""
    cells = 1 + len(single_settings(options.axes))
    if options.pairs:
        cells += len(options.axes) * (len(options.axes) - 1) // 2
    return cells, cells * options.episodes


def run_study(
    policy: TrainedPolicy,
    world: World,
    options: StudyOptions,
    label: str = "shipped",
    progress: Callable[[str, int, int], None] | None = None,
) -> StudyResult:
    """Runs a transfer study of a hierarchical navigator in its own world.

    Args:
        policy: The navigator.
        world: The world its higher level learned.
        options: The study's settings.
        label: The navigator's name in the result (its folder, or ``"shipped"``).
        progress: Called as ``progress("transfer", episodes_done, episodes_total)``.

    Raises:
        InvalidArgumentError: Bad options, or a navigator that is not hierarchical.
        PolicyFormatError: The world is not the one the navigator learned.
    """
    options.check()
    if policy.kind != "hierarchical" or policy.lower_q is None:
        raise InvalidArgumentError(f"expected a hierarchical navigator, found a {policy.kind} one")
    policy.check_world(world)
    higher, _ = navigator_for(policy, [world], seed=options.seed, threads=options.threads)
    cells = CellRun(
        world,
        policy.lower_q,
        higher,
        options.episodes,
        seed=options.seed,
        events=options.events,
        max_steps=options.max_steps,
        threads=options.threads,
        hold_heading=policy.hold_heading,
        odometry=options.odometry,
    )
    _, total = study_size(options)
    done = [0]

    def ended(count: int) -> None:
        done[0] += count
        if progress is not None:
            progress("transfer", min(done[0], total), total)

    def run(settings: list[Setting]) -> list[Cell]:
        measures = run_cells(settings, cells, progress=ended)
        return [Cell(setting, measure) for setting, measure in zip(settings, measures)]

    if progress is not None:
        progress("transfer", 0, total)
    first = run([Setting(), *single_settings(options.axes)])
    baseline, single = first[0], first[1:]
    harshest: dict[str, Level] = {}
    for axis in options.axes:
        own = [cell for cell in single if cell.setting.axes == (axis.name,)]
        worst = min(enumerate(own), key=lambda item: _harshness(*item))[1]
        harshest[axis.name] = worst.setting.get(axis.name)
    pairs: list[Cell] = []
    if options.pairs and len(options.axes) > 1:
        pairs = run(
            [
                Setting.of({a.name: harshest[a.name], b.name: harshest[b.name]})
                for a, b in itertools.combinations(options.axes, 2)
            ]
        )
    return StudyResult(
        policy=label,
        world=world.name,
        seed=options.seed,
        episodes=options.episodes,
        events=options.events,
        odometry=options.odometry,
        max_steps=options.max_steps,
        axes=tuple(options.axes),
        harshest=harshest,
        baseline=baseline,
        single=single,
        pairs=pairs,
    )
