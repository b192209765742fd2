"""Stable-Baselines3 through the batch engine: mazesim.integrations.sb3 against DummyVecEnv."""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")
pytest.importorskip(
    "stable_baselines3", reason="needs the optional extra mazesim[sb3] (make sb3-deps)"
)

import torch  # noqa: E402
from stable_baselines3 import PPO, SAC  # noqa: E402
from stable_baselines3.common.env_checker import check_env  # noqa: E402
from stable_baselines3.common.env_util import make_vec_env as sb3_make_vec_env  # noqa: E402
from stable_baselines3.common.vec_env import DummyVecEnv, VecEnv  # noqa: E402

from env_worlds import CORRIDOR  # noqa: E402
from mazesim.envs import ENV_ID, TASKS  # noqa: E402
from mazesim.envs.tasks import FORMER_IDS, GOAL_TASKS  # noqa: E402
from mazesim.errors import InvalidArgumentError  # noqa: E402
from mazesim.integrations.sb3 import MazesimVecEnv, make_vec_env  # noqa: E402


def dummy_vec_env(n_envs: int, **options: Any) -> DummyVecEnv:
    """SB3's reference: single envs stepped one by one in Python."""
    return DummyVecEnv([lambda: gymnasium.make(ENV_ID, **options) for _ in range(n_envs)])


def assert_same_infos(mine: list[dict[str, Any]], theirs: list[dict[str, Any]], where: str) -> None:
    assert len(mine) == len(theirs)
    for env, (a, b) in enumerate(zip(mine, theirs)):
        assert a.keys() == b.keys(), f"{where}, env {env}: keys {sorted(a)} != {sorted(b)}"
        for key in a:
            assert type(a[key]) is type(b[key]), f"{where}, env {env}: type of {key}"
            if isinstance(a[key], (np.ndarray, dict)):  # a goal task's observation is a dict
                assert same_arrays(a[key], b[key]), f"{where}, env {env}: {key}"
            else:
                assert a[key] == b[key], f"{where}, env {env}: {key} {a[key]} != {b[key]}"


def same_arrays(mine: Any, theirs: Any) -> bool:
    """Whether two arrays, or two dicts of arrays (``Dict`` observations), are equal, dtypes
    included."""
    if isinstance(theirs, dict):
        return mine.keys() == theirs.keys() and all(same_arrays(mine[k], theirs[k]) for k in mine)
    return mine.dtype == theirs.dtype and np.array_equal(mine, theirs)


@pytest.fixture(scope="module")
def corridor(tmp_path_factory: pytest.TempPathFactory) -> str:
    path = tmp_path_factory.mktemp("worlds") / "corridor.toml"
    path.write_text(CORRIDOR)
    return str(path)


@pytest.mark.parametrize("world", ["corridor", "random"])
def test_adapter_equals_dummy_vec_env_bit_for_bit(world: str, corridor: str) -> None:
    options = {"world": corridor if world == "corridor" else world, "max_episode_steps": 220}
    n_envs = 4
    fast = make_vec_env(ENV_ID, n_envs, seed=11, monitor=False, **options)
    reference = dummy_vec_env(n_envs, **options)
    reference.seed(11)
    assert fast.observation_space == reference.observation_space
    assert fast.action_space == reference.action_space
    assert np.array_equal(fast.reset(), reference.reset())
    assert_same_infos(fast.reset_infos, reference.reset_infos, "reset")
    rng = np.random.default_rng(3)
    dones = successes = crossings = 0
    for step in range(700):
        actions = (0.7 + 0.3 * rng.uniform(-1, 1, (n_envs, 2))).astype(np.float32)
        mine, theirs = fast.step(actions), reference.step(actions)
        for name, a, b in zip(("observations", "rewards", "dones"), mine[:3], theirs[:3]):
            assert a.dtype == b.dtype and np.array_equal(a, b), f"step {step}: {name}"
        assert_same_infos(mine[3], theirs[3], f"step {step}")
        assert_same_infos(fast.reset_infos, reference.reset_infos, f"step {step} resets")
        dones += int(mine[2].sum())
        successes += sum(info["is_success"] for info in mine[3])
        crossings += sum("checkpoint" in info for info in mine[3])
    assert dones >= n_envs
    if world == "corridor":
        assert successes > 0 and crossings > 0


