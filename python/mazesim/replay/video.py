"""Videos of recorded runs: MP4 (imageio with the ffmpeg of the ``imageio-ffmpeg`` wheel) or GIF.

Each frame is the top-down picture of :class:`mazesim.render.topdown.TopDownRenderer` with the
robot's trail, its sensor rays, and an overlay of the time, the step, the action, the running
sub-task and the last barcode event or decision; the walls as they stand at each frame (a Webots
supervisor may move, import or remove them while a run runs). A video plays in real time: one
frame per control step, or one every few steps when the control step is shorter than a frame
should be (GIFs are kept to 12.5 frames per second, so a long run stays a reasonable file; MP4
goes up to 60); :func:`video_frame_steps` says which steps become frames.
"""

from __future__ import annotations

import math
import os
import shutil
import tempfile
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import IO

import numpy as np
import numpy.typing as npt

from mazesim._atomic import atomic_file
from mazesim.errors import InvalidArgumentError, MissingDependencyError, _shown
from mazesim.render.topdown import TopDownRenderer
from mazesim.replay.run import RecordedEpisode, RecordedRun

__all__ = ["VIDEO_FORMATS", "frame_overlay", "video_frame_steps", "video_frames", "write_video"]

#: Video file suffixes and the most frames per second each is written with.
VIDEO_FORMATS = {".mp4": 60.0, ".gif": 12.5}


def video_format(path: str | os.PathLike[str]) -> str:
    """The suffix of a video file name (``.mp4`` or ``.gif``).

    Raises:
        InvalidArgumentError: Another suffix.
    """
    suffix = Path(path).suffix.lower()
    if suffix not in VIDEO_FORMATS:
        raise InvalidArgumentError(
            f"expected a video file ending in {' or '.join(VIDEO_FORMATS)}, "
            f"found {_shown(os.fspath(path))}"
        )
    return suffix


def video_frame_steps(run: RecordedRun, episode: RecordedEpisode, suffix: str) -> range:
    """The frames of an episode that a video of format ``suffix`` shows."""
    step_fps = 1000.0 / run.control_step_ms
    stride = max(1, math.ceil(step_fps / VIDEO_FORMATS[suffix] - 1e-9))
    return range(0, episode.frames, stride)


def frame_overlay(run: RecordedRun, episode: RecordedEpisode, frame: int) -> list[str]:
    """The text lines shown on a frame: time and step, action and sub-task, the last event."""
    lines = [
        f"t {frame * run.control_step_ms / 1000.0:6.2f} s   step {frame} / {episode.frames - 1}",
    ]
    doing = []
    if episode.actions is not None and episode.actions[frame]:
        doing.append(f"action {episode.actions[frame]}")
    elif episode.wheel_speeds is not None:
        left, right = episode.wheel_speeds[frame]
        doing.append(f"wheels {left:+.2f} {right:+.2f} rad/s")
    if episode.subtasks is not None and episode.subtasks[frame] >= 0 and run.subtask_names:
        doing.append(run.subtask_names[int(episode.subtasks[frame])])
    if doing:
        lines.append("   ".join(doing))
    seen = np.flatnonzero(episode.events[: frame + 1])
    if seen.size:
        event = int(episode.events[seen[-1]])
        direction = "arrival" if event > 0 else "departure"
        lines.append(f"barcode: checkpoint {abs(event)} ({direction}) at step {int(seen[-1])}")
    made = [d for d in episode.decisions if d.frame <= frame]
    if made and run.subtask_names:
        last = made[-1]
        lines.append(f"D{last.number}: {run.subtask_names[last.chosen]}")
    if frame == episode.frames - 1 and episode.outcome:
        lines.append(episode.outcome)
    return lines


