"""The maze-size curriculum moves on when a stage's window of episodes reaches its success rate,
and the env's next episodes then draw mazes of the new size (episodes under way keep theirs)."""

from __future__ import annotations

import re

import gymnasium
import numpy as np
import pytest

import mazesim  # noqa: F401  (registers the tasks)
from mazesim.envs.baselines import FrontierExplorer
from mazesim.envs.curriculum import MazeSizeCurriculum, MazeSizeCurriculumWrapper
from mazesim.errors import InvalidArgumentError, WrongTypeError

TASK = "mazesim/UnseenMazeExplore-v0"


def maze_rows(envs: gymnasium.vector.VectorEnv) -> list[int]:
    """The number of rows of each environment's current maze (native vector env)."""
    worlds = envs.unwrapped._worlds  # type: ignore[attr-defined]
    return [int(world.cell_maze()["rows"]) for world in worlds]


def test_a_stage_ends_only_after_a_full_window_at_the_rate() -> None:
    curriculum = MazeSizeCurriculum(((3, 3), (5, 5), (7, 7)), promote_at=0.75, window=4)
    assert curriculum.size == (3, 3) and not curriculum.finished
    # Three successes out of three: the window is not full yet.
    assert not curriculum.record([True, True, True, False], [True, True, True, True])
    # A failure fills it at 3 of 4 = 0.75: the next stage.
    assert curriculum.record([False, True], [True, False])
    assert curriculum.size == (5, 5) and np.isnan(curriculum.success_rate)
    # A stage starts with an empty window: 2 of 4 does not move on, then 4 of the last 4 does.
    assert not curriculum.record([True] * 4, [True, False, True, False])
    assert not curriculum.record([True], [True])
    assert curriculum.record([True, True], [True, True])
    assert curriculum.finished and curriculum.size == (7, 7)
    # The last stage stays.
    assert not curriculum.record([True] * 8, [True] * 8)
    assert curriculum.state() == {
        "stage": 2,
        "maze_size": [7, 7],
        "success_rate": 1.0,
        "episodes": [4, 7, 8],
    }


@pytest.mark.parametrize(
    ("keywords", "words"),
    [
        ({"sizes": ()}, "at least one maze size"),
        ({"sizes": ((1, 3),)}, "at least 2 cells"),
        ({"sizes": ((3, 3, 3),)}, "(width, height)"),
        ({"sizes": ((1000, 1000),)}, "at most"),
        ({"promote_at": 0.0}, "success rate in (0, 1]"),
        ({"promote_at": 1.5}, "success rate in (0, 1]"),
        ({"window": 0}, "at least 1"),
    ],
)
def test_bad_stages_are_refused_saying_what_was_expected(
    keywords: dict[str, object], words: str
) -> None:
    with pytest.raises(InvalidArgumentError, match=words.replace("(", r"\(").replace(")", r"\)")):
        MazeSizeCurriculum(**keywords)  # type: ignore[arg-type]


def test_record_refuses_dones_and_successes_of_different_shapes() -> None:
    with pytest.raises(InvalidArgumentError, match="of one shape"):
        MazeSizeCurriculum().record([True, False], [True])


def test_apply_refuses_a_fixed_world_and_what_is_not_a_maze_env() -> None:
    curriculum = MazeSizeCurriculum()
    env = gymnasium.make("mazesim/MazeFixed-v1")
    with pytest.raises(InvalidArgumentError, match="world='random'"):
        curriculum.apply(env)
    env.close()
    with pytest.raises(InvalidArgumentError, match="CartPoleEnv"):
        curriculum.apply(gymnasium.make("CartPole-v1"))


def test_the_wrapper_given_one_env_says_how_to_make_a_vector_env_of_it() -> None:
    env = gymnasium.make(TASK)
    with pytest.raises(WrongTypeError, match=r"found a TimeLimit: .*gymnasium\.make_vec\(id"):
        MazeSizeCurriculumWrapper(env, MazeSizeCurriculum())
    env.close()


