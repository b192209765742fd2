"""The hand-written baselines reach the goal of unseen mazes from the observation alone, the same
way every time, and the frontier explorer's map holds only the cells the robot has been in."""

from __future__ import annotations

import math

import gymnasium
import numpy as np
import pytest

import mazesim  # noqa: F401  (registers the tasks)
from mazesim.envs.baselines import CellAgent, FrontierExplorer, WallFollower, evaluate
from mazesim.errors import InvalidArgumentError

TASK = "mazesim/UnseenMazeExplore-v0"
AGENTS = [WallFollower, FrontierExplorer]


def run_episode(
    agent_class: type[CellAgent], seed: int, include_pose: bool = False
) -> tuple[CellAgent, list[np.ndarray], set[tuple[int, int]], dict]:
    """One episode of ``TASK``: the agent, its actions, the cells the robot's true pose was in,
    and the last info."""
    env = gymnasium.make(TASK, include_pose=include_pose)
    agent = agent_class(env.get_wrapper_attr("observation_names"))
    observation, info = env.reset(seed=seed)
    actions, cells = [], set()
    while True:
        x, y = info["pose"][:2]
        cells.add((math.floor(x / 0.25), math.floor(y / 0.25)))
        action = agent.act(observation)
        actions.append(action)
        observation, _, terminated, truncated, info = env.step(action)
        if terminated or truncated:
            env.close()
            return agent, actions, cells, info


@pytest.mark.parametrize("agent_class", AGENTS)
@pytest.mark.parametrize(("seed", "include_pose"), [(3, False), (11, False), (3, True)])
def test_a_baseline_reaches_the_goal_of_an_unseen_maze(
    agent_class: type[CellAgent], seed: int, include_pose: bool
) -> None:
    agent, actions, _, info = run_episode(agent_class, seed, include_pose)
    assert agent.uses_pose == include_pose
    assert info["is_success"]
    assert len(actions) < 1000


@pytest.mark.parametrize("agent_class", AGENTS)
def test_a_baseline_is_deterministic(agent_class: type[CellAgent]) -> None:
    _, first, _, _ = run_episode(agent_class, 5)
    _, second, _, _ = run_episode(agent_class, 5)
    assert len(first) == len(second)
    assert all(np.array_equal(a, b) for a, b in zip(first, second))


def test_the_frontier_explorer_maps_only_cells_it_has_been_in() -> None:
    agent, _, cells, info = run_episode(FrontierExplorer, 7, include_pose=True)
    assert info["is_success"]
    assert agent.known, "it mapped nothing"
    assert set(agent.known) <= cells
    # Without the pose its cells are relative to the goal's, in axes of its own: as many.
    agent, _, cells, info = run_episode(FrontierExplorer, 7)
    assert info["is_success"]
    assert 0 < len(agent.known) <= len(cells)


def test_the_frontier_explorer_goes_to_an_open_unexplored_side_first() -> None:
    """A constructed observation: the robot at the centre of cell (2, 2) facing east, only its
    north side open, the goal far to the south-east: it must go north, the only way."""
    names = ["goal_forward", "goal_left", "x", "y", "heading_cos", "heading_sin"]
    names += ["open_ahead", "open_left", "open_behind", "open_right"]
    agent = FrontierExplorer(names)
    observation = np.array([0.4, -0.4, 0.5, 0.5, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0], dtype=np.float32)
    left, right = agent.act(observation)
    assert right > left  # turning left, to the north
    assert agent.known == {(2, 2): (False, True, False, False)}


def test_an_observation_without_the_explored_map_is_refused() -> None:
    names = gymnasium.make("mazesim/MazeFixed-v1").get_wrapper_attr("observation_names")
    with pytest.raises(InvalidArgumentError, match="missing: open_ahead"):
        WallFollower(names)


def test_evaluate_counts_successes_and_lengths() -> None:
    result = evaluate(TASK, WallFollower, episodes=4, seed=10**6)
    assert result.episodes == 4
    assert result.success == 1.0
    assert result.mean_length == result.mean_success_length
    random = evaluate(TASK, None, episodes=4, seed=10**6)
    assert random.success < 1.0
    assert random.mean_length > result.mean_length


@pytest.mark.parametrize(
    ("change", "found"),
    [
        (lambda o: np.full_like(o, np.nan), "NaN or infinity"),
        (lambda o: np.full_like(o, np.inf), "NaN or infinity"),
        (lambda o: o[:3], r"shape \(3,\)"),
        (lambda o: np.stack([o, o]), r"shape \(2, "),
    ],
)
def test_an_observation_of_another_shape_or_not_finite_is_refused(change, found) -> None:  # type: ignore[no-untyped-def]
    env = gymnasium.make("mazesim/UnseenMazeExplore-v0")
    observation, _ = env.reset(seed=0)
    for agent_class in (WallFollower, FrontierExplorer):
        agent = agent_class(env.get_wrapper_attr("observation_names"))
        with pytest.raises(InvalidArgumentError, match=found):
            agent.act(change(observation))
        assert agent.act(observation).shape == (2,)


def test_evaluate_runs_mazes_of_another_size_with_agents_that_know_it() -> None:
    sizes = []

    def agent(names: list[str], maze_size: tuple[int, int]) -> CellAgent:
        sizes.append(maze_size)
        return FrontierExplorer(names, maze_size)

    small = evaluate(TASK, agent, episodes=3, seed=10**6, maze_size=(3, 3))
    assert sizes == [(3, 3)] * 3
    assert small.success == 1.0
    usual = evaluate(TASK, FrontierExplorer, episodes=3, seed=10**6)
    # Three cells a side instead of five: shorter ways to the goal.
    assert small.mean_length < usual.mean_length
