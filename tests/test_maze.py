"""The one cell-maze model: directions, breadth-first distances, and the goal distance."""

from __future__ import annotations

import math

import numpy as np
import pytest

import mazesim
from mazesim.errors import InvalidArgumentError
from mazesim.maze import (
    EAST,
    NORTH,
    SOUTH,
    WEST,
    CellMaze,
    GoalDistance,
    PathDistanceTable,
    breadth_first_distances,
)
from navigation_oracle import next_cells


def test_directions_turn_counter_clockwise_from_east() -> None:
    maze = CellMaze(mazesim.generate_maze(3, 3, seed=1))
    assert [maze.heading_of(d) for d in (EAST, NORTH, WEST, SOUTH)] == pytest.approx(
        [0.0, math.pi / 2, math.pi, 3 * math.pi / 2]
    )
    x0, y0 = maze.center((1, 1))
    for direction in (EAST, NORTH, WEST, SOUTH):
        x, y = maze.center(maze.neighbour((1, 1), direction))
        heading = maze.heading_of(direction)
        assert (x - x0, y - y0) == pytest.approx(
            (maze.cell_size * math.cos(heading), maze.cell_size * math.sin(heading)), abs=1e-12
        )


def test_breadth_first_distances_count_cells_along_open_sides() -> None:
    maze = CellMaze(mazesim.generate_maze(5, 5, seed=4))
    distance = maze.distances_from((0, 0))
    assert distance[0, 0] == 0 and np.all(distance >= 0)  # a perfect maze: all reachable
    for cell in maze.cells():
        here = distance[cell[1], cell[0]]
        steps = [
            distance[n[1], n[0]]
            for n in map(lambda d: maze.neighbour(cell, d), maze.openings(cell))
        ]
        if here > 0:
            assert min(steps) == here - 1  # one open neighbour is a cell closer
        assert all(abs(s - here) <= 1 for s in steps)


def test_many_mazes_searched_at_once_give_each_its_own_distances() -> None:
    mazes = [CellMaze(mazesim.generate_maze(6, 4, seed=seed, loops=0.3)) for seed in range(3)]
    sources = np.array([(0, 0), (5, 3), (2, 1)])
    together = breadth_first_distances(np.stack([m.open_sides() for m in mazes]), sources)
    for maze, source, distance in zip(mazes, sources, together):
        alone = breadth_first_distances(maze.open_sides()[None], source[None])[0]
        assert np.array_equal(distance, alone)
        assert np.array_equal(distance, maze.distances_from(tuple(source)))
        assert distance[source[1], source[0]] == 0 and distance.max() > 3


def test_open_sides_are_is_open_of_every_cell() -> None:
    maze = CellMaze(mazesim.load_world("seed-maze"))
    sides = maze.open_sides()
    assert sides.shape == (maze.rows, maze.cols, 4)
    for column, row in maze.cells():
        expected = [maze.is_open((column, row), direction) for direction in range(4)]
        assert sides[row, column].tolist() == expected


@pytest.mark.parametrize("loops", [0.0, 0.5])
def test_next_cells_lead_one_open_step_nearer_the_target(loops: float) -> None:
    maze = CellMaze(mazesim.generate_maze(6, 4, seed=2, loops=loops))
    target = (4, 1)
    following = next_cells(maze.open_sides()[None], np.array([target]))[0]
    distance = maze.distances_from(target)
    assert following[1, 4].tolist() == [-1, -1]
    for cell in maze.cells():
        if cell == target:
            continue
        nearer = [
            direction
            for direction in maze.openings(cell)
            if distance[maze.neighbour(cell, direction)[::-1]] == distance[cell[::-1]] - 1
        ]
        # The first such side in direction order (a tie between two ways is settled so).
        assert tuple(following[cell[1], cell[0]]) == maze.neighbour(cell, nearer[0])


def test_next_cells_are_none_where_the_target_cannot_be_reached() -> None:
    maze = CellMaze(mazesim.load_world("seed-maze"))  # (1, 1) is walled in
    following = next_cells(maze.open_sides()[None], np.array([(0, 0)]))[0]
    distance = maze.distances_from((0, 0))
    assert distance[1, 1] < 0 and following[1, 1].tolist() == [-1, -1]
    assert np.array_equal((following >= 0).all(axis=-1), distance > 0)


def test_goal_distance_at_cell_centres_is_cells_to_go() -> None:
    world = mazesim.generate_maze(5, 5, seed=7)
    maze = CellMaze(world)
    assert maze.goal_cell is not None
    cells_to_go = maze.distances_from(maze.goal_cell)
    cells = [cell for cell in maze.cells() if cell != maze.goal_cell]
    poses = np.array([[*maze.center(cell), 0.0] for cell in cells], dtype=np.float32)
    distances, reached = GoalDistance(len(cells), PathDistanceTable.of_world(world)).evaluate(poses)
    expected = np.array([cells_to_go[row, column] * maze.cell_size for column, row in cells])
    # Within a cell the distance blends its sides', so a centre lies within a quarter cell of its
    # cell count, and farther cells are farther.
    assert np.all(np.abs(distances - expected) <= 0.25 * maze.cell_size)
    order = np.argsort(expected, kind="stable")
    farther = np.diff(expected[order]) > 0
    assert np.all(np.diff(distances[order])[farther] > 0)
    assert not reached.any()


def test_a_world_without_a_maze_has_no_cell_model() -> None:
    with pytest.raises(InvalidArgumentError, match=r"\[grid\] cell maze"):
        CellMaze(mazesim.load_world("arena"))


@pytest.mark.parametrize("world_name", ["seed-maze", "arena", "generated"])
def test_goal_distance_of_one_env_in_python_floats_equals_the_vectorised_one(
    world_name: str,
) -> None:
    if world_name == "generated":
        world = mazesim.generate_maze(6, 4, seed=3)
    else:
        world = mazesim.load_world(world_name)
    table = PathDistanceTable.of_world(world)
    rng = np.random.default_rng(0)
    xmin, ymin, xmax, ymax = world.bounds
    poses = np.zeros((500, 3), dtype=np.float32)
    poses[:, 0] = rng.uniform(xmin, xmax, 500)
    poses[:, 1] = rng.uniform(ymin, ymax, 500)
    many, reached = GoalDistance(500, table).evaluate(poses)
    one = GoalDistance(1, PathDistanceTable.of_world(mazesim.load_world("seed-maze")))
    one.set(0, table)  # a table of another world replaces the first, the scalar one with it
    for i, (x, y, _) in enumerate(poses.tolist()):
        assert one.evaluate_one(x, y) == (many[i], reached[i]), i
