"""Issue 15: atomic writes work on every system and leave no temporary files behind for ever."""

from __future__ import annotations

import errno
import os
import socket
import stat
import subprocess
import sys
import threading
import time
import types
from pathlib import Path
from typing import Any

import pytest

import mazesim
from mazesim import _atomic
from mazesim._atomic import atomic_file, remove_stale_temporaries, temporary_name
from mazesim.errors import MazesimIOError


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


@pytest.mark.parametrize("mode", [0o600, 0o640, 0o755])
def test_a_replaced_file_keeps_its_permissions_in_both_writers(tmp_path: Path, mode: int) -> None:
    # A private file stays private: the Python writer (runs, policies, summaries) and the
    # core's (World.save) give the new file the old one's permission bits.
    target = tmp_path / "kept.json"
    target.write_text("old")
    target.chmod(mode)
    with atomic_file(target) as handle:
        handle.write(b"new")
    assert stat.S_IMODE(target.stat().st_mode) == mode and target.read_text() == "new"
    world_file = tmp_path / "kept.toml"
    world_file.write_text("old")
    world_file.chmod(mode)
    mazesim.load_world("arena").save(str(world_file))
    assert stat.S_IMODE(world_file.stat().st_mode) == mode
    assert mazesim.load_world(str(world_file)).name == mazesim.load_world("arena").name


def test_a_read_only_file_is_refused_and_kept_by_both_writers(tmp_path: Path) -> None:
    target = tmp_path / "frozen.json"
    target.write_text("old")
    target.chmod(0o444)
    with pytest.raises(MazesimIOError, match="frozen.json: cannot write the file: it is read-only"):
        with atomic_file(target) as handle:
            handle.write(b"new")
    world_file = tmp_path / "frozen.toml"
    world_file.write_text("old")
    world_file.chmod(0o444)
    with pytest.raises(MazesimIOError, match="it is read-only"):
        mazesim.load_world("arena").save(str(world_file))
    assert target.read_text() == world_file.read_text() == "old"
    assert _hidden(tmp_path) == []


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


def test_the_older_cores_temporaries_go_by_their_pid_from_either_writer(tmp_path: Path) -> None:
    """The core once named its temporaries ``.NAME.tmp-<pid>-<count>``: a dead writer's go on
    the next write of the target, by the Python writer or the core's, a running one's stay."""
    for name in ("tables.npz", "maze.toml"):
        target = tmp_path / name
        dead = tmp_path / f".{name}.tmp-{_dead_pid()}-7"
        live = tmp_path / f".{name}.tmp-{os.getppid()}-0"
        look_alike = tmp_path / f".{name}.tmp-{_dead_pid()}-7x"
        for path in (dead, live, look_alike):
            path.write_bytes(b"partial")
        if name == "maze.toml":  # the core's writer
            mazesim.load_world("seed-maze").save(str(target))
        else:
            with atomic_file(target) as handle:
                handle.write(b"whole")
        assert not dead.exists(), dead
        assert live.exists() and look_alike.exists()


def test_a_temporary_being_written_is_not_removed(tmp_path: Path) -> None:
    target = tmp_path / "results.json"
    with atomic_file(target) as handle:
        handle.write(b"{}")
        assert remove_stale_temporaries(target) == []
        assert len(_hidden(tmp_path)) == 1
    assert _hidden(tmp_path) == []


def test_a_name_with_a_byte_that_is_not_utf_8_is_written_and_its_temporary_kept(
    tmp_path: Path,
) -> None:
    # Python gives such a byte as a lone surrogate, which no UTF-8 text holds: the one set of
    # writes in progress keeps the name as the core keeps its own.
    target = tmp_path / os.fsdecode(b"\xff.png")
    with atomic_file(target) as handle:
        handle.write(b"new")
        assert remove_stale_temporaries(target) == []
        assert len(_hidden(tmp_path)) == 1
    assert target.read_bytes() == b"new"
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


# Issue 35: what the output path names decides how it is written; nothing but a regular file is
# ever replaced.


def test_a_symbolic_link_is_followed_and_kept(tmp_path: Path) -> None:
    target = tmp_path / "real.json"
    target.write_text("old")
    link = tmp_path / "link.json"
    link.symlink_to(target)
    with atomic_file(link) as handle:
        handle.write(b"new")
    assert link.is_symlink() and os.readlink(link) == str(target)
    assert target.read_text() == "new"
    dangling = tmp_path / "dangling.json"
    dangling.symlink_to(tmp_path / "made.json")
    with atomic_file(dangling) as handle:
        handle.write(b"made")
    assert dangling.is_symlink() and (tmp_path / "made.json").read_text() == "made"


def test_a_link_to_dev_null_writes_into_it_and_stays(tmp_path: Path) -> None:
    link = tmp_path / "null.png"
    link.symlink_to(os.devnull)
    with atomic_file(link) as handle:
        handle.write(b"picture")
    assert link.is_symlink()
    assert stat.S_ISCHR(os.stat(os.devnull).st_mode)
    assert _hidden(tmp_path) == []


@pytest.mark.skipif(os.geteuid() != 0, reason="making a device node needs root")
def test_a_device_node_is_written_into_not_replaced(tmp_path: Path) -> None:
    node = tmp_path / "null"
    os.mknod(node, stat.S_IFCHR | 0o666, os.makedev(1, 3))
    try:
        with atomic_file(node) as handle:
            handle.write(b"picture")
    except MazesimIOError as error:  # a file system mounted nodev refuses to open it
        assert error.filename == str(node)
    assert stat.S_ISCHR(node.lstat().st_mode)


