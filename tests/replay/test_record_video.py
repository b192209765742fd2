"""``mazesim[video]`` brings what gymnasium's ``RecordVideo`` needs (moviepy): it records an
episode of a mazesim environment into an MP4 (issue 37)."""

from __future__ import annotations

from pathlib import Path

import pytest

gym = pytest.importorskip("gymnasium", reason="needs gymnasium (mazesim[video])")
pytest.importorskip("moviepy", reason="RecordVideo needs moviepy (mazesim[video])")


def test_record_video_writes_an_episode_of_a_mazesim_env(tmp_path: Path) -> None:
    from gymnasium.wrappers import RecordVideo

    import mazesim  # noqa: F401  (registers the environments)

    env = gym.make("mazesim/EPuckMaze-v0", render_mode="rgb_array")
    recorder = RecordVideo(
        env, str(tmp_path / "videos"), episode_trigger=lambda _: True, disable_logger=True
    )
    recorder.reset(seed=0)
    for _ in range(10):
        recorder.step(recorder.action_space.sample())
    recorder.close()
    (video,) = (tmp_path / "videos").glob("*.mp4")
    assert video.stat().st_size > 1000
    assert video.read_bytes()[4:8] == b"ftyp"  # an MP4 container
