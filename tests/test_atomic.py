"""Issue 15: atomic writes work on every system and leave no temporary files behind for ever."""

from __future__ import annotations

import os
import stat
import subprocess
import sys
import time
import types
from pathlib import Path

import pytest

from mazesim import _atomic
from mazesim._atomic import atomic_file, remove_stale_temporaries, temporary_name


def _hidden(folder: Path) -> list[str]:
    return sorted(name for name in os.listdir(folder) if name.startswith("."))


def test_a_write_replaces_the_file_whole_with_the_usual_permissions(tmp_path: Path) -> None:
    target = tmp_path / "summary.json"
    target.write_text("old")
    with atomic_file(target) as handle:
        handle.write(b"new")
        assert target.read_text() == "old"
    assert target.read_text() == "new"
    assert _hidden(tmp_path) == []
    mask = os.umask(0)
    os.umask(mask)
    assert stat.S_IMODE(target.stat().st_mode) == 0o666 & ~mask


def test_an_error_inside_the_block_leaves_the_file_and_no_temporary(tmp_path: Path) -> None:
    target = tmp_path / "summary.json"
    target.write_text("old")
    with pytest.raises(RuntimeError), atomic_file(target) as handle:
        handle.write(b"half")
        raise RuntimeError("stop")
    assert target.read_text() == "old"
    assert _hidden(tmp_path) == []


def _dead_pid() -> int:
    process = subprocess.Popen([sys.executable, "-c", "pass"])
    process.wait()
    return process.pid


def test_orphaned_temporaries_of_the_target_are_removed_and_nothing_else(tmp_path: Path) -> None:
    target = tmp_path / "tables.npz"
    old = time.time() - 3600
    # Left by a process that is gone, by this process outside a write, by an older mazesim.
    dead = tmp_path / f".tables.npz.{_dead_pid()}-0123abcd.tmp"
    mine = Path(temporary_name(str(target)))
    old_style = tmp_path / ".tables.npz.k2j4_x9q.tmp"
    for path in (dead, mine, old_style):
        path.write_bytes(b"partial")
    os.utime(old_style, (old, old))
    # Kept: a live process's fresh temporary, an old-style one newer than this process, other
    # targets' temporaries and files that only look alike.
    live = tmp_path / f".tables.npz.{os.getppid()}-89abcdef.tmp"
    fresh_old_style = tmp_path / ".tables.npz.abcdefgh.tmp"
    others = [
        tmp_path / f".policy.json.{_dead_pid()}-0123abcd.tmp",
        tmp_path / ".tables.npz.tmp",
        tmp_path / f".tables.npz.{_dead_pid()}-0123abcd.tmp.keep",
        tmp_path / "tables.npz.12-0123abcd.tmp",
    ]
    for path in (live, fresh_old_style, *others):
        path.write_bytes(b"keep")
    with atomic_file(target) as handle:
        handle.write(b"whole")
    assert target.read_bytes() == b"whole"
    for path in (dead, mine, old_style):
        assert not path.exists(), path
    for path in (live, fresh_old_style, *others):
        assert path.exists(), path


def test_a_temporary_being_written_is_not_removed(tmp_path: Path) -> None:
    target = tmp_path / "results.json"
    with atomic_file(target) as handle:
        handle.write(b"{}")
        assert remove_stale_temporaries(target) == []
        assert len(_hidden(tmp_path)) == 1
    assert _hidden(tmp_path) == []


def test_the_windows_branch_needs_no_fchmod_no_folder_sync_and_no_kill(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(_atomic, "_WINDOWS", True)
    monkeypatch.delattr(os, "fchmod", raising=False)
    monkeypatch.setattr(_atomic, "fcntl", None)
    real_open = os.open

    def open_no_folders(path: str, flags: int, *args: int) -> int:
        if os.path.isdir(path):
            raise PermissionError(13, "Permission denied", path)
        return real_open(path, flags, *args)

    def no_kill(pid: int, signal: int) -> None:
        raise AssertionError("os.kill ends the process on Windows")

    monkeypatch.setattr(os, "open", open_no_folders)
    monkeypatch.setattr(os, "kill", no_kill)
    target = tmp_path / "trajectory.png"
    orphan = tmp_path / f".trajectory.png.{_dead_pid()}-0123abcd.tmp"
    orphan.write_bytes(b"partial")
    old = time.time() - 3600
    os.utime(orphan, (old, old))
    young = tmp_path / f".trajectory.png.{_dead_pid()}-89abcdef.tmp"
    young.write_bytes(b"unsure")
    with atomic_file(target) as handle:
        handle.write(b"picture")
    assert target.read_bytes() == b"picture"
    # Without a process probe, only a temporary older than this process counts as orphaned.
    assert not orphan.exists()
    assert young.exists()


def test_macos_files_are_flushed_with_full_fsync(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    calls: list[int] = []

    def fcntl(descriptor: int, command: int) -> int:
        calls.append(command)
        return 0

    monkeypatch.setattr(_atomic, "fcntl", types.SimpleNamespace(F_FULLFSYNC=51, fcntl=fcntl))
    with atomic_file(tmp_path / "tables.npz") as handle:
        handle.write(b"tables")
    assert calls == [51]
    assert (tmp_path / "tables.npz").read_bytes() == b"tables"
