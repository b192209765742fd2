"""The newcomer's path, replayed on a fresh clone: ``make demo`` as the README gives it, the
own-maze recipe as docs/own-maze.md prints it, and a maze without checkpoints, which ``mazesim
train`` must refuse before any training.

``make newcomer-check`` runs it (``python tests/newcomer_path.py``): it clones the checkout's
committed state into a new folder, so ``make demo`` there creates its own ``.venv`` and builds
the Rust core from nothing (minutes; pip's cache serves the packages when it has them). It
prints what each step printed and how long it took, and fails on a warning that is none (pip's
"Ignoring ... markers" lines), a warning at all, or a step that does not say how long it took.
The quick tests of its parts run in ``make test`` (``tests/test_newcomer_path.py``).
"""

from __future__ import annotations

import argparse
import os
import re
import shlex
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from docs_blocks import console_commands, parse_blocks

ROOT = Path(__file__).resolve().parents[1]
RECIPE = Path("docs") / "own-maze.md"
#: Lines that look like trouble to a newcomer: pip's notes on extras it skips, warnings of any
#: tool, deprecations, tracebacks.
_MISLEADING = re.compile(
    r"^\s*(Ignoring \S+: markers|WARNING\b|[Ww]arning:|DEPRECATION:|Traceback )|\w+Warning: "
)
#: A line that names how long a step took: "... in 98 s", "wall-clock time 2.586 s".
_DURATION = re.compile(r"\b(in|took|wall-clock time)\s+\d+(\.\d+)? (s|min)\b")
#: A guard against a step that hangs, not a speed requirement.
STEP_TIMEOUT_S = 3 * 3600


def misleading_lines(output: str) -> list[str]:
    """The lines of ``output`` a newcomer would take for a warning or an error."""
    return [line for line in output.splitlines() if _MISLEADING.search(line)]


def duration_lines(output: str) -> list[str]:
    """The lines of ``output`` that say how long something took."""
    return [line for line in output.splitlines() if _DURATION.search(line)]


def demo_problems(output: str) -> list[str]:
    """What is wrong with what ``make demo`` printed (empty when nothing): a misleading line,
    the Rust build or the demo's run not saying how long it took, no word of what to open next
    or where the ``mazesim`` command is."""
    problems = [f"misleading line: {line!r}" for line in misleading_lines(output)]
    timed = duration_lines(output)
    if not any(line.startswith("make build:") for line in timed):
        problems.append("the build does not say how long it took ('make build: ... in N s')")
    if not any(line.startswith("wall-clock time") for line in timed):
        problems.append("the demo does not say how long its run took ('wall-clock time')")
    lines = output.splitlines()
    if not any(line.startswith("next") and "replay.html in a browser" in line for line in lines):
        problems.append("the demo does not say what to open next (its replay.html)")
    if not any(line.startswith("make demo:") and "mazesim --help" in line for line in lines):
        problems.append("make demo does not say where the mazesim command is")
    return problems


def recipe_commands(checkout: Path) -> tuple[list[str], str]:
    """The own-maze recipe's commands, and what its page says ``mazesim show`` prints."""
    page = checkout / RECIPE
    blocks = parse_blocks(page, page.read_text(encoding="utf-8"), checkout)
    (recipe,) = [block for block in blocks if block.language == "console"]
    (shown,) = [block for block in blocks if block.language == "text"]
    return console_commands(recipe.text).splitlines(), shown.text


@dataclass(frozen=True)
class Step:
    """One step of the path: the command, its exit status, what it printed, how long it took."""

    command: str
    returncode: int
    output: str
    seconds: float


def run_step(command: str, cwd: Path, env: dict[str, str]) -> Step:
    """Runs ``command`` with bash in ``cwd``; stdout and stderr together, as a terminal shows."""
    started = time.monotonic()
    finished = subprocess.run(
        ["bash", "-e", "-c", command],
        cwd=cwd,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        timeout=STEP_TIMEOUT_S,
        check=False,
    )
    return Step(command, finished.returncode, finished.stdout, time.monotonic() - started)


def installed_env(venv_bin: Path) -> dict[str, str]:
    """The environment of a shell whose ``mazesim`` and ``python`` are the venv's."""
    env = {k: v for k, v in os.environ.items() if k not in ("VIRTUAL_ENV", "PYTHONPATH")}
    env["PATH"] = f"{venv_bin}{os.pathsep}{env.get('PATH', '')}"
    return env


