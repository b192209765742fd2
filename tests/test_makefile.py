"""The Makefile's choice of interpreter for ``make venv``: python3.11, else any python3 >= 3.9."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _make(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        ["make", "--no-print-directory", *args],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=60,
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
