"""The viewing options of the run commands: ``--html FILE``, ``--video FILE.mp4|.gif``,
``--record RUN.json`` and ``--live``.

``mazesim demo``, ``eval``, ``webots run`` and ``ros demo`` call :func:`add_viewing_options` on
their parser, record the run when :func:`recording_requested`, and hand the recorded run to
:func:`write_views`, which writes the replay page and the video and says where. Commands that step
a :class:`mazesim.Simulator` themselves use a :class:`SimulatorWatch` for both the recording and
the live view; :class:`FleetLiveView` shows every robot of a world of several.
"""

from __future__ import annotations

import argparse
import os
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, TextIO

from mazesim._core import RobotProfile, Simulator, World
from mazesim._paths import output_file, shell_command
from mazesim.errors import InvalidArgumentError
from mazesim.replay.run import RecordedRun

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

__all__ = [
    "MAX_RECORDED_SECONDS",
    "FleetLiveView",
    "SimulatorWatch",
    "add_viewing_options",
    "play_live",
    "recording_requested",
    "viewing_outputs",
    "viewing_requested",
    "write_views",
    "written_lines",
]


def add_viewing_options(parser: argparse.ArgumentParser, live: bool = False) -> None:
    """Adds ``--html``, ``--video``, ``--record`` (and ``--live`` when ``live``) to a parser."""
    from mazesim.replay.video import video_format

    def video_file(text: str) -> str:
        output_file(text)
        try:
            video_format(text)
        except ValueError as error:
            raise argparse.ArgumentTypeError(str(error)) from None
        return text

    parser.add_argument(
        "--html",
        default=None,
        type=output_file,
        metavar="FILE",
        help="also write a self-contained HTML replay of the run (opens in any browser, offline)",
    )
    parser.add_argument(
        "--video",
        default=None,
        type=video_file,
        metavar="FILE.mp4|FILE.gif",
        help="also write a video of the run (MP4 needs 'pip install mazesim[video]')",
    )
    parser.add_argument(
        "--record",
        default=None,
        type=output_file,
        metavar="RUN.json",
        help="also save the recorded run (.json, or .json.gz compressed) for 'mazesim replay'",
    )
    if live:
        parser.add_argument(
            "--live",
            action="store_true",
            help="show the run in a window as it goes, in real time (headless without a display)",
        )


def viewing_outputs(args: argparse.Namespace) -> list[tuple[str, str | None]]:
    """(option, path) of the files ``--html``, ``--video`` and ``--record`` write (None when not
    asked for), for :func:`mazesim._paths.refuse_overwriting_inputs`."""
    return [(f"--{name}", getattr(args, name, None)) for name in ("html", "video", "record")]


#: The longest run (simulated seconds) a command records for ``--html``, ``--video`` or
#: ``--record``: a recording is held in memory until the run ends (2,000 s of ``mazesim demo``
#: took 115 MB more and a 5.6 MB page), so 10,000 s is about 0.6 GB and a 28 MB page; the
#: million seconds ``--seconds`` allows would need about 58 GB.
MAX_RECORDED_SECONDS = 10_000.0


def recording_requested(args: argparse.Namespace) -> bool:
    """Whether the command must record its run (for ``--html``, ``--video`` or ``--record``).

    Raises:
        InvalidArgumentError: A recording of a run longer than :data:`MAX_RECORDED_SECONDS`
            (``--seconds``), refused before the run rather than when the memory runs out.
    """
    requested = [name for name in ("html", "video", "record") if getattr(args, name, None)]
    seconds = getattr(args, "seconds", None)
    if requested and isinstance(seconds, (int, float)) and seconds > MAX_RECORDED_SECONDS:
        options = "/".join(f"--{name}" for name in requested)
        raise InvalidArgumentError(
            f"expected --seconds of at most {MAX_RECORDED_SECONDS:g} with {options} (the "
            f"recording is held in memory, about 58 KB a simulated second), found {seconds:g}; "
            "record a shorter run, or run this one without them"
        )
    return bool(requested)


def viewing_requested(args: argparse.Namespace) -> bool:
    """Whether the command records its run or shows it live."""
    return recording_requested(args) or bool(getattr(args, "live", False))


