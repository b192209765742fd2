"""The keywords an RL user brings from gymnasium and SB3: ``vector_kwargs``, every
``AutoresetMode``, a JSON-able ``env.spec`` with a ``World``, each task's ``reward_threshold``,
robot profiles that compare by value."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

from gymnasium.error import ResetNeeded  # noqa: E402
from gymnasium.vector import AutoresetMode  # noqa: E402

import mazesim  # noqa: E402
from mazesim.envs import ENV_ID, TASKS, EPuckMazeVectorEnv  # noqa: E402
from mazesim.envs.tasks import REWARD_THRESHOLD  # noqa: E402
from mazesim.errors import InvalidArgumentError  # noqa: E402

SHORT = {"world": "random", "max_episode_steps": 5, "noise": False}


def test_vector_kwargs_set_the_vector_envs_own_keywords() -> None:
    envs = EPuckMazeVectorEnv(
        2, vector_kwargs={"autoreset_mode": AutoresetMode.SAME_STEP, "threads": 1}, **SHORT
    )
    assert envs.autoreset_mode == AutoresetMode.SAME_STEP
    assert envs.metadata["autoreset_mode"] == AutoresetMode.SAME_STEP
    with pytest.raises(InvalidArgumentError, match="vector_kwargs.*found unknown world"):
        EPuckMazeVectorEnv(2, vector_kwargs={"world": "random"})
    with pytest.raises(InvalidArgumentError, match="vector_kwargs to be a dict"):
        EPuckMazeVectorEnv(2, vector_kwargs=[("threads", 1)])


def test_disabled_autoreset_waits_for_a_masked_reset() -> None:
    envs = EPuckMazeVectorEnv(3, autoreset_mode="Disabled", **SHORT)
    reference = EPuckMazeVectorEnv(3, autoreset_mode=AutoresetMode.NEXT_STEP, **SHORT)
    first = envs.reset(seed=4)[0]
    assert np.array_equal(first, reference.reset(seed=4)[0])
    actions = np.zeros((3, 2), dtype=np.float32)
    for _ in range(5):
        observations, _, terminated, truncated, _ = envs.step(actions)
        assert np.array_equal(observations, reference.step(actions)[0])
    ended = terminated | truncated
    assert ended.all()
    with pytest.raises(ResetNeeded, match=r"environments \[0, 1, 2\] not reset"):
        envs.step(actions)
    mask = np.array([True, False, True])
    envs.reset(options={"reset_mask": mask})
    with pytest.raises(ResetNeeded, match=r"environments \[1\] not reset"):
        envs.step(actions)
    envs.reset(options={"reset_mask": ~mask})
    _, rewards, terminated, truncated, _ = envs.step(actions)
    assert not (terminated | truncated).any() and np.isfinite(rewards).all()


def test_sync_mode_takes_the_autoreset_mode_in_vector_kwargs() -> None:
    envs = gymnasium.make_vec(
        ENV_ID, 2, vectorization_mode="sync", vector_kwargs={"autoreset_mode": "SameStep"}
    )
    assert envs.metadata["autoreset_mode"] == AutoresetMode.SAME_STEP
    with pytest.raises(InvalidArgumentError, match="vector_kwargs"):
        gymnasium.make_vec(ENV_ID, 2, vectorization_mode="sync", autoreset_mode="SameStep")


def test_a_spec_with_a_world_object_goes_to_json_and_back() -> None:
    world = mazesim.generate_maze(4, 4, seed=3)
    envs = gymnasium.make_vec(ENV_ID, 2, world=world).unwrapped
    assert envs.spec is not None and envs.spec.to_json()
    for env, spec in (
        (gymnasium.make(ENV_ID, world=world), None),
        (envs, envs.single_env_spec),
    ):
        spec = spec or env.spec
        assert spec is not None
        restored = gymnasium.envs.registration.EnvSpec.from_json(spec.to_json())
        assert restored.kwargs["world"] == {"toml": world.to_toml(), "source": world.name}
        again = gymnasium.make(restored)
        assert again.unwrapped.options.world == world
        assert pickle.loads(pickle.dumps(env)).spec == env.spec


@pytest.mark.parametrize("task", TASKS, ids=lambda task: task.env_id)
def test_every_task_sets_the_documented_reward_threshold(task) -> None:  # type: ignore[no-untyped-def]
    assert gymnasium.spec(task.env_id).reward_threshold == REWARD_THRESHOLD
    assert REWARD_THRESHOLD == mazesim.envs.RewardWeights().goal


def test_robot_profiles_compare_by_value() -> None:
    toml = mazesim.RobotProfile.builtin("e-puck").to_toml()
    again = mazesim.RobotProfile.from_toml(toml)
    assert again == mazesim.RobotProfile.builtin("e-puck")
    assert hash(again) == hash(mazesim.RobotProfile.builtin("e-puck"))
    assert again != again.perturbed(drive=mazesim.DrivePerturbation(wheel_radius_scale=1.1))
    assert again != "e-puck"