def test_the_wrapper_moves_the_native_vector_env_to_larger_mazes() -> None:
    envs = gymnasium.make_vec(TASK, num_envs=4, include_pose=True, max_episode_steps=200)
    curriculum = MazeSizeCurriculum(((3, 3), (4, 4)), promote_at=0.5, window=4)
    wrapped = MazeSizeCurriculumWrapper(envs, curriculum)
    observations, _ = wrapped.reset(seed=0)
    assert maze_rows(envs) == [3, 3, 3, 3]
    names = envs.unwrapped.observation_names  # type: ignore[attr-defined]
    agents = [FrontierExplorer(names, (3, 3)) for _ in range(4)]
    # The frontier explorer reaches the goals of 3 x 3 mazes: after 4 episodes the stage moves
    # on, and each environment's next episode (gymnasium's next-step autoreset) is 4 x 4.
    ended = np.zeros(4, dtype=bool)
    for _ in range(2000):
        actions = np.stack([agent.act(obs) for agent, obs in zip(agents, observations)])
        observations, _, terminated, truncated, _ = wrapped.step(actions)
        for i in np.flatnonzero(ended):  # this step started their next episode
            agents[i] = FrontierExplorer(names, curriculum.size)
        ended = terminated | truncated
        rows = maze_rows(envs)
        if curriculum.stage == 0:
            assert rows == [3, 3, 3, 3]
        if rows == [4, 4, 4, 4]:
            break
    assert curriculum.stage == 1 and curriculum.episodes[0] >= 4
    assert maze_rows(envs) == [4, 4, 4, 4]
    # The observation keeps its shape whatever the size.
    assert wrapped.observation_space.shape == envs.observation_space.shape
    wrapped.close()


def test_the_wrapper_sets_the_size_of_every_single_env_of_a_sync_vector_env() -> None:
    envs = gymnasium.make_vec(TASK, num_envs=2, vectorization_mode="sync")
    wrapped = MazeSizeCurriculumWrapper(envs, MazeSizeCurriculum(((3, 4), (5, 5))))
    wrapped.reset(seed=1)
    for env in envs.unwrapped.envs:  # type: ignore[attr-defined]
        maze = env.unwrapped.world.cell_maze()
        assert (int(maze["cols"]), int(maze["rows"])) == (3, 4)
    wrapped.close()


GOAL_TASK = "mazesim/UnseenMazeGoal-v0"


@pytest.mark.parametrize("mode", ["vector_entry_point", "sync"])
def test_a_goal_task_follows_the_curriculum_inside_its_observation_space(mode: str) -> None:
    envs = gymnasium.make_vec(
        GOAL_TASK, num_envs=3, vectorization_mode=mode, maze_size=(5, 5), max_episode_steps=20
    )
    curriculum = MazeSizeCurriculum(((3, 3), (4, 4), (5, 5)), promote_at=1.0, window=1)
    wrapped = MazeSizeCurriculumWrapper(envs, curriculum)
    observations, _ = wrapped.reset(seed=0)
    wrapped.action_space.seed(0)
    sides = set()
    for stage in range(3):
        for _ in range(41):  # two episodes of 20 steps each, the next-step resets included
            observations, *_ = wrapped.step(wrapped.action_space.sample())
            assert envs.observation_space.contains(observations)
            # Every desired goal lies in the current mazes: within 3 x 3 cells of 0.25 m at first.
            sides.add(float(observations["desired_goal"].max()) < 0.25 * (3 + stage))
        if stage < 2:
            assert curriculum.record([True], [True])
            wrapped._apply()  # as the wrapper does when a stage ends
    assert sides == {True}
    single = gymnasium.make(GOAL_TASK, maze_size=(5, 5))
    MazeSizeCurriculum(((3, 3),)).apply(single)
    single.reset(seed=0)
    assert single.unwrapped.maze.world.cell_maze()["rows"] == 3
    wrapped.close()


@pytest.mark.parametrize(
    ("env_id", "options", "size"),
    [
        (GOAL_TASK, {}, (7, 7)),  # achieved_goal and desired_goal in metres
        ("mazesim/EPuckMaze-v0", {"world": "random", "include_pose": True}, (9, 9)),
    ],
)
def test_apply_refuses_stages_the_observation_space_does_not_hold_before_any_runs(
    env_id: str, options: dict[str, object], size: tuple[int, int]
) -> None:
    envs = gymnasium.make_vec(env_id, num_envs=2, **options)
    curriculum = MazeSizeCurriculum(((3, 3), size))
    with pytest.raises(
        InvalidArgumentError, match=re.escape(f"make the env with maze_size={size}")
    ):
        MazeSizeCurriculumWrapper(envs, curriculum)  # at the first stage already
    larger = gymnasium.make_vec(env_id, num_envs=2, maze_size=size, **options)
    MazeSizeCurriculumWrapper(larger, curriculum)  # made for the largest mazes: accepted
    # Observations without positions in metres hold every size.
    for plain in (
        gymnasium.make_vec("mazesim/EPuckMaze-v0", num_envs=2, world="random"),
        gymnasium.make_vec(TASK, num_envs=2, include_pose=True),  # x and y are 0 to 1
    ):
        MazeSizeCurriculumWrapper(plain, MazeSizeCurriculum(((3, 3), (9, 9))))