def test_a_fifo_is_written_into_when_read_and_refused_at_once_when_not(tmp_path: Path) -> None:
    fifo = tmp_path / "out.fifo"
    os.mkfifo(fifo)
    started = time.monotonic()
    with pytest.raises(MazesimIOError, match="FIFO that no process reads") as caught:
        with atomic_file(fifo) as handle:
            handle.write(b"lost")
    # Refused without waiting for a reader (one that never comes): a ceiling, not a pace.
    assert time.monotonic() - started < 60.0
    assert caught.value.filename == str(fifo)
    received: list[bytes] = []
    reader = threading.Thread(target=lambda: received.append(fifo.read_bytes()))
    reader.start()
    deadline = time.monotonic() + 120.0
    while time.monotonic() < deadline:  # the reader opens its end first
        try:
            with atomic_file(fifo) as handle:
                handle.write(b"through")
            break
        except MazesimIOError:
            time.sleep(0.01)
    reader.join(120.0)
    assert received == [b"through"]
    assert stat.S_ISFIFO(fifo.lstat().st_mode)


def test_proc_self_fd_is_written_into_whatever_it_is_open_on(tmp_path: Path) -> None:
    read_end, write_end = os.pipe()
    try:
        with atomic_file(f"/proc/self/fd/{write_end}") as handle:
            handle.write(b"piped")
        assert os.read(read_end, 100) == b"piped"
    finally:
        os.close(read_end)
        os.close(write_end)
    log = tmp_path / "log.txt"
    log.write_bytes(b"before\n")
    with open(log, "ab") as stdout:
        with atomic_file(f"/proc/self/fd/{stdout.fileno()}") as handle:
            handle.write(b"appended\n")
    assert log.read_bytes() == b"before\nappended\n"


def test_a_folder_or_a_socket_is_refused_naming_it(tmp_path: Path) -> None:
    with pytest.raises(MazesimIOError, match="it is a folder") as caught:
        with atomic_file(tmp_path) as handle:
            handle.write(b"x")
    assert caught.value.filename == str(tmp_path)
    address = tmp_path / "s.sock"
    with socket.socket(socket.AF_UNIX) as server:
        server.bind(str(address))
        with pytest.raises(MazesimIOError, match="found a socket"):
            with atomic_file(address) as handle:
                handle.write(b"x")
        assert stat.S_ISSOCK(address.lstat().st_mode)


def test_names_up_to_the_file_system_limit_work(tmp_path: Path) -> None:
    for length in (200, 236, 250, 255):
        target = tmp_path / ("é" * ((length - 5) // 2) + "x" * ((length - 5) % 2) + ".json")
        assert len(target.name.encode()) == length
        with atomic_file(target) as handle:
            handle.write(b"whole")
        assert target.read_bytes() == b"whole"
        assert len(os.path.basename(temporary_name(str(target))).encode()) <= 255 - 8
    assert _hidden(tmp_path) == []
    long = tmp_path / ("y" * 240)
    stale = Path(temporary_name(str(long)))
    stale.write_bytes(b"partial")
    with atomic_file(long) as handle:
        handle.write(b"whole")
    assert not stale.exists()


def test_a_full_disk_names_the_users_file_not_the_temporary(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    with pytest.raises(MazesimIOError, match="No space left on device") as caught:
        with atomic_file("/dev/full") as handle:
            handle.write(b"x" * 100)
    assert str(caught.value) == "/dev/full: cannot write the file: No space left on device"

    def full(descriptor: int) -> None:
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(_atomic, "_sync_file", full)
    target = tmp_path / "summary.json"
    with pytest.raises(MazesimIOError) as caught:
        with atomic_file(target) as handle:
            handle.write(b"x")
    assert str(caught.value) == f"{target}: cannot write the file: No space left on device"
    assert caught.value.errno == errno.ENOSPC and caught.value.filename == str(target)
    assert not target.exists() and _hidden(tmp_path) == []
    with pytest.raises(MazesimIOError, match="No such file or directory") as missing:
        with atomic_file(tmp_path / "no" / "such.json") as handle:
            handle.write(b"x")
    assert ".tmp" not in str(missing.value)


def test_writers_of_one_target_on_many_threads_leave_one_whole_file(tmp_path: Path) -> None:
    """Threads of one process writing one target at once, through the Python writer and the
    core's (World.save) alike: every write ends, or fails with a MazesimError, and the target
    is one writer's content whole, never a mix, with no temporary left behind."""
    target = tmp_path / "shared.toml"
    world = mazesim.load_world("seed-maze")
    whole = world.to_toml().encode()
    contents = {whole} | {bytes([65 + i]) * (50_000 + i) for i in range(4)}
    start = threading.Barrier(8)
    escaped: list[BaseException] = []

    def python_writer(i: int) -> None:
        start.wait()
        for _ in range(20):
            with atomic_file(target) as handle:
                handle.write(bytes([65 + i]) * (50_000 + i))

    def core_writer() -> None:
        start.wait()
        for _ in range(20):
            world.save(str(target))

    def guarded(work: Any, *args: int) -> None:
        try:
            work(*args)
        except mazesim.MazesimError:
            pass
        except BaseException as error:  # noqa: BLE001 - anything else is the finding
            escaped.append(error)

    threads = [threading.Thread(target=guarded, args=(python_writer, i)) for i in range(4)]
    threads += [threading.Thread(target=guarded, args=(core_writer,)) for _ in range(4)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert not escaped, escaped
    assert target.read_bytes() in contents
    assert _hidden(tmp_path) == []
