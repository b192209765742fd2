"""The release wheel on the oldest glibc reachable here: a Debian chroot, the wheel installed into
its own Python without network, and the quick start and a short evaluation run there.

The wheel's tag claims glibc 2.17 (manylinux2014). The oldest Debian release deb.debian.org
still serves is bullseye (glibc 2.31, Python 3.9, the oldest Python the abi3 wheel is for);
buster and older moved to archive.debian.org. The chroot is made once with debootstrap and kept
outside the checkout (``~/.cache/mazesim/oldest-glibc``, or ``$MAZESIM_OLDEST_CACHE``), beside a
folder of the wheel's dependencies fetched from PyPI for the chroot's Python. Installing and
running then needs no network: it runs in a network namespace of its own (``unshare -n``).

``python tests/oldest_glibc.py prepare`` makes the chroot and fetches the dependencies (what
needs the network); ``python tests/oldest_glibc.py check WHEEL`` installs the wheel there, runs
the quick start and ``mazesim eval`` in the chroot and on this machine, and compares them:
``make wheel-oldest`` runs both.
"""

from __future__ import annotations

import argparse
import json
import os
import shlex
import shutil
import ssl
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
QUICKSTART = ROOT / "examples" / "quickstart.py"
#: The oldest Debian release its main mirror serves, and that mirror.
SUITE = "bullseye"
MIRROR = "http://deb.debian.org/debian"
#: What the chroot needs beside debootstrap's minimal base: Python and its venv module.
CHROOT_PACKAGES = ("python3", "python3-venv")
#: Where the quick check finds the dependencies in the chroot, installed once by ``prepare``.
DEPENDENCIES = Path("/opt/mazesim-dependencies")
#: The evaluation run in both places: short, deterministic, the shipped navigator.
EVAL_ARGS = ("eval", "--episodes", "5", "--events", "truth")
#: Prints what the chroot is: its glibc and Python, and where mazesim was imported from.
ABOUT = (
    "import json, os, platform, mazesim; print(json.dumps({"
    "'glibc': os.confstr('CS_GNU_LIBC_VERSION'), 'python': platform.python_version(), "
    "'mazesim': mazesim.__file__}))"
)
#: Imports every module of the package and prints the ones that fail other than for a missing
#: optional dependency (a JSON list): a line only a newer Python reads fails here.
IMPORT_ALL = (
    "import importlib, json, pkgutil, mazesim; from mazesim.errors import MissingDependencyError; "
    "names = [m.name for m in pkgutil.walk_packages(mazesim.__path__, 'mazesim.', onerror=id) "
    "if not m.name.endswith('__main__')]; failed = []\n"
    "for name in names:\n"
    "    try: importlib.import_module(name)\n"
    "    except (ModuleNotFoundError, MissingDependencyError): pass\n"
    "    except Exception as error: failed.append(f'{name}: {type(error).__name__}: {error}')\n"
    "print(json.dumps(failed))"
)


def cache_dir() -> Path:
    """Where the chroot and the dependencies are kept: outside the checkout."""
    configured = os.environ.get("MAZESIM_OLDEST_CACHE")
    if configured:
        return Path(configured)
    base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    return base / "mazesim" / "oldest-glibc"


def chroot_root(cache: Path, suite: str = SUITE) -> Path:
    """The chroot's root folder for ``suite``."""
    return cache / suite


def wheelhouse(cache: Path, suite: str = SUITE) -> Path:
    """The folder of the wheel's dependencies fetched for the chroot's Python."""
    return cache / f"{suite}-wheelhouse"


def missing_tools() -> list[str]:
    """What this machine lacks to make and enter the chroot (empty when nothing)."""
    missing = [tool for tool in ("debootstrap", "chroot", "unshare") if shutil.which(tool) is None]
    if os.geteuid() != 0:
        missing.append("root (debootstrap and chroot need it)")
    return missing


def is_prepared(cache: Path, suite: str = SUITE) -> bool:
    """Whether the chroot and its dependency folder are complete."""
    root = chroot_root(cache, suite)
    return all(
        (folder / ".mazesim-ready").exists()
        for folder in (root, wheelhouse(cache, suite), root / DEPENDENCIES.relative_to("/"))
    )