def write_views(args: argparse.Namespace, run: RecordedRun, title: str | None = None) -> list[str]:
    """Writes the run file, the replay page and the video the command was asked for; returns
    their paths."""
    written = []
    if getattr(args, "record", None):
        from mazesim.replay.run import save_run

        save_run(run, args.record)
        written.append(os.fspath(args.record))
    if getattr(args, "html", None):
        from mazesim.replay.html import write_html

        write_html(run, args.html, title)
        written.append(os.fspath(args.html))
    if getattr(args, "video", None):
        from mazesim.replay.video import write_video

        write_video(run, args.video)
        written.append(os.fspath(args.video))
    return written


def written_lines(args: argparse.Namespace, picture: str, written: list[str]) -> str:
    """The last lines of a run command's summary: the files it wrote, and what to open next (the
    replay page when it wrote one, else the picture and how to get a replay). Every path is
    quoted as a shell needs it (:func:`mazesim._paths.shell_command`), so that one holding
    spaces pastes as one word."""
    html = getattr(args, "html", None)
    then = (
        f"open {shell_command(html)} in a browser to watch the run (offline)"
        if html
        else f"open {shell_command(picture)}; add --html run.html for a replay to watch in a "
        "browser"
    )
    files = ", ".join(shell_command(path) for path in written)
    return f"wrote              {files}\nnext               {then}\n"


def play_live(run: RecordedRun, title: str, stream: TextIO | None = None) -> None:
    """Shows the first episode of a recorded run in a live window, in real time."""
    from mazesim.render.live import LiveView
    from mazesim.replay.video import video_frames

    view = LiveView(title, run.control_step_ms / 1000.0, stream)
    if view.headless:
        return
    for frame in video_frames(run):
        view.show(frame)


class SimulatorWatch:
    """Records a :class:`mazesim.Simulator` for ``--html``/``--video`` and shows it ``--live``.

    Call :meth:`before_step` with the wheel speeds of every step before the step, and
    :meth:`finish` after the last. In a world of several robots the command drives robot 0
    and every robot is recorded and shown (the others with the wheel speeds they keep).

    Args:
        args: The command's arguments (``html``, ``video``, ``live``).
        simulator: The simulator the command steps.
        controller: What drives the robot.
        seed: The run's seed.
    """

    def __init__(
        self, args: argparse.Namespace, simulator: Simulator, controller: str, seed: int
    ) -> None:
        from mazesim.replay.recorder import FleetRecorder

        self.args = args
        self.simulator = simulator
        self.recorder: FleetRecorder | None = None
        if recording_requested(args):
            self.recorder = FleetRecorder.of_simulator(simulator, controller, seed)
        self.live: FleetLiveView | None = None
        if getattr(args, "live", False):
            self.live = FleetLiveView(
                simulator.world,
                simulator.robot,
                simulator.control_step_ms,
                f"mazesim: {simulator.world.name}",
            )
        #: The world whose walls the window draws, and what they were made of when it last
        #: took them (:meth:`follow`).
        self.world = simulator.world if self.live is not None else None
        self._walls_seen: Any = None

    def follow(self, simulation: Any) -> None:
        """Draws (and records) the walls where they are now in the run of a Webots controller
        (``simulation``, its :class:`~mazesim.webots.simulation.RobotSimulation`), when a
        supervisor has moved, imported or removed some since the window last drew them."""
        from mazesim.webots.walls_now import walls_seen

        seen = walls_seen(simulation)
        if self._walls_seen is None:
            self._walls_seen = seen
        if seen == self._walls_seen:
            return
        self._walls_seen = seen
        world = self.simulator.world
        if self.recorder is not None:
            self.recorder.follow(world)
        if self.live is None:
            return
        self.world = world
        self.live.follow(world)

    def before_step(self, left: float, right: float) -> None:
        """Records the frame before a step and the wheel speeds it runs with (robot 0's; the
        others keep theirs); shows it live."""
        simulator = self.simulator
        kept = [simulator.robot_state(i)["wheel_speeds"] for i in range(1, simulator.num_robots)]
        self.before_robots_step([(left, right), *kept])

    def before_robots_step(
        self, commands: Sequence[Sequence[float]] | npt.NDArray[np.float64]
    ) -> None:
        """Records the frame before a step and each robot's wheel speeds (left, right) in
        ``commands``, in the simulator's order; shows it live."""
        if self.recorder is not None:
            self.recorder.capture_simulator(self.simulator)
            for index, (left, right) in enumerate(commands):
                self.recorder.acted(index, float(left), float(right))
        self._show()

    def _show(self) -> None:
        if self.live is None:
            return
        states = [self.simulator.robot_state(i) for i in range(self.simulator.num_robots)]
        self.live.show(
            [state["pose"] for state in states],
            [bool(state["colliding"]) for state in states],
            f"t {self.simulator.time:6.2f} s   step {self.simulator.steps}",
        )

    def finish(self, outcome: str = "", title: str | None = None) -> list[str]:
        """Records the last frame and writes the views asked for; returns their paths."""
        self._show()
        if self.live is not None:
            self.live.close()
        if self.recorder is None:
            return []
        self.recorder.capture_simulator(self.simulator)
        return write_views(self.args, self.recorder.run(outcome), title)


