"""Steady-state throughput of a batch: warm up, then time blocks of steps.

A batch just reset runs faster than one that has been going for a while: its robots sit at their
start poses, clear of walls, with sensor caches warm. So a measurement here first steps
``warmup_steps`` (at least :data:`MIN_WARMUP_STEPS`), with episodes ending and being reset as in
training, and only then times ``blocks`` blocks of ``block_steps`` steps each. Every block
reports its env-steps per wall-second, per CPU-second of the whole process (the stepping threads
included), and the share of its env-steps that ended in contact with a wall.

Episodes end at a step limit, ``episode_steps``; env ``i`` starts its first episode
``i * episode_steps // N`` steps in, so that about ``N / episode_steps`` envs are reset at every
step and the batch as a whole never restarts at once.
"""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

import mazesim
from mazesim._settings import MAX_COUNT, MAX_SEED, bounded, check_settings, setting
from mazesim.errors import InvalidArgumentError, RegisteredName

from .memory import engine_bytes, resident_bytes
from .workloads import WORKLOADS, Workload, make_workload

__all__ = [
    "MIN_WARMUP_STEPS",
    "MAZE_KINDS",
    "Block",
    "BenchSettings",
    "SteadyState",
    "make_worlds",
    "measure",
]

#: The shortest warm-up a measurement accepts, in steps.
MIN_WARMUP_STEPS = 1000

#: ``distinct``: env i gets the generated maze of seed ``seed + i``; ``shared``: every env
#: steps the maze of seed ``seed``.
MAZE_KINDS = ("distinct", "shared")
#: The most envs of a batch of distinct mazes: the design's largest benchmark batch, whose mazes
#: take about 1 GB (a larger batch is checked against the memory when it is made).
MAX_DISTINCT_MAZES = 65_536


@dataclass(frozen=True)
class BenchSettings:
    """What a steady-state measurement runs; every field is reported with its figures.

    Attributes:
        envs: Envs in the batch.
        workload: The wheel-speed rule, one of :data:`~mazesim.benchmark.WORKLOADS`.
        mazes: ``distinct`` (a generated 5 x 5 maze per env) or ``shared`` (one for all).
        threads: Stepping threads; 0 for one per core.
        warmup_steps: Steps before the first timed block (at least 1,000).
        block_steps: Steps in each timed block.
        blocks: Timed blocks.
        episode_steps: The episode step limit; an env is reset when its episode reaches it.
        steps_per_call: Control steps per call into the engine. 1: the workload's rule in
            numpy between single steps, as a Python training loop runs. More: the engine's own
            controller for the workload runs that many steps in one ``BatchSimulator.run``
            call; episodes that reach their limit within a call are reset after it.
        seed: Seeds the mazes, the sensor noise and the random workload.
    """

    envs: int = bounded(1024, least=1, most=MAX_COUNT)
    workload: RegisteredName = setting(
        "braitenberg",
        "the wheel-speed rule: braitenberg (wander clear of walls), contact (about "
        "half the steps pushing into walls), random (uniform wheel speeds)",
        choices=tuple(WORKLOADS),
    )
    mazes: RegisteredName = setting(
        "distinct", "a generated maze per env, or one shared by all", choices=MAZE_KINDS
    )
    threads: int = setting(
        0, "worker threads", "T", default_text="0 = all cores", least=0, most=MAX_COUNT
    )
    warmup_steps: int = bounded(MIN_WARMUP_STEPS, least=MIN_WARMUP_STEPS, most=MAX_COUNT)
    block_steps: int = setting(300, "steps per timed block", "S", least=1, most=MAX_COUNT)
    blocks: int = setting(5, "timed blocks", "B", least=1, most=MAX_COUNT)
    episode_steps: int = setting(
        1000,
        "episode step limit; an env is reset when it reaches it",
        "E",
        least=1,
        most=MAX_COUNT,
    )
    steps_per_call: int = bounded(1, least=1, most=MAX_COUNT)
    seed: int = setting(
        0,
        "seeds the mazes, the sensor noise and the random workload",
        "S",
        least=0,
        most=MAX_SEED,
    )

    def __post_init__(self) -> None:
        # A workload or a maze kind is a registered name, and each count in its range, refused
        # when made (as its option).
        check_settings(self)

    def check(self) -> None:
        """Raises :class:`~mazesim.errors.InvalidArgumentError` naming the first setting that
        does not fit the others (each is in its own range since the settings were made)."""
        if self.mazes == "distinct" and self.envs > MAX_DISTINCT_MAZES:
            raise InvalidArgumentError(
                f"benchmark setting envs: expected at most {MAX_DISTINCT_MAZES} envs with distinct "
                f"mazes (each generated beforehand), found {self.envs}; more share one maze "
                "(mazes='shared')"
            )
        if self.seed + self.envs > 2**64:
            raise InvalidArgumentError(
                f"benchmark setting seed: env i's maze takes seed + i, so expected a seed of at "
                f"most 2^64 - {self.envs} for {self.envs} envs, found {self.seed}"
            )
        if self.steps_per_call > 1 and WORKLOADS[self.workload].builtin is None:
            multi = ", ".join(name for name, kind in WORKLOADS.items() if kind.builtin)
            raise InvalidArgumentError(
                f"benchmark setting steps_per_call: the {self.workload} workload runs one step "
                f"per call (the engine has no controller for it), found {self.steps_per_call}; "
                f"workloads that run many steps per call: {multi}"
            )


