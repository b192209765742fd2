"""The native vector env's frames are the single env's: the trail since the reset and the
overlay (time, step, reward, return, last event), drawn by the same code
(:class:`mazesim.render.episode.EpisodeTrace`)."""

from __future__ import annotations

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

import mazesim  # noqa: E402, F401
from mazesim.envs import ENV_ID  # noqa: E402


@pytest.mark.parametrize("env_id", [ENV_ID, "mazesim/UnseenMaze-v2"])
def test_a_vector_frame_equals_the_single_env_frame(env_id: str) -> None:
    single = gymnasium.make(env_id, render_mode="rgb_array")
    vector = gymnasium.make_vec(env_id, num_envs=2, render_mode="rgb_array")
    single.reset(seed=5)
    vector.reset(seed=5)  # env 0 is seeded 5, as SyncVectorEnv seeds it
    assert np.array_equal(vector.render()[0], single.render())
    rng = np.random.default_rng(0)
    for _ in range(60):
        action = rng.uniform(-0.2, 1.0, size=2).astype(np.float32)
        single.step(action)
        vector.step(np.stack([action, action]))
    frames = vector.render()
    assert np.array_equal(frames[0], single.render())
    first = vector.reset(seed=5)  # a new episode: the trail starts again
    assert first is not None and not np.array_equal(vector.render()[0], frames[0])
    single.close()
    vector.close()