@pytest.mark.parametrize(
    "task", TASKS[1:] + GOAL_TASKS, ids=[task.env_id for task in TASKS[1:] + GOAL_TASKS]
)
def test_adapter_equals_dummy_vec_env_on_every_tier(task: Any) -> None:
    n_envs = 3
    fast = make_vec_env(task.env_id, n_envs, seed=5, monitor=False, max_episode_steps=40)
    reference = DummyVecEnv(
        [lambda: gymnasium.make(task.env_id, max_episode_steps=40) for _ in range(n_envs)]
    )
    reference.seed(5)
    assert fast.observation_space == reference.observation_space
    assert same_arrays(fast.reset(), reference.reset())
    rng = np.random.default_rng(5)
    dones = 0
    for step in range(100):
        actions = rng.uniform(-1, 1, (n_envs, 2)).astype(np.float32)
        mine, theirs = fast.step(actions), reference.step(actions)
        for name, a, b in zip(("observations", "rewards", "dones"), mine[:3], theirs[:3]):
            assert same_arrays(a, b), f"step {step}: {name}"
        assert_same_infos(mine[3], theirs[3], f"step {step}")
        dones += int(mine[2].sum())
    assert dones >= 2 * n_envs  # episodes ended and restarted in new starts and goals


def test_her_relabels_through_the_adapter_of_a_goal_task() -> None:
    from stable_baselines3 import SAC, HerReplayBuffer

    envs = make_vec_env("mazesim/EPuckGoal-v0", 2, seed=0, max_episode_steps=40)
    model = SAC(
        "MultiInputPolicy",
        envs,
        replay_buffer_class=HerReplayBuffer,
        learning_starts=100,
        batch_size=32,
        policy_kwargs={"net_arch": [16, 16]},
        seed=0,
        device="cpu",
    )
    model.learn(total_timesteps=200)
    sample = model.replay_buffer.sample(64)  # relabelled rewards, from compute_reward
    recomputed = envs.env_method(
        "compute_reward",
        sample.next_observations["achieved_goal"].numpy(),
        sample.observations["desired_goal"].numpy(),
        None,
        indices=[0],
    )[0]
    assert np.array_equal(sample.rewards.numpy().ravel(), recomputed.astype(np.float32))
    assert set(np.unique(recomputed)) <= {-1.0, 0.0}


def test_ppo_trained_through_the_adapter_gives_the_same_weights() -> None:
    def train(envs: VecEnv) -> dict[str, torch.Tensor]:
        model = PPO(
            "MlpPolicy", envs, n_steps=128, batch_size=128, n_epochs=2, seed=5, device="cpu"
        )
        model.learn(total_timesteps=2048)
        return model.policy.state_dict()

    options = {"world": "random", "max_episode_steps": 100}
    fast = train(make_vec_env(ENV_ID, 4, **options))
    reference = train(dummy_vec_env(4, **options))
    assert fast.keys() == reference.keys()
    for name in fast:
        assert torch.equal(fast[name], reference[name]), name
    untrained = PPO("MlpPolicy", make_vec_env(ENV_ID, 4, **options), seed=5, device="cpu")
    assert not all(torch.equal(fast[n], untrained.policy.state_dict()[n]) for n in fast)


def test_make_vec_env_monitors_episodes_and_success(corridor: str) -> None:
    envs = make_vec_env(ENV_ID, 2, seed=0, world=corridor, noise=False)
    envs.reset()
    forward = np.full((2, 2), 0.8, dtype=np.float32)
    for _ in range(300):
        _, _, dones, infos = envs.step(forward)
        if dones.any():
            break
    assert dones.all()
    for info in infos:
        assert info["is_success"] is True and not info["TimeLimit.truncated"]
        assert info["episode"]["l"] < 300 and info["episode"]["r"] > 10.0
        assert info["terminal_observation"].shape == (11,)


@pytest.mark.parametrize("task", TASKS, ids=[task.env_id for task in TASKS])
def test_check_env_of_stable_baselines3_passes_on_every_task(task: Any) -> None:
    check_env(gymnasium.make(task.env_id).unwrapped, warn=True)