@dataclass(frozen=True)
class Block:
    """One timed block of steps.

    Attributes:
        first_step: The batch's step count (since it was made) when the block began.
        steps: Steps in the block (each of them one env-step per env).
        env_steps: ``steps * envs``.
        wall_seconds: Wall time of the block.
        cpu_seconds: CPU time of the whole process (all its threads) during the block.
        contact_steps: Env-steps that ended with the robot touching a wall.
        episodes_ended: Episodes that reached the step limit (and were reset) in the block.
    """

    first_step: int
    steps: int
    env_steps: int
    wall_seconds: float
    cpu_seconds: float
    contact_steps: int
    episodes_ended: int

    @property
    def env_steps_per_second(self) -> float:
        """Env-steps per wall-clock second."""
        return self.env_steps / self.wall_seconds

    @property
    def env_steps_per_cpu_second(self) -> float:
        """Env-steps per CPU-second of the process."""
        return self.env_steps / max(self.cpu_seconds, 1e-9)

    @property
    def contact_share(self) -> float:
        """The share of env-steps in contact with a wall."""
        return self.contact_steps / self.env_steps

    def summary(self) -> dict[str, Any]:
        """The block's counts and its rates, as plain numbers."""
        return dict(
            asdict(self),
            env_steps_per_s=self.env_steps_per_second,
            env_steps_per_cpu_s=self.env_steps_per_cpu_second,
            contact_share=self.contact_share,
        )


def make_worlds(envs: int, mazes: str, seed: int) -> list[mazesim.World]:
    """The canonical workload's mazes: 5 x 5 cells of 0.25 m, 0.01 m walls, a tenth of extra
    openings; one per env (``distinct``) or one for all (``shared``)."""
    count = envs if mazes == "distinct" else 1
    return [mazesim.generate_maze(5, 5, seed=seed + i, loops=0.1) for i in range(count)]


