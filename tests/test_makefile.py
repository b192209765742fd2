"""The Makefile's choice of interpreter for ``make venv``: python3.11, else any python3 >= 3.9."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _make(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        ["make", "--no-print-directory", *args],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )


@pytest.mark.skipif(shutil.which("make") is None, reason="needs make")
def test_venv_prefers_python311_else_python3(tmp_path: Path) -> None:
    # A dry run into a new folder shows the interpreter the venv would be made with.
    dry_run = _make("-n", "venv", f"VENV={tmp_path / 'venv'}")
    assert dry_run.returncode == 0, dry_run.stderr
    expected = shutil.which("python3.11") or shutil.which("python3")
    assert f"{expected} -m venv {tmp_path / 'venv'}" in dry_run.stdout


@pytest.mark.skipif(shutil.which("make") is None, reason="needs make")
def test_venv_refuses_a_python_older_than_39(tmp_path: Path) -> None:
    old_python = tmp_path / "python3.8"
    old_python.write_text(
        "#!/bin/sh\n"
        'case "$1" in --version) echo "Python 3.8.18"; exit 0;; -c) exit 1;; esac\n'
        'echo "should not be used: $*" >&2; exit 3\n'
    )
    old_python.chmod(0o755)
    refused = _make("venv", f"VENV={tmp_path / 'venv'}", f"PYTHON={old_python}")
    assert refused.returncode != 0
    assert "mazesim needs Python >= 3.9" in refused.stderr
    assert "Python 3.8.18" in refused.stderr and "make PYTHON=" in refused.stderr
    assert "should not be used" not in refused.stderr
    assert not (tmp_path / "venv").exists()


@pytest.mark.skipif(shutil.which("make") is None, reason="needs make")
def test_a_venv_left_without_pip_is_made_again(tmp_path: Path) -> None:
    # What `python3 -m venv` leaves where Debian's python3-venv is missing: a python, no pip.
    venv = tmp_path / "venv"
    subprocess.run(
        [shutil.which("python3") or "python3", "-m", "venv", "--without-pip", str(venv)],
        check=True,
        timeout=60,
    )
    # The interpreter that would make it again: it says what it was asked and stops there.
    python = tmp_path / "python3"
    python.write_text('#!/bin/sh\necho "asked: $*" >&2; exit 1\n')
    python.chmod(0o755)
    made = _make("venv", f"VENV={venv}", f"PYTHON={python}")
    assert made.returncode != 0
    assert f"make venv: {venv} has no pip" in made.stderr and "python3-venv" in made.stderr
    assert f"asked: -m venv --clear {venv}" in made.stderr
    assert "No module named pip" not in made.stderr


#: The developer tools: `make demo` must not install them, the targets that use them must.
DEV_TOOLS = (
    "pytest",
    "pytest-xdist",
    "hypothesis",
    "ruff",
    "mypy",
    "selenium",
    "ray",
    "tensorboardX",
)


def _dry_run(target: str, tmp_path: Path) -> str:
    """The commands ``make TARGET`` would run for a new venv in ``tmp_path``."""
    dry_run = _make("-n", target, f"VENV={tmp_path / 'venv'}")
    assert dry_run.returncode == 0, dry_run.stderr
    return dry_run.stdout


def _installed_by(commands: str) -> set[str]:
    """The packages the ``pip install`` lines of a dry run name."""
    names: set[str] = set()
    for line in commands.splitlines():
        if "-m pip install" in line:
            words = line.split("|")[0].split()
            names.update(w for w in words[words.index("install") + 1 :] if not w.startswith("-"))
    return names


@pytest.mark.skipif(shutil.which("make") is None, reason="needs make")
def test_make_demo_installs_what_the_demo_needs_and_no_developer_tool(tmp_path: Path) -> None:
    commands = _dry_run("demo", tmp_path)
    installed = _installed_by(commands)
    assert {"maturin", "numpy", "matplotlib"} <= installed
    assert installed.isdisjoint(DEV_TOOLS), installed & set(DEV_TOOLS)
    assert "torch" not in commands and "stable-baselines3" not in commands


@pytest.mark.skipif(shutil.which("make") is None, reason="needs make")
@pytest.mark.parametrize("target", ["test", "lint", "typecheck", "fmt"])
def test_the_targets_that_use_the_developer_tools_install_them(target: str, tmp_path: Path) -> None:
    assert set(DEV_TOOLS) <= _installed_by(_dry_run(target, tmp_path))


@pytest.mark.skipif(shutil.which("make") is None, reason="needs make")
def test_make_test_runs_every_test_once_and_logs_the_slowest(tmp_path: Path) -> None:
    runs = [line for line in _dry_run("test", tmp_path).splitlines() if "-m pytest" in line]
    # The parallel part leaves out exactly the tests the second part runs one at a time.
    assert len(runs) == 2, runs
    assert '-m "not alone"' in runs[0] and "-n" in runs[0].split(), runs
    # One test file in one process: the code blocks of a docs page build on each other.
    assert "--dist loadfile" in runs[0], runs
    assert runs[1].split()[-3:-1] == ["-m", "alone"] and "-n" not in runs[1].split(), runs
    assert all(any(word.startswith("--durations=") for word in run.split()) for run in runs)


def test_the_ros_tests_are_marked_to_run_alone() -> None:
    # Not imported from tests/conftest.py: under pytest-xdist `conftest` may name another folder's.
    alone_folders = ("ros", "ros2")
    tests = Path(__file__).parent
    marked = subprocess.run(
        [sys.executable, "-m", "pytest", "--co", "-q", "-m", "alone", "-p", "no:cacheprovider"]
        + [str(tests / folder) for folder in alone_folders + ("barcode", "replay")],
        capture_output=True,
        text=True,
        cwd=tests.parent,
    ).stdout.splitlines()
    folders = {line.split("/")[1] for line in marked if "::" in line}
    # Every test of the ROS folders, the replay test that needs ROS 1, none of the barcode tests.
    assert folders == set(alone_folders) | {"replay"}, folders
    assert not any(line.startswith("tests/replay/") and "ros" not in line for line in marked)


@pytest.mark.skipif(shutil.which("make") is None, reason="needs make")
def test_long_steps_say_what_they_cost_and_show_their_progress(tmp_path: Path) -> None:
    demo = _dry_run("demo", tmp_path)
    lines = demo.splitlines()
    develop = next(i for i, line in enumerate(lines) if "maturin develop" in line)
    # Before the Rust build: what it does and how long the first one takes; cargo's progress
    # shows (no --quiet), pip's "Ignoring ... markers" lines do not (PIP_QUIET).
    assert any("takes about 2 minutes" in line for line in lines[:develop])
    assert "--quiet" not in lines[develop] and "PIP_QUIET=1" in lines[develop]
    for line in lines:
        if "-m pip install" in line and "--upgrade pip" not in line and "DOCS" not in line:
            assert "--quiet" not in line or "mkdocs" in line, line
    # The largest download says so before it starts.
    sb3 = _dry_run("sb3-deps", tmp_path).splitlines()
    install = next(i for i, line in enumerate(sb3) if "stable-baselines3" in line and "pip" in line)
    assert any("3 GB to download" in line for line in sb3[:install])


@pytest.mark.skipif(shutil.which("make") is None, reason="needs make")
def test_make_wheel_links_with_zig_for_manylinux2014_and_asks_auditwheel(tmp_path: Path) -> None:
    commands = _dry_run("wheel", tmp_path)
    assert {"ziglang", "auditwheel"} <= _installed_by(commands)
    (build,) = [line for line in commands.splitlines() if "maturin build" in line]
    assert "--zig" in build and "--compatibility manylinux2014" in build
    assert commands.index("maturin build") < commands.index("auditwheel show")


#: The targets that download more than about 100 MB the first time, and what they say first.
LARGE_DOWNLOADS = {
    "sb3-deps": "3 GB to download",
    "dev-deps": "600 MB in",
    "wheel-deps": "410 MB installed",
    "bench-peers": "140 MB to download",
}


@pytest.mark.skipif(shutil.which("make") is None, reason="needs make")
@pytest.mark.parametrize("target", sorted(LARGE_DOWNLOADS))
def test_a_large_download_says_so_before_it_starts(target: str, tmp_path: Path) -> None:
    lines = _dry_run(target, tmp_path).splitlines()
    # The target's own install: the last pip install of the dry run (the venv's come first).
    install = max(
        i for i, line in enumerate(lines) if "-m pip install" in line and "--upgrade" not in line
    )
    said = [line for line in lines[:install] if LARGE_DOWNLOADS[target] in line]
    assert said and "echo" in said[-1], lines[: install + 1]


@pytest.mark.skipif(shutil.which("make") is None, reason="needs make")
@pytest.mark.parametrize("target", ["test", "typecheck"])
def test_the_targets_that_check_mazesim_marl_install_pettingzoo(
    target: str, tmp_path: Path
) -> None:
    assert '"pettingzoo>=1.24"' in _installed_by(_dry_run(target, tmp_path))


def _fake_python(path: Path, version: str) -> Path:
    """An executable that answers the Makefile's version question with ``version``."""
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(f"#!/bin/sh\necho {version}\n")
    path.chmod(0o755)
    return path


