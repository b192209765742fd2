"""A release wheel installs into a new virtual environment and runs from another directory."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import venv
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.skipif(shutil.which("cargo") is None, reason="building a wheel needs cargo")
def test_release_wheel_runs_the_demo_from_anywhere(tmp_path: Path) -> None:
    maturin = Path(sys.executable).with_name("maturin")
    dist = tmp_path / "dist"
    subprocess.run(
        [str(maturin), "build", "--release", "--quiet", "--out", str(dist)],
        cwd=ROOT,
        check=True,
    )
    wheels = list(dist.glob("mazesim-*.whl"))
    assert len(wheels) == 1, wheels
    env_dir = tmp_path / "venv"
    venv.create(env_dir, with_pip=True)
    python = env_dir / "bin" / "python"
    subprocess.run(
        [
            str(python),
            "-m",
            "pip",
            "install",
            "--quiet",
            "--disable-pip-version-check",
            str(wheels[0]),
        ],
        check=True,
    )
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    clean_env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    result = subprocess.run(
        [str(env_dir / "bin" / "mazesim"), "demo", "--seconds", "5", "--out", "out"]
        + ["--html", "out/replay.html"],
        cwd=elsewhere,
        env=clean_env,
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 0, result.stderr
    assert "seed-maze" in result.stdout
    png = elsewhere / "out" / "trajectory.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # The replay's viewer (package data) came with the wheel.
    assert "window.mazesimReplay" in (elsewhere / "out" / "replay.html").read_text()
    # The installed package is the wheel's, not the source tree's.
    where = subprocess.run(
        [str(python), "-c", "import mazesim; print(mazesim.__file__)"],
        cwd=elsewhere,
        env=clean_env,
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    assert str(env_dir) in where
