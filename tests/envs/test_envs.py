"""The gymnasium environments: API conformance, the native vector env against SyncVectorEnv, the
reward's shortest-path distance, rendering and the checks of every action."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

from gymnasium.error import ClosedEnvironmentError, ResetNeeded  # noqa: E402
from gymnasium.utils.env_checker import check_env  # noqa: E402

import mazesim  # noqa: E402
from env_worlds import CORRIDOR  # noqa: E402
from mazesim.actions import (  # noqa: E402
    ACTION_CODES,
    WHEEL_SPEED_FRACTIONS,
    action_index,
    wheel_speeds,
)
from mazesim.envs import ENV_ID, EPuckMazeEnv, EPuckMazeVectorEnv  # noqa: E402
from mazesim.envs.reward import GoalDistance, PathDistanceTable  # noqa: E402
from mazesim.errors import InvalidActionError, InvalidArgumentError  # noqa: E402
from mazesim.render.topdown import ROBOT_RGB  # noqa: E402


@pytest.fixture(scope="module")
def corridor(tmp_path_factory: pytest.TempPathFactory) -> str:
    path = tmp_path_factory.mktemp("worlds") / "corridor.toml"
    path.write_text(CORRIDOR)
    return str(path)


def test_import_registers_both_entry_points() -> None:
    spec = gymnasium.spec(ENV_ID)
    assert spec.max_episode_steps == 3000
    assert spec.entry_point == "mazesim.envs.maze_env:EPuckMazeEnv"
    assert spec.vector_entry_point == "mazesim.envs.vector:EPuckMazeVectorEnv"
    mazesim.envs.register_envs()  # again: no second registration, no warning


def test_import_mazesim_works_without_gymnasium() -> None:
    script = (
        "import sys; sys.modules['gymnasium'] = None\n"
        "import mazesim\n"
        "assert mazesim.Simulator(mazesim.load_world('arena')).time == 0.0\n"
        "try:\n"
        "    import mazesim.envs\n"
        "except mazesim.errors.MissingDependencyError as error:\n"
        "    assert 'pip install' in str(error)\n"
        "else:\n"
        "    raise AssertionError('mazesim.envs imported without gymnasium')\n"
    )
    subprocess.run([sys.executable, "-W", "error", "-c", script], check=True)


@pytest.mark.parametrize(
    "options",
    [
        {"action_mode": "continuous"},
        {"action_mode": "discrete"},
        {"world": "random"},
        {"world": "random", "action_mode": "discrete", "robot": "seed", "include_pose": True},
        {"robot": "alphabot2", "noise": False},
    ],
    ids=["continuous", "discrete", "random", "random-discrete-seed-pose", "alphabot2"],
)
def test_check_env_passes_without_warnings(options: dict[str, Any]) -> None:
    # pytest turns every warning into an error (pyproject.toml).
    env = gymnasium.make(ENV_ID, **options)
    check_env(env.unwrapped)
    env.close()


def _assert_same(native: tuple[Any, ...], sync: tuple[Any, ...], where: str) -> None:
    names = ("observations", "rewards", "terminations", "truncations")
    for name, mine, theirs in zip(names, native[:-1], sync[:-1]):
        assert mine.dtype == theirs.dtype, f"{where}: {name} dtype"
        assert np.array_equal(mine, theirs), f"{where}: {name} differ"
    info, expected = native[-1], sync[-1]
    assert info.keys() == expected.keys(), f"{where}: info keys"
    for key in info:
        assert info[key].dtype == expected[key].dtype, f"{where}: info[{key!r}] dtype"
        assert np.array_equal(info[key], expected[key]), f"{where}: info[{key!r}] differ"


@pytest.mark.parametrize(
    ("options", "forward_bias"),
    [
        ({"max_episode_steps": 40}, False),
        ({"max_episode_steps": 60, "action_mode": "discrete"}, False),
        ({"max_episode_steps": 50, "world": "random", "include_pose": True}, False),
        ({"max_episode_steps": 180, "world": "CORRIDOR"}, True),
    ],
    ids=["seed-maze", "discrete", "random-maze", "corridor-goal-and-barcode"],
)
def test_native_vector_env_equals_sync_vector_env(
    options: dict[str, Any], forward_bias: bool, corridor: str
) -> None:
    if options.get("world") == "CORRIDOR":
        options = {**options, "world": corridor}
    num_envs = 6
    native = gymnasium.make_vec(
        ENV_ID, num_envs, vectorization_mode="vector_entry_point", threads=2, **options
    )
    sync = gymnasium.make_vec(ENV_ID, num_envs, vectorization_mode="sync", **options)
    assert isinstance(native.unwrapped, EPuckMazeVectorEnv)
    assert native.single_observation_space == sync.single_observation_space
    assert native.single_action_space == sync.single_action_space
    assert native.observation_space == sync.observation_space
    assert native.action_space == sync.action_space
    _assert_same((*native.reset(seed=42),), (*sync.reset(seed=42),), "reset")

    native.action_space.seed(7)
    rng = np.random.default_rng(7)
    seen = {"terminated": 0, "truncated": 0, "checkpoint": 0}
    for step in range(1000):
        if forward_bias:  # random wheel speeds round 0.7 of the limit: the robots reach the goal
            actions: Any = (0.7 + 0.3 * rng.uniform(-1, 1, (num_envs, 2))).astype(np.float32)
        else:
            actions = native.action_space.sample()
        result = native.step(actions)
        _assert_same(result, sync.step(actions), f"step {step}")
        seen["terminated"] += int(result[2].sum())
        seen["truncated"] += int(result[3].sum())
        seen["checkpoint"] += "checkpoint" in result[4]

    mask = np.zeros(num_envs, dtype=bool)
    mask[[1, 4]] = True
    reset_native = native.reset(seed=9, options={"reset_mask": mask})
    _assert_same(reset_native, sync.reset(seed=9, options={"reset_mask": mask}), "masked reset")
    assert reset_native[1]["_pose"].tolist() == mask.tolist()
    for step in range(20):
        actions = native.action_space.sample()
        _assert_same(native.step(actions), sync.step(actions), f"after masked reset, step {step}")

    assert seen["truncated"] > 0
    if forward_bias:
        assert seen["terminated"] > 0 and seen["checkpoint"] > 0
    native.close()
    sync.close()


def _rollout(env: Any, seed: int, steps: int) -> list[Any]:
    observation, info = env.reset(seed=seed)
    env.action_space.seed(seed)
    trace = [observation, info]
    for _ in range(steps):
        trace.append(env.step(env.action_space.sample()))
    return trace


@pytest.mark.parametrize("world", ["seed-maze", "random"])
def test_same_seed_same_episode(world: str) -> None:
    first = _rollout(gymnasium.make(ENV_ID, world=world), seed=3, steps=200)
    again = _rollout(gymnasium.make(ENV_ID, world=world), seed=3, steps=200)
    other = _rollout(gymnasium.make(ENV_ID, world=world), seed=4, steps=200)
    assert gymnasium.utils.env_checker.data_equivalence(first, again, exact=True)
    assert not gymnasium.utils.env_checker.data_equivalence(first, other)


def test_vector_env_seeds_env_i_with_seed_plus_i() -> None:
    vector = EPuckMazeVectorEnv(num_envs=3, world="random")
    observations, _ = vector.reset(seed=10)
    for i in range(3):
        single = EPuckMazeEnv(world="random")
        observation, _ = single.reset(seed=10 + i)
        assert np.array_equal(observation, observations[i])


def test_vector_env_takes_numpy_seeds_and_refuses_others_by_name() -> None:
    vector = EPuckMazeVectorEnv(num_envs=2, world="random")
    reference, _ = vector.reset(seed=10)
    assert np.array_equal(vector.reset(seed=np.int64(10))[0], reference)
    assert np.array_equal(vector.reset(seed=[np.int32(10), 11])[0], reference)
    for seed in (2.5, "10", -1, [10, 11, 12], [10, 1.5], (True, 3)):
        # A text is refused by the argument check before the call, naming the annotation.
        with pytest.raises(InvalidArgumentError, match="expected seed|seed refused: expected int"):
            vector.reset(seed=seed)  # type: ignore[arg-type]


def test_close_twice_is_safe() -> None:
    env = gymnasium.make(ENV_ID)
    env.reset(seed=0)
    env.close()
    env.close()
    unwrapped = EPuckMazeEnv()
    unwrapped.close()
    with pytest.raises(ClosedEnvironmentError):
        unwrapped.step(np.zeros(2, dtype=np.float32))
    vector = gymnasium.make_vec(ENV_ID, num_envs=4)
    vector.reset(seed=0)
    vector.close()
    vector.close()
    with pytest.raises(ClosedEnvironmentError):
        vector.step(np.zeros((4, 2), dtype=np.float32))


def test_step_before_reset_raises() -> None:
    with pytest.raises(ResetNeeded):
        EPuckMazeVectorEnv(num_envs=2).step(np.zeros((2, 2), dtype=np.float32))


@pytest.mark.parametrize(
    ("action", "message"),
    [
        (np.zeros(3, dtype=np.float32), "shape"),
        (np.zeros((1, 2), dtype=np.float32), "shape"),
        (np.array(["a", "b"]), "dtype"),
        (np.array([True, False]), "dtype"),
        (np.array([1 + 0j, 0j]), "dtype"),
        (np.array([np.nan, 0.0], dtype=np.float32), "finite"),
        (np.array([0.0, np.inf]), "finite"),
        (np.array([1.5, 0.0], dtype=np.float32), "[-1, 1]"),
        (np.array([0.0, -1.01]), "[-1, 1]"),
    ],
)
def test_bad_continuous_actions_raise_invalid_action_error(action: Any, message: str) -> None:
    env = gymnasium.make(ENV_ID, clip_actions=False)
    env.reset(seed=0)
    with pytest.raises(InvalidActionError, match=message.replace("[", r"\[").replace("]", r"\]")):
        env.step(action)
    assert issubclass(InvalidActionError, ValueError)


@pytest.mark.parametrize("action", [12, -1, 2.0, np.float32(1), True, "00", np.array([1, 2])])
def test_bad_discrete_actions_raise_invalid_action_error(action: Any) -> None:
    env = gymnasium.make(ENV_ID, action_mode="discrete")
    env.reset(seed=0)
    with pytest.raises(InvalidActionError, match="expected"):
        env.step(action)


def test_bad_vector_actions_name_the_environment() -> None:
    envs = gymnasium.make_vec(ENV_ID, num_envs=4, clip_actions=False)
    envs.reset(seed=0)
    actions = np.zeros((4, 2), dtype=np.float32)
    actions[2, 1] = np.nan
    with pytest.raises(InvalidActionError, match="right wheel in environment 2"):
        envs.step(actions)
    with pytest.raises(InvalidActionError, match="shape"):
        envs.step(np.zeros((3, 2), dtype=np.float32))
    discrete = gymnasium.make_vec(ENV_ID, num_envs=4, action_mode="discrete")
    discrete.reset(seed=0)
    with pytest.raises(InvalidActionError, match="found 12 in environment 3"):
        discrete.step(np.array([0, 1, 2, 12]))
    with pytest.raises(InvalidActionError, match="integers"):
        discrete.step(np.zeros(4, dtype=np.float32))


def test_bad_options_raise_clear_errors() -> None:
    with pytest.raises(mazesim.UnknownNameError, match="action_mode"):
        EPuckMazeEnv(action_mode="joystick")
    # Once an InvalidArgumentError: code that caught ValueError (or LookupError) still does.
    with pytest.raises(ValueError, match="action_mode"):
        EPuckMazeEnv(action_mode="joystick")
    with pytest.raises(LookupError, match="action_mode"):
        EPuckMazeEnv(action_mode="joystick")
    with pytest.raises(mazesim.UnknownNameError):
        EPuckMazeEnv(world="no-such-world")
    with pytest.raises(mazesim.UnknownNameError):
        EPuckMazeEnv(robot="no-such-robot")
    with pytest.raises(mazesim.UnknownNameError, match="render_mode"):
        EPuckMazeEnv(render_mode="window")
    with pytest.raises(mazesim.UnknownNameError, match="render_mode"):
        EPuckMazeVectorEnv(num_envs=2, render_mode="human")  # images only
    with pytest.raises(InvalidArgumentError, match="reset_mask"):
        vector = EPuckMazeVectorEnv(num_envs=2)
        vector.reset(options={"reset_mask": np.array([1, 0])})


def test_action_table_is_the_reports() -> None:
    assert ACTION_CODES == ("00", "11", "22", "33", "44", "55", "66", "77", "88", "aa", "bb", "99")
    assert WHEEL_SPEED_FRACTIONS.shape == (12, 2)
    assert not WHEEL_SPEED_FRACTIONS.flags.writeable
    assert wheel_speeds("00", 6.28) == (3.14, 3.14)
    assert wheel_speeds("AA", 6.28) == (1.57, -1.57)
    assert wheel_speeds("44", 6.28) == (3.14, 0.0)
    assert action_index("99") == 11
    right, left = WHEEL_SPEED_FRACTIONS[1:5], WHEEL_SPEED_FRACTIONS[5:9]
    assert np.all(right[:, 0] > right[:, 1]) and np.all(np.diff(right[:, 1]) < 0)
    assert np.array_equal(left, right[:, ::-1])
    with pytest.raises(InvalidActionError, match="00, 11"):
        wheel_speeds("12", 6.28)


def test_discrete_actions_drive_the_table_speeds() -> None:
    env = EPuckMazeEnv(action_mode="discrete", noise=False)
    env.reset(seed=0)
    simulator = env._simulator
    assert simulator is not None
    for index, code in enumerate(ACTION_CODES):
        env.step(index)
        expected = np.float32(wheel_speeds(code, 6.28)).astype(np.float64)
        assert simulator.wheel_speeds == pytest.approx(tuple(expected), abs=1e-6)


def test_observations_stay_inside_the_space_with_noise() -> None:
    for robot in ("e-puck", "seed", "alphabot2"):
        envs = EPuckMazeVectorEnv(num_envs=64, robot=robot, world="random", include_pose=True)
        observations, _ = envs.reset(seed=1)
        space = envs.single_observation_space
        for _ in range(100):
            assert all(space.contains(row) for row in observations)
            observations, *_ = envs.step(envs.action_space.sample())
        assert envs.observation_names[-3:] == ["x", "y", "yaw"]


def test_shortest_path_distance_follows_the_corridors(corridor: str) -> None:
    table = PathDistanceTable.of_world(mazesim.load_world(corridor))
    assert table.mode == "maze"
    y = 0.125
    xs = np.array([0.125, 0.25 - 1e-9, 0.25 + 1e-9, 0.375, 0.5, 0.625])
    poses = np.column_stack((xs, np.full(6, y), np.zeros(6))).astype(np.float32)
    distances = GoalDistance(6, table).evaluate(poses)[0]
    # Two cells from the goal at the start, linear along the corridor, 0 at the goal point.
    assert distances[0] == pytest.approx(0.5)
    assert distances[1] == pytest.approx(distances[2], abs=1e-6)
    assert distances[3] == pytest.approx(0.25)
    assert distances[5] == pytest.approx(0.0, abs=1e-6)
    assert np.all(np.diff(distances[[0, 2, 3, 4, 5]]) < 0)

    # In seed-maze the distance falls along the way to the goal, and is 0 at the goal.
    world = mazesim.load_world("seed-maze")
    goal = GoalDistance(1, PathDistanceTable.of_world(world))
    start = goal.evaluate(np.array([world.start], dtype=np.float32))[0][0]
    at_goal = goal.evaluate(np.array([[*world.goal[:2], 0.0]], dtype=np.float32))[0][0]
    assert start > 2.0 and at_goal == pytest.approx(0.0, abs=1e-6)


def test_progress_rewards_sum_to_the_distance_gained(corridor: str) -> None:
    env = EPuckMazeEnv(world=corridor, noise=False, collision_penalty=0.0, goal_reward=0.0)
    _, info = env.reset(seed=0)
    start = info["distance_to_goal"]
    total, terminated, steps = 0.0, False, 0
    while not terminated and steps < 400:
        _, reward, terminated, _, info = env.step(np.array([0.8, 0.8], dtype=np.float32))
        total += float(reward)
        steps += 1
    assert terminated
    assert total == pytest.approx(10.0 * (start - info["distance_to_goal"]))
    assert info["collisions"] == 0


def test_goal_bonus_and_collision_penalty(corridor: str) -> None:
    env = EPuckMazeEnv(world=corridor, noise=False, progress_reward=0.0)
    env.reset(seed=0)
    rewards = []
    terminated = False
    while not terminated:
        _, reward, terminated, _, info = env.step(np.array([0.8, 0.8], dtype=np.float32))
        rewards.append(reward)
    assert rewards[-1] == pytest.approx(10.0) and sum(rewards[:-1]) == 0.0
    env.reset(seed=0)
    for _ in range(80):  # backwards into the west wall
        _, reward, _, _, info = env.step(np.array([-1.0, -1.0], dtype=np.float32))
    assert info["colliding"] and reward == pytest.approx(-0.1)


def test_rgb_array_frames_show_the_robot() -> None:
    env = gymnasium.make(ENV_ID, render_mode="rgb_array")
    env.reset(seed=0)
    frame = env.render()
    assert frame.shape == (400, 400, 3) and frame.dtype == np.uint8
    renderer = env.unwrapped._renderer
    x, y, _ = env.unwrapped._simulator.pose
    column, row = int(renderer._x0 + x * renderer.scale), int(renderer._y0 - y * renderer.scale)
    assert tuple(frame[row + 5, column]) == ROBOT_RGB  # beside the heading mark
    small = gymnasium.make(ENV_ID, render_mode="rgb_array", render_size=(160, 120))
    small.reset(seed=0)
    assert small.render().shape == (120, 160, 3)
    vector = gymnasium.make_vec(ENV_ID, num_envs=3, world="random", render_mode="rgb_array")
    vector.reset(seed=0)
    frames = vector.render()
    assert len(frames) == 3 and all(f.shape == (400, 400, 3) for f in frames)
    assert not np.array_equal(frames[0], frames[1])  # each env its own maze


def test_readme_examples_run(tmp_path: Path) -> None:
    envs = gymnasium.make_vec(ENV_ID, num_envs=16, world="random")
    assert isinstance(envs.unwrapped, EPuckMazeVectorEnv)  # the native vector env by default
    observations, infos = envs.reset(seed=0)
    for _ in range(10):
        actions = envs.action_space.sample()
        observations, rewards, terminations, truncations, infos = envs.step(actions)
    assert observations.shape == (16, 11) and rewards.dtype == np.float64
    envs.close()

    image_module = pytest.importorskip("PIL.Image")
    env = gymnasium.make(ENV_ID, render_mode="rgb_array", action_mode="discrete")
    env.reset(seed=0)
    frames = [env.render()]
    for _ in range(5):
        *_, terminated, truncated, info = env.step(env.action_space.sample())
        frames.append(env.render())
    images = [image_module.fromarray(frame) for frame in frames]
    path = tmp_path / "episode.gif"
    images[0].save(path, save_all=True, append_images=images[1:], duration=32, loop=0)
    assert path.read_bytes().startswith(b"GIF8")
