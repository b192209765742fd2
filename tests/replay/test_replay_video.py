"""Videos of recorded runs, and the overlays and live window of the gym env's render()."""

from __future__ import annotations

import io
from pathlib import Path

import gymnasium
import matplotlib
import numpy as np
import pytest

from mazesim.cli import main
from mazesim.errors import MOST_MESSAGE, InvalidArgumentError
from mazesim.render.live import LiveView, display_problem
from mazesim.render.topdown import START_RGB, TRAIL_RGB
from mazesim.replay import load_run
from mazesim.replay.video import video_frame_steps, write_video

imageio = pytest.importorskip("imageio.v3", reason="videos need imageio (mazesim[video])")


def test_the_demo_gif_has_a_frame_per_shown_step(navigator_demo: dict[str, Path]) -> None:
    run = load_run(navigator_demo["run"])
    episode = run.episodes[0]
    steps = video_frame_steps(run, episode, ".gif")
    assert steps.step == 2  # 64 ms steps, at most 12.5 frames per second
    frames = list(imageio.imiter(navigator_demo["gif"]))
    assert len(frames) == len(steps) == (episode.frames + 1) // 2
    assert frames[0].shape[:2] == (400, 400)
    assert not np.array_equal(frames[0], frames[-1])


def test_an_mp4_decodes_to_one_frame_per_step(
    navigator_demo: dict[str, Path], tmp_path: Path
) -> None:
    pytest.importorskip("imageio_ffmpeg", reason="MP4 needs imageio-ffmpeg (mazesim[video])")
    import imageio.v2 as imageio2

    run = load_run(navigator_demo["run"])
    run.episodes[0] = _first_frames(run.episodes[0], 90)
    path = tmp_path / "run.mp4"
    assert write_video(run, path) == 90
    reader = imageio2.get_reader(path, format="FFMPEG")
    try:
        assert reader.count_frames() == 90
        assert reader.get_meta_data()["fps"] == pytest.approx(1000 / 64, abs=0.01)
    finally:
        reader.close()
    assert [p.name for p in tmp_path.iterdir()] == ["run.mp4"]


@pytest.mark.parametrize("suffix", [".mp4", ".gif"])
def test_two_writers_of_one_video_each_write_a_whole_one(
    navigator_demo: dict[str, Path], tmp_path: Path, suffix: str
) -> None:
    """A second write of the same video starting while the first runs (a second command) leaves
    a whole video, the last finished, and no temporary files; one stopped midway leaves the
    video as it was."""
    if suffix == ".mp4":
        pytest.importorskip("imageio_ffmpeg", reason="MP4 needs imageio-ffmpeg (mazesim[video])")
    run = load_run(navigator_demo["run"])
    long, short = _first_frames(run.episodes[0], 60), _first_frames(run.episodes[0], 20)
    path = tmp_path / f"video{suffix}"
    other = load_run(navigator_demo["run"])
    other.episodes[0] = short
    run.episodes[0] = long

    def second_write(done: int, total: int) -> None:
        if done == 5:
            write_video(other, path)

    assert write_video(run, path, progress=second_write) == len(
        video_frame_steps(run, long, suffix)
    )
    assert _frame_count(path) == len(video_frame_steps(run, long, suffix))
    assert [p.name for p in tmp_path.iterdir()] == [path.name]

    def stop(done: int, total: int) -> None:
        if done == 5:
            raise KeyboardInterrupt

    before = path.read_bytes()
    with pytest.raises(KeyboardInterrupt):
        write_video(other, path, progress=stop)
    assert path.read_bytes() == before
    assert [p.name for p in tmp_path.iterdir()] == [path.name]


def _frame_count(path: Path) -> int:
    """The frames of a GIF or MP4 file, its reader closed."""
    if path.suffix == ".gif":
        return len(list(imageio.imiter(path)))
    import imageio.v2 as imageio2

    reader = imageio2.get_reader(path, format="FFMPEG")
    try:
        return int(reader.count_frames())
    finally:
        reader.close()


def _first_frames(episode, count):  # type: ignore[no-untyped-def]
    from dataclasses import replace

    def cut(values):  # type: ignore[no-untyped-def]
        return None if values is None else values[:count]

    return replace(
        episode,
        poses=episode.poses[:count],
        readings=episode.readings[:count],
        rays=episode.rays[:count],
        colliding=episode.colliding[:count],
        events=episode.events[:count],
        actions=cut(episode.actions),
        subtasks=cut(episode.subtasks),
        levels=cut(episode.levels),
        decisions=[d for d in episode.decisions if d.frame < count],
    )


