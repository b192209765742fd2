"""Every registered task says the frame rate of its control step in ``metadata["render_fps"]``,
whichever way it is made (``gymnasium.make``, the native vector env, ``SyncVectorEnv``), so that
``RecordVideo`` plays an episode at the speed it ran."""

from __future__ import annotations

from pathlib import Path

import pytest

gymnasium = pytest.importorskip("gymnasium")

import mazesim  # noqa: E402, F401  registers the tasks
from mazesim.envs.tasks import FORMER_IDS, task_ids  # noqa: E402

#: Every id mazesim registers, the goal-conditioned tasks' and the former ones included.
REGISTERED_IDS = [*task_ids(), *FORMER_IDS]


def control_step_fps(env_id: str, **options: float) -> float:
    """Frames per second of one frame a control step: the option, else the task's, else the
    built-in worlds' basic step of 32 ms."""
    step = options.get("control_step_ms", gymnasium.spec(env_id).kwargs.get("control_step_ms"))
    return 1000.0 / (32.0 if step is None else step)


@pytest.mark.parametrize("env_id", REGISTERED_IDS)
def test_render_fps_is_the_control_steps_rate_however_the_env_is_made(
    env_id: str, tmp_path: Path
) -> None:
    fps = control_step_fps(env_id)
    with gymnasium.make(env_id, render_mode="rgb_array") as env:
        assert env.metadata["render_fps"] == env.unwrapped.metadata["render_fps"] == fps
        recorder = gymnasium.wrappers.RecordVideo(env, str(tmp_path / "videos"))
        assert recorder.frames_per_sec == fps
    for mode in ("vector_entry_point", "sync"):
        envs = gymnasium.make_vec(env_id, num_envs=2, vectorization_mode=mode)
        assert envs.metadata["render_fps"] == fps, mode
        envs.close()


@pytest.mark.parametrize("env_id", ["mazesim/EPuckMaze-v0", "mazesim/EPuckGoal-v0"])
def test_render_fps_follows_a_control_step_given_at_make(env_id: str) -> None:
    fps = control_step_fps(env_id, control_step_ms=64.0)
    assert fps == 15.625
    with gymnasium.make(env_id, control_step_ms=64.0) as env:
        assert env.metadata["render_fps"] == fps
    envs = gymnasium.make_vec(env_id, num_envs=2, control_step_ms=64.0)
    assert envs.metadata["render_fps"] == fps
    envs.close()
