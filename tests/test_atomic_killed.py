"""A writer killed in the middle of a write leaves the old file whole, and the next write of the
same file, by either of mazesim's two writers (the core's, behind ``World.save``, and the Python
one every other file goes through: Q-tables, summaries, figures, videos, CSV, checkpoints,
corpus tables), removes the temporary file it left behind (#35, #15).

The writer runs in a child process that rewrites one file for ever; the test stops it (SIGSTOP)
at a moment its temporary file exists, which it checks once the child is stopped, and only then
kills it: a condition waited for, never a time.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

import mazesim
from mazesim._atomic import atomic_file

#: The child writing for ever, by writer family: the core's (a world saved) and Python's.
WRITERS = {
    "core": (
        "import sys, mazesim\n"
        "world = mazesim.generate_maze(24, 24, seed=1)\n"
        "while True:\n"
        "    world.save(sys.argv[1])\n"
    ),
    "python": (
        "import sys\n"
        "from mazesim._atomic import atomic_file\n"
        "while True:\n"
        "    with atomic_file(sys.argv[1]) as out:\n"
        "        out.write(b'x' * (4 << 20))\n"
    ),
}


def _temporaries(folder: Path, name: str) -> list[str]:
    """The temporary files of ``name`` in ``folder``, of either writer (of this version,
    ``.NAME.<pid>-<token>.tmp``, or of an older core, ``.NAME.tmp-<pid>-<count>``)."""
    return [f for f in os.listdir(folder) if f.startswith(f".{name}.") and "tmp" in f]


def _kill_mid_write(family: str, target: Path) -> list[str]:
    """Runs the ``family`` writer on ``target`` and kills it while its temporary file exists;
    returns the temporaries left."""
    child = subprocess.Popen([sys.executable, "-c", WRITERS[family], str(target)])
    try:
        while True:
            if child.poll() is not None:
                pytest.fail(f"the {family} writer ended by itself ({child.returncode})")
            if not _temporaries(target.parent, target.name):
                continue
            os.kill(child.pid, signal.SIGSTOP)
            # Stopped: the folder no longer changes; the write is caught in the middle or not.
            left = _temporaries(target.parent, target.name)
            if left:
                os.kill(child.pid, signal.SIGKILL)
                child.wait()
                return left
            os.kill(child.pid, signal.SIGCONT)
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()


@pytest.mark.parametrize("killed", sorted(WRITERS))
@pytest.mark.parametrize("next_writer", sorted(WRITERS))
def test_a_killed_write_keeps_the_old_file_and_the_next_write_removes_its_orphan(
    tmp_path: Path, killed: str, next_writer: str
) -> None:
    target = tmp_path / "maze.toml"
    old = mazesim.World.builtin("seed-maze")
    old.save(str(target))
    before = target.read_bytes()
    left = _kill_mid_write(killed, target)
    assert left, "the writer was caught in the middle of a write"
    after = target.read_bytes()
    # The old file whole, or the child's complete new one: never a part of either.
    if after != before:
        if killed == "core":
            assert mazesim.World.from_toml(after.decode()).name
        else:
            assert after == b"x" * (4 << 20)
    if next_writer == "core":
        old.save(str(target))
    else:
        with atomic_file(target) as out:
            out.write(before)
    assert _temporaries(tmp_path, target.name) == []
    assert target.read_bytes() == before
