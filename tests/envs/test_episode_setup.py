"""The per-episode set-up of the maze tasks in the core (``World.distance_targets``,
``World.connected_cells``) equals the Python model it replaced, bit for bit."""

from __future__ import annotations

import numpy as np
import pytest

import mazesim
from mazesim import InvalidArgumentError
from mazesim._core import World, generate_maze
from mazesim.maze import CellMaze
from navigation_oracle import cell_targets, largest_connected_cells


def worlds() -> list[World]:
    """Built-in worlds with a cell maze (seed-maze has walled-in cells) and generated mazes,
    trees and mazes with loops, square and not."""
    built = [mazesim.load_world(name) for name in ("seed-maze",)]
    generated = [
        generate_maze(width, height, seed=seed, loops=loops)
        for width, height, seed, loops in ((5, 5, 1, 0.0), (7, 3, 2, 0.3), (2, 6, 3, 0.6))
    ]
    return built + generated


@pytest.mark.parametrize("world", worlds(), ids=lambda world: world.name)
def test_the_distance_targets_towards_every_goal_cell_are_pythons(world: World) -> None:
    maze = CellMaze(world)
    for column, row in maze.cells():
        core = world.distance_targets(row * maze.cols + column)
        model = cell_targets(maze, (column, row))
        assert core.shape == (maze.rows * maze.cols, 5)
        np.testing.assert_array_equal(core, model)  # NaN where NaN, every other bit equal


@pytest.mark.parametrize("world", worlds(), ids=lambda world: world.name)
def test_the_connected_cells_are_pythons(world: World) -> None:
    cells = [tuple(cell) for cell in world.connected_cells().tolist()]
    assert cells == largest_connected_cells(CellMaze(world))


def test_seed_maze_leaves_its_walled_in_cells_out() -> None:
    world = mazesim.load_world("seed-maze")
    maze = CellMaze(world)
    assert 1 < len(world.connected_cells()) < maze.rows * maze.cols


def test_a_world_without_a_cell_maze_or_a_cell_off_the_grid_is_refused() -> None:
    open_world = World.builtin("arena")
    with pytest.raises(InvalidArgumentError, match="cell maze"):
        open_world.connected_cells()
    with pytest.raises(InvalidArgumentError, match="cell maze"):
        open_world.distance_targets(0)
    maze = generate_maze(3, 3, seed=0)
    with pytest.raises(InvalidArgumentError, match=r"goal_cell to be an int in 0..=8, found 9"):
        maze.distance_targets(9)
