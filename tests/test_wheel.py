"""`make wheel`: a manylinux2014 abi3 wheel (glibc 2.17 and newer, linked with zig's linker) that
auditwheel accepts, that installs into a new virtual environment and runs from another directory,
and an sdist that carries everything the Rust core embeds; the wheel installed on the oldest
glibc reachable here (Debian bullseye's, in a chroot `make oldest-glibc-deps` makes) runs the
quick start and an evaluation as this machine does.

`make wheel` builds with zig in ``target/`` beside `make build`'s release build: the first build
compiles the dependencies (minutes), later ones take seconds; the new virtual environment and the
installation of numpy and matplotlib (from pip's cache when it has them) take most of the rest.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import tarfile
import venv
import zipfile
from pathlib import Path

import pytest

import oldest_glibc

ROOT = Path(__file__).resolve().parents[1]
QUICKSTART = ROOT / "examples" / "quickstart.py"


def _make_wheel(dist: Path) -> tuple[Path, Path, str]:
    """Runs ``make wheel`` into ``dist``; returns the wheel, the sdist and what make printed."""
    env = dict(os.environ, PYO3_PYTHON=sys.executable)
    result = subprocess.run(
        ["make", "-s", "wheel", f"DIST={dist}"],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 0, result.stdout + result.stderr
    wheels = list(dist.glob("mazesim-*.whl"))
    sdists = list(dist.glob("mazesim-*.tar.gz"))
    assert len(wheels) == 1 and len(sdists) == 1, list(dist.iterdir())
    return wheels[0], sdists[0], result.stdout + result.stderr


@pytest.fixture(scope="module")
def made(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path, str]:
    if shutil.which("cargo") is None or shutil.which("make") is None:
        pytest.skip("building the wheel needs cargo and make")
    return _make_wheel(tmp_path_factory.mktemp("dist"))


@pytest.fixture(scope="module")
def built(made: tuple[Path, Path, str]) -> tuple[Path, Path]:
    return made[0], made[1]


def test_wheel_is_abi3_and_manylinux2014(built: tuple[Path, Path]) -> None:
    wheel, _ = built
    # name-version-python-abi-platform: one wheel for CPython 3.9 and newer, installable from an
    # index on any x86_64 Linux with glibc 2.17 or newer (Ubuntu 20.04, Debian 11, RHEL 8).
    platforms = set(wheel.name[: -len(".whl")].split("-")[-1].split("."))
    assert re.fullmatch(r"mazesim-[\d.]+-cp39-abi3-[\w.]+\.whl", wheel.name)
    assert platforms == {"manylinux2014_x86_64", "manylinux_2_17_x86_64"}, wheel.name


def test_auditwheel_accepts_the_wheel_for_its_tag(made: tuple[Path, Path, str]) -> None:
    wheel, _, printed = made
    # `make wheel` ran `auditwheel show`; asked again here, it names the tag the wheel fits.
    shown = subprocess.run(
        [str(Path(sys.executable).parent / "auditwheel"), "show", str(wheel)],
        capture_output=True,
        text=True,
        check=False,
    )
    assert shown.returncode == 0, shown.stderr
    text = " ".join(shown.stdout.split())
    assert 'consistent with the following platform tag: "manylinux_2_17_x86_64"' in text, text
    assert 'platform tag: "manylinux_2_17_x86_64"' in " ".join(printed.split())  # make showed it
    # It ends saying how to install the wheel it wrote, as the next test does.
    install = (
        f"python -m pip install '{wheel}' (with the RL environments: python -m pip install "
        f"'{wheel}[gym]')"
    )
    assert any(line.endswith(install) for line in printed.splitlines()), printed


def test_sdist_carries_what_the_core_embeds(built: tuple[Path, Path]) -> None:
    _, sdist = built
    with tarfile.open(sdist) as archive:
        names = {name.split("/", 1)[1] for name in archive.getnames() if "/" in name}
    embedded = set()
    for source in (ROOT / "crates").rglob("*.rs"):
        for relative in re.findall(r'include_(?:str|bytes)!\(\s*"([^"]+)"', source.read_text()):
            target = (source.parent / relative).resolve()
            embedded.add(target.relative_to(ROOT).as_posix())
    assert {"worlds/seed-maze.toml", "robots/e-puck.toml"} <= embedded
    assert embedded <= names, sorted(embedded - names)
    assert {"pyproject.toml", "Cargo.lock", "python/mazesim/_core.pyi"} <= names


def test_wheel_carries_the_shipped_navigators(built: tuple[Path, Path]) -> None:
    wheel, _ = built
    with zipfile.ZipFile(wheel) as archive:
        names = set(archive.namelist())
    for folder in ("seed-maze", "seed-maze-randomised"):
        files = {f"mazesim/learn/data/{folder}/{name}" for name in ("policy.json", "tables.npz")}
        assert files <= names, sorted(files - names)


def test_wheel_carries_the_c_controller_library(built: tuple[Path, Path]) -> None:
    # A pip-installed mazesim compiles C controllers against these files.
    wheel, _ = built
    with zipfile.ZipFile(wheel) as archive:
        names = set(archive.namelist())
    library = ROOT / "python" / "mazesim" / "webots" / "capi"
    files = {
        f"mazesim/webots/capi/{path.relative_to(library).as_posix()}"
        for path in library.rglob("*")
        if path.suffix in (".c", ".h")
    }
    assert len(files) > 20 and files <= names, sorted(files - names)
    # ...and every controller's classes answer by the table of Webots' API names.
    assert "mazesim/webots/webots_api.toml" in names


def test_release_wheel_runs_the_demo_and_the_quick_start_from_anywhere(
    built: tuple[Path, Path], tmp_path: Path
) -> None:
    # Only the wheel and the quick start's text leave the source tree.
    wheel = Path(shutil.copy(built[0], tmp_path))
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    script = Path(shutil.copy(QUICKSTART, elsewhere))
    env_dir = tmp_path / "venv"
    venv.create(env_dir, with_pip=True)
    python = env_dir / "bin" / "python"
    clean_env = {
        key: value
        for key, value in os.environ.items()
        if key not in ("PYTHONPATH", "VIRTUAL_ENV", "PYTHONHOME")
    }
    install = subprocess.run(
        [str(python), "-m", "pip", "install", "--quiet", "--disable-pip-version-check", wheel],
        cwd=elsewhere,
        env=clean_env,
        capture_output=True,
        text=True,
        check=False,
    )
    assert install.returncode == 0, install.stderr

    def run(*argv: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            argv, cwd=elsewhere, env=clean_env, capture_output=True, text=True, check=False
        )

    demo = run(
        str(env_dir / "bin" / "mazesim"),
        *("demo", "--seconds", "5", "--out", "out", "--html", "out/replay.html"),
    )
    assert demo.returncode == 0, demo.stderr
    assert "seed-maze" in demo.stdout
    assert (elsewhere / "out" / "trajectory.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # The replay's viewer (package data) came with the wheel.
    assert "window.mazesimReplay" in (elsewhere / "out" / "replay.html").read_text()

    # -I (isolated): neither the script's folder nor user site-packages are on the path.
    quickstart = run(str(python), "-I", str(script))
    assert quickstart.returncode == 0, quickstart.stderr
    lines = quickstart.stdout.splitlines()
    assert lines[0].startswith("after 32.00 s (1000 steps): x ")
    assert lines[1].startswith("collisions: ")
    assert len(lines[2].split()) == 2 + 8 and len(lines[3].split()) == 2 + 3  # ps0..7, gs0..2
    # The installed package is the wheel's, and it runs the quick start exactly as the source
    # tree's build does: same seed, same run.
    where = run(str(python), "-I", "-c", "import mazesim; print(mazesim.__file__)").stdout
    assert where.startswith(str(env_dir))
    here = subprocess.run(
        [sys.executable, str(QUICKSTART)], capture_output=True, text=True, check=True
    )
    assert quickstart.stdout == here.stdout


def test_release_wheel_runs_on_the_oldest_glibc_here_as_it_does_here(
    built: tuple[Path, Path],
) -> None:
    cache = oldest_glibc.cache_dir()
    missing = oldest_glibc.missing_tools()
    if missing:
        pytest.skip(f"the chroot of the oldest glibc needs {', '.join(missing)}")
    if not oldest_glibc.is_prepared(cache):
        pytest.skip(f"no {oldest_glibc.SUITE} chroot in {cache}: `make oldest-glibc-deps` makes it")
    # A new venv of the chroot's own Python, the wheel installed without network; the
    # dependencies come from the venv `make oldest-glibc-deps` installed them into.
    there = oldest_glibc.run_in_chroot(built[0], cache, quick=True)
    here = oldest_glibc.run_here()
    assert there.glibc == "2.31" and there.python.startswith("3.9."), there
    assert there.mazesim.startswith("/tmp/mazesim-oldest-") and "/venv/" in there.mazesim
    assert there.quickstart.startswith("after 32.00 s (1000 steps): x ")
    assert "success rate        100.0%" in there.evaluation
    # Every module imports with the oldest Python (a `|` of types fails there when it runs).
    assert there.unimportable == (), there.unimportable
    # The same seed, the same run, bit for bit, whatever the glibc and the Python.
    assert there.quickstart == here.quickstart
    assert there.evaluation == here.evaluation
