"""``mazesim replay RUN -o FILE``: a recorded run as an HTML replay or a video.

The output's suffix says what to write: ``.html`` the replay page, ``.mp4`` or ``.gif`` a video of
one episode (``--episode``).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any, TextIO

from mazesim._paths import output_file, refuse_overwriting_inputs
from mazesim.cli._help import examples
from mazesim.cli.progress import add_progress_option, progress_display
from mazesim.errors import InvalidArgumentError, _shown

__all__ = ["run_replay"]


def register(commands: Any) -> None:
    """Adds ``replay`` to the ``mazesim`` command's subparsers."""
    replay = commands.add_parser(
        "replay",
        help="turn a recorded run into an HTML replay or a video",
        description=(
            "Turn a recorded run (a .json or .json.gz run file, see docs/watching.md) into a "
            "self-contained HTML replay (-o FILE.html) or a video of one episode "
            "(-o FILE.mp4 or FILE.gif)."
        ),
        epilog=examples(
            "mazesim replay run.json.gz -o replay.html",
            "mazesim replay run.json.gz -o episode2.mp4 --episode 2",
            "mazesim replay run.json.gz -o run.gif",
        ),
    )
    replay.add_argument("run_file", metavar="RUN", help="the recorded run (.json or .json.gz)")
    replay.add_argument(
        "-o",
        "--out",
        required=True,
        type=output_file,
        metavar="FILE",
        help="the page or video to write: FILE.html, FILE.mp4 or FILE.gif",
    )
    replay.add_argument(
        "--episode",
        type=int,
        default=0,
        metavar="K",
        help="the episode a video shows, counted from 0 (default: %(default)s)",
    )
    add_progress_option(replay)
    replay.set_defaults(run=lambda args: run_replay(args, sys.stdout))


def run_replay(args: argparse.Namespace, out: TextIO) -> int:
    """Runs ``mazesim replay``."""
    from mazesim.replay.run import load_run

    suffix = Path(args.out).suffix.lower()
    if suffix not in (".html", ".htm", ".mp4", ".gif"):
        raise InvalidArgumentError(
            f"expected -o FILE.html, FILE.mp4 or FILE.gif, found {_shown(args.out)}"
        )
    refuse_overwriting_inputs([("-o", args.out)], [("the run", args.run_file)])
    run = load_run(args.run_file)
    # Checked whatever the output: an HTML replay shows every episode, but an episode the run
    # does not have is a mistake to say, not to pass over.
    if not run.episodes:
        raise InvalidArgumentError(
            f"{args.run_file}: expected a run of at least one episode, found none (nothing to "
            "replay)"
        )
    if not 0 <= args.episode < len(run.episodes):
        raise InvalidArgumentError(
            f"--episode {args.episode}: expected an episode of {args.run_file} from 0 to "
            f"{len(run.episodes) - 1}"
        )
    if suffix in (".html", ".htm"):
        from mazesim.replay.html import write_html

        write_html(run, args.out)
        frames = sum(episode.frames for episode in run.episodes)
        episodes = len(run.episodes)
        noun = "episode" if episodes == 1 else "episodes"
        out.write(f"wrote {args.out} ({episodes} {noun}, {frames} frames)\n")
        return 0
    from mazesim.replay.video import write_video

    with progress_display(args, unit="frames") as display:
        count = write_video(
            run,
            args.out,
            episode=args.episode,
            progress=lambda done, total: display("video", done, total),
        )
    out.write(f"wrote {args.out} ({count} frames of episode {args.episode})\n")
    return 0