def video_frames(
    run: RecordedRun, episode: int = 0, size: int = 400, steps: range | None = None
) -> Iterator[npt.NDArray[np.uint8]]:
    """The (size, size, 3) uint8 frames of an episode (every frame, or those of ``steps``)."""
    recorded = run.episode(episode)
    profile = run.robot_profile
    renderer = TopDownRenderer(run.world, profile, (size, size), profile.distance_sensor_range)
    drawn = None  # the walls drawn: the world's, or those of a change while the run ran
    for frame in steps if steps is not None else range(recorded.frames):
        walls = recorded.walls_at(frame)
        if walls is not drawn:
            drawn = walls
            renderer = TopDownRenderer(
                run.world, profile, (size, size), profile.distance_sensor_range, walls=walls
            )
        x, y, yaw = recorded.poses[frame]
        yield renderer.frame(
            (float(x), float(y), float(yaw)),
            bool(recorded.colliding[frame]),
            trail=recorded.poses[: frame + 1, :2],
            overlay=frame_overlay(run, recorded, frame),
            others=[
                (
                    (
                        float(track.poses[frame, 0]),
                        float(track.poses[frame, 1]),
                        float(track.poses[frame, 2]),
                    ),
                    bool(track.colliding[frame]),
                    track.poses[: frame + 1, :2],
                )
                for track in recorded.robots
            ],
        )


def write_video(
    run: RecordedRun,
    path: str | os.PathLike[str],
    episode: int = 0,
    size: int = 400,
    progress: Callable[[int, int], None] | None = None,
) -> int:
    """Writes a video of one episode of a run; the format follows the suffix.

    The file appears only when complete (written beside it, then renamed).

    Args:
        run: The recorded run.
        path: The video file, ``.mp4`` or ``.gif``.
        episode: The episode shown, counted from 0.
        size: Width and height of the frames in pixels, a multiple of 16.
        progress: Called as ``progress(done, total)`` after each frame drawn.

    Returns:
        The number of frames written.

    Raises:
        InvalidArgumentError: Not ``.mp4`` or ``.gif``, or no such episode.
        MissingDependencyError: MP4 without imageio and imageio-ffmpeg.
    """
    suffix = video_format(path)
    if size % 16:
        raise InvalidArgumentError(f"expected a frame size that is a multiple of 16, found {size}")
    steps = video_frame_steps(run, run.episode(episode), suffix)
    fps = 1000.0 / (run.control_step_ms * steps.step)
    frames = video_frames(run, episode, size, steps)
    if progress is not None:
        frames = _counted(frames, len(steps), progress)
    # Written to a temporary file of this process alone, then switched in whole: two commands
    # writing one video, or one stopped midway, never leave a mixed or partial file.
    with atomic_file(path) as handle:
        if suffix == ".gif":
            return _write_gif(frames, handle, fps)
        # ffmpeg names its container from the file name: it writes a file of its own, in a
        # private folder (never beside a device or FIFO the user named), copied in.
        with tempfile.TemporaryDirectory(prefix="mazesim-video-") as folder:
            encoded = Path(folder) / f"video{suffix}"
            count = _write_mp4(frames, encoded, fps)
            with open(encoded, "rb") as video:
                shutil.copyfileobj(video, handle)
        return count


def _counted(
    frames: Iterator[npt.NDArray[np.uint8]], total: int, progress: Callable[[int, int], None]
) -> Iterator[npt.NDArray[np.uint8]]:
    """The frames, calling ``progress(done, total)`` after each."""
    for done, frame in enumerate(frames, start=1):
        yield frame
        progress(done, total)


def _write_gif(frames: Iterator[npt.NDArray[np.uint8]], path: IO[bytes], fps: float) -> int:
    from PIL import Image

    # Each frame keeps its own 64-colour palette: a fraction of the memory of RGB frames.
    pictures = [Image.fromarray(frame).quantize(colors=64) for frame in frames]
    if not pictures:
        raise InvalidArgumentError("expected at least one frame to write")
    duration = int(round(1000.0 / fps))
    pictures[0].save(
        path, format="GIF", save_all=True, append_images=pictures[1:], duration=duration, loop=0
    )
    return len(pictures)


def _write_mp4(frames: Iterator[npt.NDArray[np.uint8]], path: Path, fps: float) -> int:
    try:
        import imageio.v2 as imageio
        import imageio_ffmpeg  # noqa: F401
    except ImportError as error:
        raise MissingDependencyError(
            f"writing MP4 videos needs imageio and imageio-ffmpeg ({error}); "
            "install them with: pip install 'mazesim[video]'"
        ) from None
    count = 0
    writer = imageio.get_writer(
        os.fspath(path),
        format="FFMPEG",
        mode="I",
        fps=fps,
        codec="libx264",
        quality=7,
        macro_block_size=16,
    )
    try:
        for frame in frames:
            writer.append_data(frame)
            count += 1
    finally:
        writer.close()
    return count