def prepare(cache: Path, suite: str = SUITE, mirror: str = MIRROR) -> None:
    """Makes the chroot, fetches the wheel's dependencies for its Python and installs them
    into a venv there for the quick check: each once.

    The chroot and the dependency folder are made in a temporary folder and renamed when
    complete, so an interrupted run leaves no half chroot behind.
    """
    cache.mkdir(parents=True, exist_ok=True)
    root = chroot_root(cache, suite)
    if not (root / ".mazesim-ready").exists():
        print(f"oldest-glibc: debootstrap {suite} into {root} (about 45 MB to download)")
        building = Path(tempfile.mkdtemp(prefix=f".{suite}-", dir=cache))
        include = ",".join(CHROOT_PACKAGES)
        subprocess.run(
            ["debootstrap", "--variant=minbase", f"--include={include}", suite, building, mirror],
            check=True,
        )
        for package in (building / "var" / "cache" / "apt" / "archives").glob("*.deb"):
            package.unlink()  # installed already: 45 MB less on disk
        (building / ".mazesim-ready").write_text(f"{suite} {mirror}\n")
        if root.exists():
            shutil.rmtree(root)
        building.rename(root)
    house = wheelhouse(cache, suite)
    if not (house / ".mazesim-ready").exists():
        # The chroot's own pip fetches them, so that they fit its Python and its markers.
        print(f"oldest-glibc: fetching mazesim's dependencies for {suite}'s Python into {house}")
        fetching = Path(tempfile.mkdtemp(prefix="mazesim-wheelhouse-", dir=root / "tmp"))
        inside = Path("/") / fetching.relative_to(root)
        requirements = " ".join(shlex.quote(d) for d in _dependencies())
        # pip there trusts the certificate authorities pip trusts here (a proxy's, say).
        shutil.copy(_certificate_authorities(), fetching / "authorities.pem")
        fetched = _in_chroot(
            root,
            f"cd {inside} && python3 -m venv venv && venv/bin/python -m pip download --quiet "
            f"--disable-pip-version-check --only-binary=:all: --dest wheelhouse {requirements}",
            timeout_s=1800,
            network=True,
            env=(f"PIP_CERT={inside / 'authorities.pem'}",),
        )
        if fetched.returncode != 0:
            shutil.rmtree(fetching, ignore_errors=True)
            raise RuntimeError(f"fetching the dependencies in {suite} failed:\n{fetched.stderr}")
        (fetching / "wheelhouse" / ".mazesim-ready").write_text(f"{requirements}\n")
        if house.exists():
            shutil.rmtree(house)
        shutil.move(fetching / "wheelhouse", house)
        shutil.rmtree(fetching, ignore_errors=True)
    installed = root / DEPENDENCIES.relative_to("/")
    if not (installed / ".mazesim-ready").exists():
        # The dependencies installed once, for the quick check: it installs the wheel alone.
        shutil.rmtree(installed, ignore_errors=True)
        shutil.copytree(house, root / "tmp" / "mazesim-wheelhouse", dirs_exist_ok=True)
        made = _in_chroot(
            root,
            f"python3 -m venv {DEPENDENCIES} && {DEPENDENCIES}/bin/python -m pip install --quiet "
            "--disable-pip-version-check --no-index --find-links /tmp/mazesim-wheelhouse "
            + " ".join(shlex.quote(d) for d in _dependencies()),
            timeout_s=1800,
        )
        shutil.rmtree(root / "tmp" / "mazesim-wheelhouse", ignore_errors=True)
        if made.returncode != 0:
            raise RuntimeError(f"installing the dependencies in {suite} failed:\n{made.stderr}")
        (installed / ".mazesim-ready").write_text("installed from the wheelhouse\n")


def _dependencies() -> list[str]:
    """mazesim's run-time requirements, as pyproject.toml states them."""
    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover - the venv's Python is 3.11 where the figures were measured
        import tomli as tomllib
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    return list(project["dependencies"])


def _certificate_authorities() -> str:
    """The certificate authorities pip trusts on this machine."""
    for name in ("PIP_CERT", "REQUESTS_CA_BUNDLE", "SSL_CERT_FILE"):
        if os.path.isfile(os.environ.get(name, "")):
            return os.environ[name]
    return ssl.get_default_verify_paths().cafile or "/etc/ssl/certs/ca-certificates.crt"


def _in_chroot(
    root: Path, script: str, timeout_s: float, network: bool = False, env: tuple[str, ...] = ()
) -> subprocess.CompletedProcess[str]:
    """Runs a shell script in the chroot with its own /proc and a clean environment; without
    network unless ``network``."""
    return subprocess.run(
        [
            *("unshare", *(() if network else ("--net",)), "--mount", "--pid", "--fork"),
            f"--mount-proc={root / 'proc'}",
            *("chroot", str(root), "/usr/bin/env", "-i", "HOME=/root", "LANG=C.UTF-8"),
            *("PATH=/usr/local/bin:/usr/bin:/bin", *env, "/bin/sh", "-e", "-c", script),
        ],
        capture_output=True,
        text=True,
        timeout=timeout_s,
        check=False,
    )


@dataclass(frozen=True)
class Outcome:
    """What one place printed: its glibc and Python, where mazesim was imported from, the quick
    start's output and the evaluation's (without its first line, which names the navigator's
    folder), and how long installing the wheel took there (0 where nothing was installed)."""

    glibc: str
    python: str
    mazesim: str
    quickstart: str
    evaluation: str
    install_s: float = 0.0
    #: The modules that failed to import (other than for a missing optional dependency).
    unimportable: tuple[str, ...] = ()


