"""Watching runs: the recorded-run format, the HTML replay, videos, world previews (the pictures
and the live window are :mod:`mazesim.render`'s).

- :mod:`mazesim.replay.run`: :class:`RecordedRun`, the versioned run format, :func:`save_run` and
  :func:`load_run`;
- :mod:`mazesim.replay.recorder` and :mod:`mazesim.replay.navigator`: recording a simulator or
  the navigator's episodes;
- :mod:`mazesim.replay.html`: the self-contained HTML replay (:func:`write_html`);
- :mod:`mazesim.replay.video`: MP4 and GIF videos (:func:`write_video`);
- :mod:`mazesim.replay.preview`: a labelled picture of a world (``mazesim show``);
- :mod:`mazesim.replay.views`: the ``--html``, ``--video`` and ``--live`` options of the run
  commands.
"""

from __future__ import annotations

from mazesim.replay.run import (
    FORMAT_VERSION,
    Decision,
    RecordedEpisode,
    RecordedRun,
    RunRobot,
    load_run,
    save_run,
)

__all__ = [
    "FORMAT_VERSION",
    "Decision",
    "RecordedEpisode",
    "RecordedRun",
    "RunRobot",
    "load_run",
    "save_run",
]