class SteadyState:
    """A batch under a workload, stepped with episodes ending and being reset.

    Args:
        settings: The batch (envs, mazes, threads, seed), workload and episode step limit;
            the warm-up and blocks are :func:`measure`'s business.
    """

    def __init__(self, settings: BenchSettings) -> None:
        settings.check()
        self.settings = settings
        n = settings.envs
        resident_before = resident_bytes()
        worlds = make_worlds(n, settings.mazes, settings.seed)
        self.batch = mazesim.BatchSimulator(
            worlds if settings.mazes == "distinct" else worlds[0],
            num_envs=None if settings.mazes == "distinct" else n,
            robot="e-puck",
            seeds=settings.seed,
            threads=settings.threads,
        )
        del worlds
        self.observations, self.poses, self.colliding, self.crossings = self.batch.output_buffers()
        self.actions = np.zeros((n, 2), np.float32)
        # Env i starts i * limit // n steps into its first episode, so that resets spread
        # evenly; the envs of offset v, whose episodes all end at the same steps, are a slice of
        # the batch (:meth:`envs_of_offset`).
        self.episode_offset = (np.arange(n, dtype=np.int64) * settings.episode_steps) // n
        self.ended = np.zeros(n, np.bool_)
        self.workload: Workload = make_workload(settings.workload, n, settings.seed)
        #: Steps since the batch was made.
        self.steps_done = 0
        #: Seeds the engine's controller streams in the next ``run`` call (env i: this + i);
        #: each call moves it on by N, so that no call repeats another's draws.
        state = np.random.SeedSequence(settings.seed).generate_state(1, np.uint64)
        self.controller_seed = int(state[0]) >> 1
        self.batch.reset(self.observations, self.poses, self.colliding, self.crossings)
        engine = engine_bytes(self.batch)
        #: Memory per env: the resident set's growth while the batch was built (only in a
        #: fresh process is it the batch's own: elsewhere memory freed before can be reused,
        #: and the growth can even be negative), and the engine's own count where it has one
        #: (None otherwise).
        self.memory = {
            "resident_bytes_per_env": (resident_bytes() - resident_before) / n,
            "engine_bytes_per_env": engine / n,
        }

    def advance(self, steps: int) -> tuple[int, int]:
        """Steps the batch ``steps`` times under the workload, resetting envs whose episode
        reaches the step limit.

        Returns:
            The env-steps that ended in contact with a wall, and the episodes that ended.
        """
        if self.settings.steps_per_call > 1:
            return self._advance_in_calls(steps)
        batch, obs, poses = self.batch, self.observations, self.poses
        colliding, crossings, actions = self.colliding, self.crossings, self.actions
        ended, limit = self.ended, self.settings.episode_steps
        envs_of_offset = self.envs_of_offset
        act = self.workload.act
        contacts = episodes = 0
        done = self.steps_done
        for _ in range(steps):
            batch.step(act(obs, actions), obs, poses, colliding, crossings)
            contacts += int(np.count_nonzero(colliding))
            done += 1
            # The envs of this offset have just reached the limit.
            first, last = envs_of_offset(-done % limit)
            if last > first:
                episodes += last - first
                ended[first:last] = True
                batch.reset(obs, poses, colliding, crossings, mask=ended)
                ended[first:last] = False
        self.steps_done = done
        return contacts, episodes

    def _advance_in_calls(self, steps: int) -> tuple[int, int]:
        """:meth:`advance` in calls of ``steps_per_call`` steps of the engine's controller."""
        batch, obs, poses = self.batch, self.observations, self.poses
        colliding, crossings, ended = self.colliding, self.crossings, self.ended
        limit, per_call = self.settings.episode_steps, self.settings.steps_per_call
        controller = self.workload.builtin
        assert controller is not None  # BenchSettings.check
        contacts = episodes = 0
        left = steps
        while left > 0:
            k = min(per_call, left)
            settings = mazesim.RunSettings(seeds=self.controller_seed)
            counts = batch.run(k, controller, obs, poses, colliding, crossings, settings=settings)
            self.controller_seed += self.settings.envs
            contacts += int(counts["steps_in_contact"].sum())
            # The envs whose episodes reached the limit during the call are reset after it.
            for done in range(self.steps_done + 1, self.steps_done + k + 1):
                first, last = self.envs_of_offset(-done % limit)
                ended[first:last] = True
            if ended.any():
                episodes += int(np.count_nonzero(ended))
                batch.reset(obs, poses, colliding, crossings, mask=ended)
                ended[:] = False
            self.steps_done += k
            left -= k
        return contacts, episodes

    def envs_of_offset(self, offset: int) -> tuple[int, int]:
        """The slice ``first:last`` of the envs that start ``offset`` steps into their first
        episode (``i * limit // n == offset`` exactly for ``ceil(offset * n / limit) <= i <
        ceil((offset + 1) * n / limit)``); empty where no env has that offset."""
        n, limit = self.settings.envs, self.settings.episode_steps
        return -(-offset * n // limit), -(-(offset + 1) * n // limit)

    def timed_block(self, steps: int) -> Block:
        """Advances ``steps`` steps and times them."""
        first = self.steps_done
        wall, cpu = time.perf_counter(), time.process_time()
        contacts, episodes = self.advance(steps)
        cpu = time.process_time() - cpu
        wall = time.perf_counter() - wall
        return Block(
            first_step=first,
            steps=steps,
            env_steps=steps * self.settings.envs,
            wall_seconds=wall,
            cpu_seconds=cpu,
            contact_steps=contacts,
            episodes_ended=episodes,
        )


#: A progress report: steps done and steps in all (warm-up included).
Progress = Callable[[int, int], None]


def measure(settings: BenchSettings, progress: Progress | None = None) -> dict[str, Any]:
    """Measures the steady-state throughput of ``settings`` in this process.

    Args:
        settings: What to run.
        progress: Called after the warm-up and after each block with the steps done so far
            and the steps in all.

    Returns:
        ``settings`` (as a dict), ``blocks`` (each block's :meth:`Block.summary`), and over
        all blocks: ``env_steps_per_s`` and ``env_steps_per_cpu_s`` (the median block's),
        ``env_steps_per_s_range`` (the slowest and fastest block's), ``contact_share``,
        ``episodes_ended``, ``warmup_steps_done``; and ``memory``: the batch's bytes per env
        (:attr:`SteadyState.memory`; run it in a fresh process for a figure of its own).
    """
    run = SteadyState(settings)
    total = settings.warmup_steps + settings.blocks * settings.block_steps
    run.advance(settings.warmup_steps)
    if progress is not None:
        progress(run.steps_done, total)
    blocks = []
    for _ in range(settings.blocks):
        blocks.append(run.timed_block(settings.block_steps))
        if progress is not None:
            progress(run.steps_done, total)
    return dict(summarise(settings, blocks), memory=run.memory)


def summarise(settings: BenchSettings, blocks: list[Block]) -> dict[str, Any]:
    """The figures of :func:`measure` over its blocks (all but ``memory``)."""
    rates = [b.env_steps_per_second for b in blocks]
    env_steps = sum(b.env_steps for b in blocks)
    return {
        "settings": asdict(settings),
        "warmup_steps_done": blocks[0].first_step if blocks else 0,
        "env_steps_per_s": statistics.median(rates),
        "env_steps_per_s_range": [min(rates), max(rates)],
        "env_steps_per_cpu_s": statistics.median(b.env_steps_per_cpu_second for b in blocks),
        "contact_share": sum(b.contact_steps for b in blocks) / env_steps,
        "episodes_ended": sum(b.episodes_ended for b in blocks),
        "blocks": [b.summary() for b in blocks],
    }