def test_adapter_refuses_a_next_step_vector_env() -> None:
    from mazesim.envs import EPuckMazeVectorEnv

    with pytest.raises(InvalidArgumentError, match="SAME_STEP"):
        MazesimVecEnv(EPuckMazeVectorEnv(num_envs=2))


@pytest.mark.parametrize("attribute", ["observation_space", "action_space"])
def test_get_attr_gives_each_environments_space_as_dummy_vec_env(attribute: str) -> None:
    fast = make_vec_env(ENV_ID, 3, seed=0)
    reference = dummy_vec_env(3)
    spaces = fast.get_attr(attribute)
    assert spaces == reference.get_attr(attribute)
    assert spaces[0] == getattr(fast, attribute)
    assert fast.get_attr(attribute, indices=[1]) == reference.get_attr(attribute, indices=[1])


def test_get_attr_spec_is_a_single_envs_spec_that_makes_the_same_env() -> None:
    options = {"noise": False, "max_episode_steps": 99}
    fast = make_vec_env("mazesim/MazeFixed-v1", 2, seed=0, threads=1, **options)
    reference = DummyVecEnv([lambda: gymnasium.make("mazesim/MazeFixed-v1", **options)])
    spec = fast.get_attr("spec")[0]
    assert spec == reference.get_attr("spec")[0]
    evaluation = gymnasium.make(spec)  # refused the vector env's num_envs, threads, ... before
    assert evaluation.spec is not None and evaluation.spec.max_episode_steps == 99
    assert np.array_equal(evaluation.reset(seed=0)[0], reference.envs[0].reset(seed=0)[0])


def test_env_method_calls_each_environments_method_not_the_whole_engines() -> None:
    fast = make_vec_env(ENV_ID, 3, seed=0, world="random", render_mode="rgb_array")
    fast.reset()
    images = fast.get_images()
    frames = fast.env_method("render", indices=[2])
    assert len(frames) == 1 and np.array_equal(frames[0], images[2])  # env 2's image alone
    assert [frame.shape for frame in fast.env_method("render")] == [(400, 400, 3)] * 3
    for method in ("reset", "step", "close"):  # would act on all three environments at once
        with pytest.raises(InvalidArgumentError, match=f"found '{method}'"):
            fast.env_method(method, indices=[0])


def test_make_vec_env_takes_sb3s_arguments(tmp_path: Any) -> None:
    options = {"world": "random", "max_episode_steps": 20}
    shifted = make_vec_env(
        ENV_ID,
        2,
        seed=3,
        start_index=4,
        env_kwargs=options,
        vec_env_kwargs={"threads": 1},
        monitor_dir=str(tmp_path),
        monitor_kwargs={"info_keywords": ("is_success",)},
    )
    same = make_vec_env(ENV_ID, n_envs=2, seed=7, monitor=False, **options)
    assert np.array_equal(shifted.reset(), same.reset())
    actions = np.zeros((2, 2), dtype=np.float32)
    for _ in range(20):
        shifted.step(actions)
    shifted.close()
    log = (tmp_path / "monitor.monitor.csv").read_text().splitlines()
    assert log[1] == "r,l,t,is_success" and len(log) == 4  # two episodes of 20 steps
    assert make_vec_env(ENV_ID).num_envs == 1
    with pytest.raises(InvalidArgumentError, match="wrapper_class"):
        make_vec_env(ENV_ID, 2, wrapper_class=gymnasium.wrappers.ClipAction)
    with pytest.raises(InvalidArgumentError, match="vec_env_cls"):
        make_vec_env(ENV_ID, 2, vec_env_cls=DummyVecEnv)


#: Every id mazesim registers with gymnasium: its tasks and their former ids.
REGISTERED_IDS = [*(task.env_id for task in (*TASKS, *GOAL_TASKS)), *FORMER_IDS]