@pytest.mark.skipif(shutil.which("make") is None, reason="needs make")
def test_a_python_asked_for_after_the_venv_was_made_is_told_the_venv_keeps_its_own(
    tmp_path: Path,
) -> None:
    venv = tmp_path / "venv"
    _fake_python(venv / "bin" / "python", "3.11")
    (venv / ".installed").touch()  # made, and newer than the Makefile
    other = _fake_python(tmp_path / "python3.9", "3.9")
    told = _make("venv", f"VENV={venv}", f"PYTHON={other}")
    assert told.returncode == 0, told.stderr
    assert f"{venv} already exists with Python 3.11, and keeps it: PYTHON={other} (Python " in (
        told.stderr
    )
    assert f"remove {venv} first (rm -rf {venv}) to make it with {other}" in told.stderr
    same = _make("venv", f"VENV={venv}", f"PYTHON={_fake_python(tmp_path / 'py311', '3.11')}")
    assert same.returncode == 0 and same.stderr == "", same.stderr


@pytest.mark.skipif(shutil.which("git") is None, reason="needs git")
def test_make_lint_reads_every_folder_that_holds_python_files() -> None:
    tracked = subprocess.run(
        ["git", "ls-files", "*.py"], capture_output=True, text=True, cwd=ROOT, check=True
    ).stdout.split()
    folders = {Path(name).parts[0] for name in tracked if len(Path(name).parts) > 1}
    sources = next(
        line.split(":=", 1)[1].split()
        for line in (ROOT / "Makefile").read_text().splitlines()
        if line.startswith("PY_SOURCES :=")
    )
    assert folders and folders <= set(sources), folders - set(sources)
