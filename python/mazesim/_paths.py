"""Guards on the files a command reads and writes: no command writes over one of its inputs."""

from __future__ import annotations

import os
from collections.abc import Iterable

from mazesim.errors import InvalidArgumentError

__all__ = ["output_files", "refuse_overwriting_inputs", "same_file"]


def same_file(first: str | os.PathLike[str], second: str | os.PathLike[str]) -> bool:
    """Whether two paths name one existing file, whatever their spelling (relative or absolute,
    ``..``, symbolic or hard links, case on case-insensitive disks)."""
    try:
        return os.path.samefile(first, second)
    except (OSError, ValueError):
        return False


def refuse_overwriting_inputs(
    outputs: Iterable[tuple[str, str | os.PathLike[str] | None]],
    inputs: Iterable[tuple[str, str | os.PathLike[str] | None]],
) -> None:
    """Raises when a file a command would write is one of the files it reads.

    Args:
        outputs: (what it is, path) of each file the command writes, e.g.
            ``("--out", "x.toml")``; None paths are skipped.
        inputs: (what it is, path) of each file or folder the command reads.

    Raises:
        InvalidArgumentError: An output is an input (the message names both and what to do),
            or an output file is a folder.
    """
    read = [(label, path) for label, path in inputs if path is not None]
    for out_label, out_path in outputs:
        if out_path is None:
            continue
        if os.path.isdir(out_path):
            raise InvalidArgumentError(
                f"{out_label} {os.fspath(out_path)!r} is a folder; expected the path of a file"
            )
        for in_label, in_path in read:
            if same_file(out_path, in_path):
                raise InvalidArgumentError(
                    f"{out_label} {os.fspath(out_path)!r} is the same file as {in_label} "
                    f"{os.fspath(in_path)!r}; mazesim does not write over its own input: "
                    f"choose another {out_label}"
                )


def output_files(
    folder: str | os.PathLike[str], names: Iterable[str]
) -> list[tuple[str, str | os.PathLike[str] | None]]:
    """(what it is, path) of the files a command writes into its output folder."""
    return [(f"the output {name}", os.path.join(folder, name)) for name in names]