@pytest.mark.parametrize("env_id", REGISTERED_IDS)
def test_every_registered_id_trains_through_sb3s_make_vec_env_and_the_adapter(env_id: str) -> None:
    """SB3's env checker, then SB3's PPO through SB3's own make_vec_env and through mazesim's
    adapter: the two give the same spaces and neither fails (a former id included, which the
    adapter refused)."""
    env = gymnasium.make(env_id)
    goal = isinstance(env.observation_space, gymnasium.spaces.Dict)
    # SB3's goal-env check calls compute_reward on the env it is given, which gymnasium 1.x
    # wrappers do not pass on: the goal tasks are checked unwrapped (docs/rl.md).
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*out of date", category=DeprecationWarning)
        check_env(env.unwrapped if goal else env, warn=True)
        made = [make(env_id, n_envs=2, seed=0) for make in (sb3_make_vec_env, make_vec_env)]
    env.close()
    for envs in made:
        assert envs.observation_space == env.observation_space
        assert envs.action_space == env.action_space
        model = PPO(_policy(goal), envs, n_steps=32, batch_size=64, seed=0, device="cpu")
        assert model.learn(64).num_timesteps == 64
        envs.close()


@pytest.mark.parametrize("env_id", ["mazesim/UnseenMaze-v2", "mazesim/EPuckGoal-v0"])
def test_sac_trains_through_the_adapter(env_id: str) -> None:
    envs = make_vec_env(env_id, n_envs=2, seed=0)
    goal = isinstance(envs.observation_space, gymnasium.spaces.Dict)
    model = SAC(_policy(goal), envs, learning_starts=32, buffer_size=256, batch_size=32, seed=0)
    assert model.learn(96).num_timesteps == 96
    envs.close()


def _policy(goal: bool) -> str:
    return "MultiInputPolicy" if goal else "MlpPolicy"


def test_a_former_id_makes_its_tasks_env_through_the_adapter() -> None:
    former, now = next(iter(FORMER_IDS.items()))
    with pytest.warns(DeprecationWarning, match="out of date"):
        old = make_vec_env(former, n_envs=2, seed=4, monitor=False)
    new = make_vec_env(now, n_envs=2, seed=4, monitor=False)
    assert np.array_equal(old.reset(), new.reset())
    actions = np.full((2, 2), 0.5, dtype=np.float32)
    assert np.array_equal(old.step(actions)[0], new.step(actions)[0])


def test_sb3_trains_through_a_curriculum_wrapper_of_the_native_vector_env() -> None:
    from gymnasium.vector import AutoresetMode

    from mazesim.envs.curriculum import MazeSizeCurriculum, MazeSizeCurriculumWrapper

    curriculum = MazeSizeCurriculum(((3, 3), (5, 5)), promote_at=1.0, window=4)
    native = gymnasium.make_vec(
        "mazesim/UnseenMazeExplore-v0",
        4,
        autoreset_mode=AutoresetMode.SAME_STEP,
        max_episode_steps=20,
    )
    envs = MazesimVecEnv(MazeSizeCurriculumWrapper(native, curriculum))
    assert envs.get_attr("spec")[0].id == "mazesim/UnseenMazeExplore-v0"
    PPO("MlpPolicy", envs, n_steps=32, batch_size=64, seed=0, device="cpu").learn(128)
    # The steps went through the wrapper: it counted the episodes that ended (at 20 steps).
    assert curriculum.episodes[0] >= 4  # 32 steps of each of the 4 envs
    assert native.unwrapped.options.maze_size == (3, 3)


@pytest.mark.parametrize("env_id", ["mazesim/MazeFixed-v1", "mazesim/EPuckGoal-v0"])
def test_video_recorder_plays_the_adapters_videos_at_dummy_vec_envs_frame_rate(
    env_id: str, tmp_path: Any
) -> None:
    from stable_baselines3.common.vec_env import VecVideoRecorder

    def frame_rate(venv: VecEnv) -> float:
        return VecVideoRecorder(venv, str(tmp_path), lambda step: False).frames_per_sec

    fast = make_vec_env(env_id, n_envs=2, render_mode="rgb_array", monitor=False)
    reference = DummyVecEnv([lambda: gymnasium.make(env_id, render_mode="rgb_array")] * 2)
    assert frame_rate(fast) == frame_rate(reference) == 1000 / 128  # the tasks' 128 ms step