def test_replay_command_writes_a_video(
    navigator_demo: dict[str, Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = tmp_path / "again.gif"
    assert main(["replay", str(navigator_demo["run"]), "-o", str(path)]) == 0
    count = len(list(imageio.imiter(path)))
    assert f"wrote {path} ({count} frames of episode 0)" in capsys.readouterr().out
    with pytest.raises(InvalidArgumentError, match=r"ending in \.mp4 or \.gif"):
        write_video(load_run(navigator_demo["run"]), tmp_path / "x.avi")


def test_a_bad_video_name_is_a_usage_error(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["demo", "--video", "run.avi"]) == 2
    assert "expected a video file ending in .mp4 or .gif" in capsys.readouterr().err


def test_render_shows_start_trail_and_an_overlay() -> None:
    env = gymnasium.make("mazesim/EPuckMaze-v0", render_mode="rgb_array")
    env.reset(seed=0)
    first = env.render()
    renderer = env.unwrapped._renderer
    sx, sy, _ = env.unwrapped.world.start
    column = int(renderer._x0 + (sx - 0.9 * 0.037) * renderer.scale)
    row = int(renderer._y0 - sy * renderer.scale)
    ring = first[row - 2 : row + 3, column - 2 : column + 3].reshape(-1, 3)
    assert any(tuple(pixel) == START_RGB for pixel in ring)
    for _ in range(40):
        env.step(np.array([1.0, 1.0], dtype=np.float32))
    later = env.render()
    assert not env.unwrapped._simulator.colliding  # the body is blue, so red pixels are the trail
    # The trail is drawn from the start to where the robot is now.
    assert np.any(np.all(later == np.array(TRAIL_RGB, dtype=np.uint8), axis=-1))
    # The overlay (dark box, white text) at the top left changes with the step number.
    assert not np.array_equal(first[:40, :160], later[:40, :160])
    env.close()


def test_a_long_headless_notice_is_said_shortened() -> None:
    # A notice of 100,000 characters was written whole (found by the surface walk, seed
    # 20261214); it is said shortened as every message quoting a value is.
    matplotlib.use("Agg")
    stream = io.StringIO()
    view = LiveView(stream=stream, headless_notice="no window: {problem}; " + "x" * 100_000)
    assert view.headless
    said = stream.getvalue()
    assert said.startswith("no window: ") and "characters ...]" in said
    assert len(said) <= MOST_MESSAGE + 100  # with the note of what was left out


def test_human_mode_carries_on_headless_with_agg(capsys: pytest.CaptureFixture[str]) -> None:
    matplotlib.use("Agg")
    assert display_problem() is not None
    env = gymnasium.make("mazesim/EPuckMaze-v0", render_mode="human")
    env.reset(seed=0)
    for _ in range(5):
        env.step(np.array([1.0, 0.5], dtype=np.float32))
    view = env.unwrapped._live
    assert isinstance(view, LiveView) and view.headless
    assert view.frames_shown == 6  # reset and every step, each as it happened
    assert env.render() is None
    env.close()
    said = capsys.readouterr().err
    assert said.count('render_mode="human" shows no window here') == 1
    assert 'render_mode="rgb_array" returns them' in said and "live view off" not in said


def test_check_env_says_why_its_human_mode_env_shows_nothing(
    capsys: pytest.CaptureFixture[str],
) -> None:
    # check_env makes an env of every declared render mode; its "human" one printed the
    # commands' "live view off ... carrying on headless", which a newcomer who asked for no
    # window could not place.
    from gymnasium.utils.env_checker import check_env

    matplotlib.use("Agg")
    env = gymnasium.make("mazesim/MazeFixed-v1")
    check_env(env.unwrapped)
    env.close()
    said = capsys.readouterr().err
    assert "live view off" not in said
    assert 'render_mode="human"' in said and "check_env" in said


def test_demo_live_carries_on_headless(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    matplotlib.use("Agg")
    assert main(["demo", "--seconds", "2", "--out", str(tmp_path), "--live"]) == 0
    captured = capsys.readouterr()
    assert "live view off" in captured.err
    assert f"wrote              {tmp_path / 'trajectory.png'}" in captured.out