class DeferredWatch:
    """A :class:`SimulatorWatch` of whichever simulator is stepped first: an observer of
    :func:`mazesim.webots.simulation.observing_steps`, for runs whose simulator is made later.

    Args:
        args: The command's arguments (``html``, ``video``, ``record``, ``live``).
        controller: What drives the robot.
        seed: The run's seed.
    """

    def __init__(self, args: argparse.Namespace, controller: str, seed: int) -> None:
        self.args = args
        self.controller = controller
        self.seed = seed
        self.watch: SimulatorWatch | None = None

    def __call__(self, simulation: Any, left: float, right: float) -> None:
        """Records the state before a step of ``simulation`` (its ``simulator``)."""
        if self.watch is None:
            self.watch = SimulatorWatch(self.args, simulation.simulator, self.controller, self.seed)
        self.watch.follow(simulation)
        self.watch.before_step(left, right)

    def finish(self, outcome: str = "", title: str | None = None) -> list[str]:
        """See :meth:`SimulatorWatch.finish`; nothing when no step was taken."""
        return [] if self.watch is None else self.watch.finish(outcome, title)


class FleetLiveView:
    """The live window of a run: robot 0 with its rays, the others (in a world of several
    robots) each in a colour of its own, every trail.

    Args:
        world: The world.
        robot: Robot 0's profile (its rays are drawn).
        control_step_ms: Simulated time between two frames (the window keeps to real time).
        title: The window's title.
    """

    def __init__(
        self, world: World, robot: RobotProfile, control_step_ms: float, title: str
    ) -> None:
        from mazesim.render.live import LiveView

        self.live = LiveView(title, control_step_ms / 1000.0)
        self._robot = robot
        #: The world whose walls the window draws.
        self.world: World | None = None
        self.renderer: Any = None
        self.trails: list[list[tuple[float, float]]] = []
        self.follow(world)

    def follow(self, world: World) -> None:
        """Draws the walls of ``world`` from now on, when it is not the world drawn (a
        supervisor moved, imported or removed walls)."""
        if world is self.world:
            return
        self.world = world
        if not self.live.headless:
            from mazesim.render.topdown import TopDownRenderer

            robot = self._robot
            self.renderer = TopDownRenderer(world, robot, ray_length=robot.distance_sensor_range)

    def show(
        self,
        poses: list[tuple[float, float, float] | None],
        colliding: list[bool],
        overlay: str,
    ) -> None:
        """Shows every robot at its pose (robot 0 first; None: a robot no longer in the world,
        not drawn, the first one still there drawn with its rays), with a line of text."""
        if self.renderer is None:
            return
        while len(self.trails) < len(poses):
            self.trails.append([])
        here = []
        for pose, touching, trail in zip(poses, colliding, self.trails):
            if pose is not None:
                trail.append((pose[0], pose[1]))
                here.append((pose, touching, trail))
        if not here:
            return
        (pose, touching, trail), others = here[0], here[1:]
        self.live.show(
            self.renderer.frame(pose, touching, trail=trail, overlay=[overlay], others=others)
        )

    def close(self) -> None:
        """Closes the window."""
        self.live.close()
