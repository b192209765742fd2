"""``mazesim train``: training the hierarchical navigator.

``mazesim train`` trains from scratch (or, with ``--resume``, continues a stopped run) and saves
the navigator into ``--out``; ``--flat`` trains the flat baseline instead, for the same budget.
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any, TextIO

from mazesim._paths import (
    output_files,
    refuse_overwriting_inputs,
    shell_command,
    writing_alone,
)
from mazesim.cli._args import (
    add_out_folder,
    add_setting_options,
    seed_argument,
)
from mazesim.cli._help import examples
from mazesim.cli.progress import add_progress_option, progress_display
from mazesim.errors import InvalidArgumentError

if TYPE_CHECKING:
    from mazesim.batch import RobotChoice
    from mazesim.learn.train import RobotDraw, TrainSettings

__all__ = ["run_train"]

DEFAULT_OUT = "mazesim-policy"
#: What each training stage counts.
_UNITS = {"lower": "rounds", "higher": "episodes", "flat": "steps"}


def register(commands: Any) -> None:
    """Adds ``train`` to the ``mazesim`` command's subparsers."""
    from mazesim.learn.train import TrainSettings

    defaults = TrainSettings()
    train = commands.add_parser(
        "train",
        help="train the hierarchical navigator (lower level on generated mazes, higher level on "
        "the world)",
        description=(
            "Train the hierarchical Q-learning navigator from scratch: the four sub-tasks on "
            "generated mazes with many robots at once, then the higher level on --world. "
            "Checkpoints are written to --out as it goes; --resume continues a stopped run to the "
            "same tables as an uninterrupted one. The navigator is saved as "
            "--out/tables.npz and --out/policy.json (which keeps the path of a --world file, so "
            "'mazesim eval --policy DIR' finds it again). Progress shows on stderr with the time "
            "left (ETA). A world the navigator cannot learn (no goal, a goal out of reach, no "
            "barcode checkpoints) is refused before training, with what to change."
        ),
        epilog=examples(
            "mazesim train --out my-policy",
            "mazesim train --world my-maze.toml --out my-navigator --steps 4M",
            "mazesim train --out my-policy --resume",
            "mazesim train --flat --out flat-policy",
            notes="A full run of the defaults takes about a minute on 2 cores; --steps sets the "
            "lower level's budget (the shipped navigator: 36M).",
        ),
    )
    # --envs and --steps take their fields' declared ranges.
    add_setting_options(train, defaults, {"seed": seed_argument})
    add_out_folder(train, DEFAULT_OUT, "the checkpoint and the navigator")
    train.add_argument(
        "--resume",
        action="store_true",
        help="continue the run whose checkpoint is in --out (same settings)",
    )
    train.add_argument(
        "--flat",
        action="store_true",
        help="train the flat Q-learning baseline on --world instead, for --steps env-steps",
    )
    train.add_argument(
        "--randomise",
        metavar="SPEC",
        help="domain randomisation: each lower-level round's robots (and the higher level's) "
        "are the seed robot, or a base profile drawn from robot=name|name, perturbed at random "
        "within these ranges, inline (robot=seed|e-puck,wheel_radius=0.95:1.05,ir_angle=-10:10) "
        "or a TOML file with a [randomise] table; see the transfer study's page",
    )
    train.add_argument(
        "--door-distance",
        action="store_true",
        help="the door sub-tasks' phases also count the distance driven since the checkpoint "
        "(18 phases), so a robot that cannot see a door from the corridor's middle (an e-puck's "
        "own sensors, dark walls) can learn where it is",
    )
    train.add_argument(
        "--blind-forward",
        action="store_true",
        help="'Corridors and Corners' drives forward where no sensor sees a wall, in training "
        "and after",
    )
    train.add_argument(
        "--hold-heading",
        action="store_true",
        help="there, it also holds its heading on the maze's grid: it steers back to the nearest "
        "multiple of 90 degrees and finishes a turn on the spot it began (implies "
        "--blind-forward); for robots that drive blind down a corridor's middle, such as the "
        "e-puck's own sensors",
    )
    train.add_argument(
        "--tensorboard",
        action="store_true",
        help="also log the learning curve to TensorBoard event files in --out/tensorboard "
        "(needs pip install 'mazesim[tensorboard]'); --out/learning_curve.csv is always written",
    )
    add_progress_option(train)
    train.set_defaults(run=lambda args: run_train(args, sys.stdout))