def recipe_problems(checkout: Path, venv_bin: Path, folder: Path) -> tuple[list[str], list[Step]]:
    """Runs the own-maze recipe as printed in ``folder``; returns what went wrong and the
    steps."""
    commands, shown = recipe_commands(checkout)
    env = installed_env(venv_bin)
    steps, problems = [], []
    for command in commands:
        step = run_step(command, folder, env)
        steps.append(step)
        if step.returncode != 0:
            problems.append(f"{command!r} failed ({step.returncode}):\n{step.output}")
            return problems, steps
    show, train = steps[1].output, steps[2].output
    if show != shown:
        problems.append(f"mazesim show printed\n{show}\nthe page says\n{shown}")
    advised = train.splitlines()[-1].split(": ", 1)[-1]
    if not commands[3].startswith(advised):
        problems.append(f"train advises {advised!r}; the recipe's next command is {commands[3]!r}")
    return problems, steps


#: A 4 x 4 maze that is one corridor: no junction, so no barcode checkpoint.
CORRIDOR = (
    "import mazesim; mazesim.generate_maze(4, 4, seed=3, junction=False).save('corridor.toml')"
)


def refusal_problems(venv_bin: Path, folder: Path) -> tuple[list[str], list[Step]]:
    """Trains on a maze without checkpoints: ``mazesim train`` must refuse it before training,
    saying what to change, and write nothing."""
    env = installed_env(venv_bin)
    made = run_step(f"python -c {shlex.quote(CORRIDOR)}", folder, env)
    train = run_step("mazesim train --world corridor.toml --out corridor-navigator", folder, env)
    problems = []
    if made.returncode != 0:
        problems.append(f"making the corridor maze failed:\n{made.output}")
    if train.returncode != 2:
        problems.append(f"train exited {train.returncode}, expected 2 (refused):\n{train.output}")
    if "no barcode checkpoints" not in train.output:
        problems.append(f"train's refusal does not name the missing checkpoints:\n{train.output}")
    if (folder / "corridor-navigator").exists():
        problems.append("train wrote corridor-navigator/ although it refused the maze")
    return problems, [made, train]


def fresh_clone(destination: Path) -> Path:
    """Clones the checkout's committed state (HEAD) into ``destination``."""
    subprocess.run(
        ["git", "clone", "--quiet", "--no-hardlinks", str(ROOT), str(destination)], check=True
    )
    return destination


def _report(step: Step) -> None:
    print(f"$ {step.command}    # {step.seconds:.0f} s, exit {step.returncode}")
    print(step.output, end="" if step.output.endswith("\n") or not step.output else "\n")


def main(argv: list[str] | None = None) -> int:
    """Clones, runs ``make demo``, the recipe and the refusal; 0 when nothing went wrong."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--folder", type=Path, help="work here (default: a new temporary folder)")
    args = parser.parse_args(argv)
    folder = args.folder or Path(tempfile.mkdtemp(prefix="mazesim-newcomer-"))
    folder.mkdir(parents=True, exist_ok=True)
    clone = fresh_clone(folder / "mazesim")
    print(f"newcomer-check: a fresh clone of {ROOT} (HEAD) in {clone}")
    env = {k: v for k, v in os.environ.items() if k not in ("VIRTUAL_ENV", "PYTHONPATH")}
    env.pop("PYO3_PYTHON", None)
    demo = run_step("make demo", clone, env)
    _report(demo)
    problems = [] if demo.returncode == 0 else [f"make demo failed ({demo.returncode})"]
    problems += demo_problems(demo.output)
    venv_bin = clone / ".venv" / "bin"
    later: list[Step] = []
    if demo.returncode == 0:
        own = folder / "own-maze"
        own.mkdir(exist_ok=True)
        found, later = recipe_problems(clone, venv_bin, own)
        found_refusal, refusal = refusal_problems(venv_bin, own)
        later += refusal
        for step in later:
            _report(step)
        problems += found + found_refusal
    total = demo.seconds + sum(step.seconds for step in later)
    print(f"newcomer-check: make demo took {demo.seconds:.0f} s; the whole path {total:.0f} s")
    for problem in problems:
        print(f"newcomer-check: PROBLEM: {problem}", file=sys.stderr)
    print("newcomer-check: " + ("no problem" if not problems else f"{len(problems)} problem(s)"))
    return 0 if not problems else 1


if __name__ == "__main__":
    sys.exit(main())
