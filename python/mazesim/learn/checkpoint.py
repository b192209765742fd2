"""A training run's folder: the checkpoint to continue from, the checkpoints as the run goes, and
the navigator at the end.

:class:`RunFolder` is what :func:`mazesim.learn.train.train` writes through (its ``checkpoint``
argument): ``--resume`` continues from the folder's checkpoint when the run's settings are the
same, the checkpoints are written as the run goes, and the navigator is saved at the end
(:func:`mazesim.learn.tables.save_policy`). Training itself writes nothing; ``mazesim train``
hands it a folder. The checkpoint file itself, complete or absent at every instant, is
:mod:`mazesim.learn.tables`' (:func:`~mazesim.learn.tables.write_checkpoint`).
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

from mazesim._paths import another_output_folder, make_output_folder, shell_command
from mazesim.errors import InvalidArgumentError, PolicyFormatError, _argument
from mazesim.learn.schema import differing
from mazesim.learn.tables import (
    CHECKPOINT_FILE,
    CHECKPOINT_FORMAT,
    METADATA_FILE,
    Checkpoint,
    TrainedPolicy,
    checkpoint_exists,
    read_checkpoint_file,
    remove_checkpoint_leftovers,
    save_policy,
    write_checkpoint,
)

__all__ = [
    "CHECKPOINT_FILE",
    "CHECKPOINT_FORMAT",
    "Checkpoint",
    "RunFolder",
    "checkpoint_exists",
    "read_checkpoint",
    "remove_checkpoint_leftovers",
    "write_checkpoint",
]


def _read_or_none(folder: Path, door_distance: bool) -> tuple[Checkpoint, dict[str, Any]] | None:
    try:
        return read_checkpoint_file(folder, door_distance)
    except PolicyFormatError:
        return None


def _settings_difference(asked: dict[str, Any], saved: dict[str, Any]) -> str:
    """The settings that differ between a run asked for and a checkpoint's, each as
    ``name: expected <the checkpoint's>, found <asked>`` (long values clipped where they differ,
    by :func:`mazesim.learn.schema.differing`)."""
    missing = object()
    names = sorted(set(asked) | set(saved))
    parts = []
    for name in names:
        theirs, ours = saved.get(name, missing), asked.get(name, missing)
        if theirs != ours:
            expected, found = (
                "(not set)" if value is missing else json.dumps(value) for value in (theirs, ours)
            )
            parts.append(f"{name}: {differing(expected, found)}")
    return "; ".join(parts)


def read_checkpoint(folder: Path, settings: dict[str, Any]) -> Checkpoint:
    """Reads and checks the checkpoint in ``folder``.

    Args:
        folder: The run's folder.
        settings: The settings of the run to continue; the checkpoint's must be the same.

    Raises:
        PolicyFormatError: No checkpoint, a malformed one, or one of a run with other settings.
    """
    # The tables' shape follows the run's door sub-task phases (``mazesim train --door-distance``).
    door_distance = bool(settings.get("door_distance", False))
    try:
        checkpoint, saved = read_checkpoint_file(folder, door_distance)
    except PolicyFormatError:
        # Tables of the other phases are a run with other settings, said below.
        other = _read_or_none(folder, not door_distance)
        if other is None or other[1] == settings:
            raise
        checkpoint, saved = other
    if saved != settings:
        raise PolicyFormatError(
            f"{folder / CHECKPOINT_FILE}: the checkpoint is of a run with other settings "
            f"({_settings_difference(settings, saved)}); resume it with those, "
            "or start afresh in another folder"
        )
    return checkpoint


class RunFolder:
    """A training run's folder: its checkpoints, the one to continue from, and the navigator.

    Args:
        folder: The folder (created when the run starts, if missing).
        resume: Continue the run whose checkpoint is in ``folder``; otherwise the folder must hold
            no checkpoint.
    """

    def __init__(self, folder: str | os.PathLike[str], resume: bool = False) -> None:
        self.folder = Path(folder)
        self.resume = resume
        #: The seconds the run had taken before it was resumed (0 for a fresh run).
        self.resumed_seconds = 0.0

    def start(self, settings: dict[str, Any]) -> Checkpoint | None:
        """Prepares the folder for a run with ``settings`` (its identity) and returns the
        checkpoint to continue from, or None for a fresh run.

        Raises:
            InvalidArgumentError: The folder is a file.
            PolicyFormatError: ``resume`` without a usable checkpoint of the same settings, or,
                without ``resume``, a checkpoint or a finished run's navigator already in the
                folder.
        """
        folder = self.folder
        if folder.exists() and not folder.is_dir():
            raise InvalidArgumentError(
                f"expected a folder for the navigator, found a file: {folder}"
            )
        saved = None
        if self.resume:
            if not checkpoint_exists(folder):
                raise PolicyFormatError(
                    f"{folder / CHECKPOINT_FILE}: no checkpoint to resume from; a run writes one "
                    f"into its output folder as it trains: start a fresh run there without "
                    f"{_argument('--resume', 'resume')}"
                )
            saved = read_checkpoint(folder, settings)
            self.resumed_seconds = saved.lower_seconds
        elif (folder / METADATA_FILE).exists():
            # A finished run keeps its checkpoint beside the navigator it saved last.
            measure = shell_command("mazesim", "eval", "--policy", folder)
            raise PolicyFormatError(
                f"{folder} already holds a trained navigator ({METADATA_FILE}, tables.npz) and "
                f"its run's checkpoint: {another_output_folder('folder')} for a new one, or delete "
                f"{folder} to train afresh there ('{measure}' measures the one it holds)"
            )
        elif checkpoint_exists(folder):
            raise PolicyFormatError(
                f"{folder} holds the checkpoint of a run that has not finished (interrupted, or "
                f"still running): pass {_argument('--resume', 'resume=True')} to continue it, or "
                f"{another_output_folder('folder')}"
            )
        make_output_folder(folder)
        remove_checkpoint_leftovers(folder)
        return saved

    def save(self, settings: dict[str, Any], checkpoint: Checkpoint) -> None:
        """Writes the run's checkpoint (:func:`write_checkpoint`)."""
        write_checkpoint(self.folder, settings, checkpoint)

    def finish(self, policy: TrainedPolicy) -> None:
        """Saves the trained navigator into the folder and names it as its source."""
        make_output_folder(self.folder)
        save_policy(policy, self.folder)
        policy.source = str(self.folder)