def run_train(args: argparse.Namespace, out: TextIO) -> int:
    """Runs ``mazesim train``."""
    from mazesim.learn.checkpoint import RunFolder
    from mazesim.learn.learning_curve import CURVE_FILE, LearningCurve
    from mazesim.learn.tables import checkpoint_exists
    from mazesim.learn.train import (
        TrainSettings,
        command_line_fields,
        navigator_world,
        train,
        train_flat_policy,
    )

    refuse_overwriting_inputs(
        output_files(args.out, ("tables.npz", "policy.json", "checkpoint.npz", CURVE_FILE)),
        [("--world", args.world)],
    )
    settings = TrainSettings(**{f.name: getattr(args, f.name) for f in command_line_fields()})
    navigator_world(settings.world)  # a world it cannot learn is refused before any training
    if args.door_distance or args.blind_forward or args.hold_heading:
        if args.flat:
            raise InvalidArgumentError(
                "--door-distance, --blind-forward and --hold-heading train hierarchical "
                "navigators only, not --flat"
            )
        settings = dataclasses.replace(
            settings,
            door_distance=args.door_distance,
            blind_forward=args.blind_forward or args.hold_heading,
            hold_heading=args.hold_heading,
        )
    robot: RobotChoice | RobotDraw = "seed"
    if args.randomise is not None:
        if args.flat:
            raise InvalidArgumentError(
                "--randomise trains hierarchical navigators only, not --flat"
            )
        from mazesim.transfer.randomise import parse_spec, robot_draw

        spec = parse_spec(args.randomise)
        settings = dataclasses.replace(settings, randomise=spec.text())
        robot = robot_draw(spec, settings.seed)
    curve = LearningCurve(Path(args.out), tensorboard=args.tensorboard)
    started = time.perf_counter()
    if args.flat:
        if args.resume:
            raise InvalidArgumentError("--resume continues hierarchical runs only, not --flat")
        with writing_alone(args.out, "mazesim train"), curve:
            with progress_display(args, units=_UNITS) as progress:
                policy = train_flat_policy(
                    settings, RunFolder(args.out), progress=progress, curve=curve
                )
        seconds = time.perf_counter() - started
        out.write(
            f"trained the flat baseline for {policy.world_name} in {seconds:.0f} s "
            f"({settings.steps} env-steps)\nwrote {Path(args.out) / 'tables.npz'}, "
            f"{Path(args.out) / 'policy.json'}, {curve.path}\n"
            f"evaluate it with: {shell_command('mazesim', 'eval', '--policy', args.out)}\n"
        )
        return 0
    folder = RunFolder(args.out, resume=args.resume)
    try:
        with writing_alone(args.out, "mazesim train", create=not args.resume), curve:
            if not args.resume or checkpoint_exists(Path(args.out)):
                _say_whole_rounds(settings)  # a resume with nothing to resume is refused alone
            with progress_display(args, units=_UNITS) as progress:
                result = train(settings, folder, progress=progress, curve=curve, robot=robot)
    except KeyboardInterrupt:
        if not checkpoint_exists(Path(args.out)):
            raise
        resume = "" if args.resume else " with --resume"
        raise KeyboardInterrupt(
            f"the run's checkpoint is kept in {args.out}: run the same command{resume} to "
            "continue it to the tables an uninterrupted run makes"
        ) from None
    if result is None:
        return 0
    # A resumed run's time counts the part before the resume, as its lower level's time does.
    seconds = time.perf_counter() - started + folder.resumed_seconds
    resumed = (
        f", {folder.resumed_seconds:.0f} s of it before --resume" if folder.resumed_seconds else ""
    )
    info = result.training
    out.write(
        f"trained a navigator for {result.world_name} in {seconds:.0f} s{resumed} "
        f"(lower level {info['lower_seconds']:.0f} s, {info['lower_env_steps']} env-steps; "
        f"higher level {info['higher_seconds']:.0f} s)\n"
        f"higher-level training: {100 * info['higher_success_last_100']:.0f}% of the last 100 "
        f"episodes reached the goal\n"
        f"wrote {Path(args.out) / 'tables.npz'}, {Path(args.out) / 'policy.json'}, "
        f"{curve.path}\n"
        f"evaluate it with: {shell_command('mazesim', 'eval', '--policy', args.out)}\n"
    )
    return 0


def _say_whole_rounds(settings: TrainSettings) -> None:
    """Says, once the output folder is taken and before the run, how ``--steps`` rounds: the
    lower level trains in whole rounds, never fewer steps than asked."""
    lower = settings.lower()
    trained_steps = lower.rounds * lower.num_envs * lower.round_steps
    if trained_steps != settings.steps:
        print(
            f"mazesim: --steps {settings.steps:,} trains {trained_steps:,} env-steps: "
            f"{lower.rounds} whole round(s) of {lower.num_envs:,} robots (--envs) x "
            f"{lower.round_steps} steps",
            file=sys.stderr,
        )