def _outcome(
    about: str, quickstart: str, evaluation: str, install_s: float, unimportable: str = "[]"
) -> Outcome:
    facts = json.loads(about)
    return Outcome(
        glibc=facts["glibc"].split()[-1],
        python=facts["python"],
        mazesim=facts["mazesim"],
        quickstart=quickstart,
        evaluation=evaluation.split("\n", 1)[1],
        install_s=install_s,
        unimportable=tuple(json.loads(unimportable)),
    )


def run_in_chroot(
    wheel: Path, cache: Path, suite: str = SUITE, quick: bool = False, timeout_s: float = 900
) -> Outcome:
    """Installs ``wheel`` into a new venv of the chroot's Python without network, then runs the
    quick start and the evaluation there.

    The venv gets the dependencies from the dependency folder alone, or, ``quick``, from the
    venv ``prepare`` installed them into (a ``.pth`` file), so that only the wheel is installed.
    """
    root = chroot_root(cache, suite)
    work = Path(tempfile.mkdtemp(prefix="mazesim-oldest-", dir=root / "tmp"))
    inside = Path("/") / work.relative_to(root)
    try:
        shutil.copy(wheel, work)
        shutil.copy(QUICKSTART, work)
        (work / "import_all.py").write_text(IMPORT_ALL + "\n", encoding="utf-8")
        if quick:
            dependencies = (
                f"echo {DEPENDENCIES}/lib/python3*/site-packages "
                "> $(echo venv/lib/python3*/site-packages)/mazesim-dependencies.pth && "
            )
            install = f"--no-deps {wheel.name}"
        else:
            shutil.copytree(wheelhouse(cache, suite), work / "wheelhouse")
            dependencies = ""
            install = f"--find-links wheelhouse {wheel.name}"
        started = time.monotonic()
        installed = _in_chroot(
            root,
            f"cd {inside} && python3 -m venv venv && {dependencies}venv/bin/python -m pip install "
            f"--quiet --no-index --disable-pip-version-check {install}",
            timeout_s,
        )
        install_s = time.monotonic() - started
        if installed.returncode != 0:
            raise RuntimeError(f"installing {wheel.name} in {suite} failed:\n{installed.stderr}")
        ran = _in_chroot(
            root,
            f'cd {inside} && venv/bin/python -I -c "{ABOUT}" && echo --- '
            f"&& venv/bin/python -I quickstart.py && echo --- "
            f"&& venv/bin/mazesim {' '.join(EVAL_ARGS)} && echo --- "
            f"&& venv/bin/python -I import_all.py",
            timeout_s,
        )
        if ran.returncode != 0:
            raise RuntimeError(f"mazesim in {suite} failed:\n{ran.stdout}\n{ran.stderr}")
        about, quickstart, evaluation, unimportable = ran.stdout.split("---\n")
        return _outcome(about, quickstart, evaluation, install_s, unimportable)
    finally:
        shutil.rmtree(work, ignore_errors=True)


def run_here() -> Outcome:
    """The quick start and the evaluation with this machine's Python and mazesim."""

    def output(*argv: str) -> str:
        return subprocess.run(argv, capture_output=True, text=True, check=True).stdout

    return _outcome(
        output(sys.executable, "-c", ABOUT),
        output(sys.executable, str(QUICKSTART)),
        output(sys.executable, "-m", "mazesim", *EVAL_ARGS),
        0.0,
    )


def main(argv: list[str] | None = None) -> int:
    """``prepare`` (needs the network) or ``check WHEEL`` (needs none)."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cache", type=Path, default=None, help="default: " + str(cache_dir()))
    parser.add_argument("--suite", default=SUITE, help=f"the Debian release (default {SUITE})")
    commands = parser.add_subparsers(dest="command", required=True)
    commands.add_parser("prepare", help="make the chroot and fetch the dependencies (once)")
    check = commands.add_parser("check", help="install WHEEL in the chroot, run and compare")
    check.add_argument("wheel", type=Path)
    args = parser.parse_args(argv)
    cache = args.cache or cache_dir()
    missing = missing_tools()
    if missing:
        print(f"oldest-glibc: this machine lacks {', '.join(missing)}", file=sys.stderr)
        return 2
    if args.command == "prepare":
        prepare(cache, args.suite)
        return 0
    if not is_prepared(cache, args.suite):
        print(f"oldest-glibc: no chroot in {cache}: run 'prepare' first", file=sys.stderr)
        return 2
    there = run_in_chroot(args.wheel, cache, args.suite)
    here = run_here()
    print(
        f"oldest-glibc: {args.wheel.name} installed in Debian {args.suite} (glibc {there.glibc}, "
        f"Python {there.python}) in {there.install_s:.0f} s, from {there.mazesim}"
    )
    same = there.quickstart == here.quickstart and there.evaluation == here.evaluation
    print(there.quickstart + there.evaluation, end="")
    print(
        f"oldest-glibc: the quick start and `mazesim {' '.join(EVAL_ARGS)}` print "
        + ("the same" if same else "NOT the same")
        + f" as here (glibc {here.glibc}, Python {here.python})"
    )
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
