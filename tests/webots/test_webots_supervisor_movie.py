"""A supervisor's movie: ``movieStartRecording`` to ``movieStopRecording`` writes an MP4 of the
top-down view, one frame a step, with Webots' ready and failed states and its refusals (#32)."""

from __future__ import annotations

from pathlib import Path

import pytest

from mazesim.webots import controller
from mazesim.webots.view_export import VIEW_SIZE
from supervised_world import WORLD, drive, supervisor_in

pytestmark = pytest.mark.usefixtures("fresh_robot")
imageio = pytest.importorskip("imageio.v2")
pytest.importorskip("imageio_ffmpeg")


def movie_of(path: Path) -> tuple[int, tuple[int, int], float]:
    """An MP4's number of frames, size and frames per second (its reader closed)."""
    reader = imageio.get_reader(path, format="FFMPEG")
    try:
        meta = reader.get_meta_data()
        return int(reader.count_frames()), tuple(meta["size"]), float(meta["fps"])
    finally:
        reader.close()


def test_a_movie_holds_a_frame_a_step_and_is_ready_once_written(tmp_path: Path) -> None:
    supervisor = supervisor_in(tmp_path, WORLD)
    movie = tmp_path / "run.mp4"
    assert supervisor.movieIsReady() and not supervisor.movieFailed()
    supervisor.movieStartRecording(str(movie), 1280, 720, 0, 90, 1, False)
    assert not supervisor.movieIsReady(), "recording: not ready until stopped"
    drive(supervisor, 3.0, 20)
    assert not movie.exists(), "the file appears whole, when the movie stops"
    supervisor.movieStopRecording()
    assert supervisor.movieIsReady() and not supervisor.movieFailed()
    # The first frame at the start, then one a 32 ms step (the world's basic step), played at
    # the simulation's pace.
    assert movie_of(movie) == (21, (VIEW_SIZE, VIEW_SIZE), pytest.approx(1000 / 32, abs=0.01))


def test_a_faster_movie_keeps_every_few_steps(tmp_path: Path) -> None:
    supervisor = supervisor_in(tmp_path, WORLD)
    movie = tmp_path / "fast.mp4"
    # 31.25 steps a second, played 4 times as fast: 125 frames a second, so every third step.
    supervisor.movieStartRecording(str(movie), 640, 480, 0, 50, 4, True)
    drive(supervisor, 3.0, 30)
    supervisor.movieStopRecording()
    frames, _, fps = movie_of(movie)
    assert frames == 11 and fps == pytest.approx(125 / 3, abs=0.01)


@pytest.mark.parametrize(
    ("arguments", "said"),
    [
        (("", 640, 480, 0, 50, 1, False), "called with NULL or empty 'filename' argument"),
        (("m.mp4", 0, 480, 0, 50, 1, False), "'width' and 'height' arguments must be postitive"),
        (("m.mp4", 640, 480, 0, 0, 1, False), "'quality' argument (0) must be between 1 and 100"),
        (("m.mp4", 640, 480, 0, 50, 0, False), "'acceleration' argument must be greater than"),
    ],
)
def test_arguments_out_of_range_are_refused_and_nothing_recorded(
    tmp_path: Path, capfd: pytest.CaptureFixture[str], arguments: tuple, said: str
) -> None:
    supervisor = supervisor_in(tmp_path, WORLD)
    supervisor.step(32)
    capfd.readouterr()
    supervisor.movieStartRecording(*arguments)
    err = capfd.readouterr().err
    assert "Error: wb_supervisor_movie_start_recording()" in err and said in err
    assert supervisor.movieIsReady()
    supervisor.movieStopRecording()
    assert not list(tmp_path.glob("*.mp4"))


def test_a_second_start_is_refused_while_recording(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    supervisor = supervisor_in(tmp_path, WORLD)
    supervisor.movieStartRecording(str(tmp_path / "a.mp4"), 640, 480, 0, 50, 1, False)
    capfd.readouterr()
    supervisor.movieStartRecording(str(tmp_path / "b.mp4"), 640, 480, 0, 50, 1, False)
    assert "movie recording has already been started" in capfd.readouterr().err
    supervisor.step(32)
    supervisor.movieStopRecording()
    assert (tmp_path / "a.mp4").is_file() and not (tmp_path / "b.mp4").exists()


def test_the_movie_functions_are_the_supervisors() -> None:
    for name in ("movieStartRecording", "movieStopRecording", "movieIsReady", "movieFailed"):
        assert callable(getattr(controller.Supervisor, name))
