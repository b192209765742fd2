"""The maze generator's checkpoints, as the navigator needs them: one on every way into a door."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mazesim
from mazesim.maze import CellMaze, DoorApproach, navigator_problems


def code_centre(maze: CellMaze, approach: DoorApproach) -> tuple[float, float]:
    """Where the generator paints the middle of an approach's code: the middle of a straight
    approach cell, else the middle of the edge between the cell and the door."""
    x, y = maze.center(approach.cell)
    if approach.straight:
        return x, y
    shift = maze.cell_size / 2.0
    angle = maze.heading_of(approach.heading)
    return x + shift * round(math.cos(angle)), y + shift * round(math.sin(angle))


CODE_LENGTH = 5 * 0.017


def crossed_codes(world: mazesim.World, start: np.ndarray, end: np.ndarray) -> list[int]:
    """Ids of the codes a sensor driving straight from ``start`` to ``end`` crosses end to end."""
    direction = (end - start) / np.linalg.norm(end - start)
    ids = []
    for checkpoint in world.checkpoints():
        centre = np.array(checkpoint["center"], dtype=float)
        yaw = float(checkpoint["yaw"])
        axis = np.array([math.cos(yaw), math.sin(yaw)])
        along = float((centre - start) @ direction)
        offset = centre - start
        off_line = abs(float(direction[0] * offset[1] - direction[1] * offset[0]))
        parallel = abs(abs(float(axis @ direction)) - 1.0) < 1e-9
        inside = CODE_LENGTH / 2 <= along <= float(np.linalg.norm(end - start)) - CODE_LENGTH / 2
        if parallel and inside and off_line < 1e-9:
            ids.append(int(checkpoint["id"]))
    return ids


@pytest.mark.parametrize(("loops", "most_skipped"), [(0.0, 2), (0.1, 30)])
def test_every_way_into_a_door_crosses_one_code(loops: float, most_skipped: int) -> None:
    # Perfect 5 x 5 mazes (those of the transfer test) nearly always have codes enough; mazes
    # with loops have more doors and often run out.
    skipped = 0
    for seed in range(40):
        world = mazesim.generate_maze(5, 5, seed=seed, loops=loops)
        maze = CellMaze(world)
        approaches = maze.door_approaches()
        if len(world.checkpoints()) == len(mazesim.default_codes()):
            skipped += 1  # the book ran out: the Rust tests cover that
            continue
        for approach in approaches:
            heading = np.array(
                [
                    math.cos(maze.heading_of(approach.heading)),
                    math.sin(maze.heading_of(approach.heading)),
                ]
            )
            # From 6 cm behind the approach cell's middle (before a code there begins) to the
            # door's middle.
            start = np.array(maze.center(approach.cell)) - 0.06 * heading
            end = np.array(maze.center(approach.door))
            crossed = crossed_codes(world, start, end)
            assert len(crossed) == 1, f"seed {seed} loops {loops}: {approach} crosses {crossed}"
            # Where the navigator's training expects it.
            centres = [np.array(c["center"]) for c in world.checkpoints()]
            expected = np.array(code_centre(maze, approach))
            assert any(np.allclose(c, expected) for c in centres), approach
    assert skipped <= most_skipped


def test_a_straight_cell_between_two_doors_has_one_code() -> None:
    # Seed 5002 with loops 0.3 has a straight cell between two doors: it once got two codes at
    # the same centre facing opposite ways.
    world = mazesim.generate_maze(5, 5, seed=5002, loops=0.3)
    centres = [tuple(np.round(c["center"], 9)) for c in world.checkpoints()]
    assert len(set(centres)) == len(centres)
    maze = CellMaze(world)
    shared = [
        c
        for c in world.checkpoints()
        if any(
            np.allclose(maze.center(cell), c["center"])
            and len(maze.openings(cell)) == 2
            and all(maze.is_door(maze.neighbour(cell, d)) for d in maze.openings(cell))
            for cell in maze.cells()
        )
    ]
    assert shared, "expected a code in a straight cell between two doors"
    codes = [str(c["code"]) for c in world.checkpoints()]
    mazesim.validate_codes(codes)


# --- issue 37: the Worlds page's promise, through the public surface -----------------------------

WORLDS_PAGE = Path(__file__).resolve().parents[2] / "docs" / "worlds.md"


@settings(max_examples=300, deadline=None)
@given(
    width=st.integers(2, 12),
    height=st.integers(2, 12),
    seed=st.integers(0, 2**64 - 1),
    loops=st.one_of(st.just(0.0), st.floats(0.0, 0.5)),
)
def test_every_generated_maze_larger_than_2_by_2_is_one_the_navigator_can_learn(
    width: int, height: int, seed: int, loops: float
) -> None:
    world = mazesim.generate_maze(width, height, seed=seed, loops=loops)
    problems = navigator_problems(world)
    if max(width, height) > 2:
        assert problems == [], f"{width} x {height} seed {seed} loops {loops}: {problems}"
        assert world.checkpoints()
    else:
        assert not world.checkpoints()  # a ring of four cells has no junction


def test_the_share_of_single_corridor_first_draws_is_the_pages() -> None:
    shown = re.search(
        r"about (\d+) % of first draws at 3 x 3, (\d+) % at 4 x 4, (\d+) %\s+at 5 x 5",
        WORLDS_PAGE.read_text(encoding="utf-8"),
    )
    assert shown is not None
    draws = 2000
    for size, percent in zip((3, 4, 5), shown.groups()):
        corridors = sum(
            not mazesim.generate_maze(size, size, seed=seed, junction=False).checkpoints()
            for seed in range(draws)
        )
        assert round(100 * corridors / draws) == int(percent), (size, corridors)
