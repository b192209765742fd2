"""Runs one corpus project from a local mirror: exports it, imports its world, runs its first
controller with ``mazesim webots run`` for the project's simulated time, and checks its facts.

A world in which several robots have a controller runs whole (``mazesim webots run WORLD``:
every robot with its own controller, in lockstep), and so does a world without an e-puck that
declares the E-puck PROTO ``IMPORTABLE`` (a supervisor that imports the swarm, as Webots from
R2023b has it declared); the facts about one robot's path are then checked on the robot that
runs the project's first controller."""

from __future__ import annotations

import csv
import json
import os
import re
import signal
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from webots_corpus.census import DROPPED_WORDS, Census, losses
from webots_corpus.facts import MOVED, Outcome, check, farthest_from_start, parse_fact
from webots_corpus.manifest import RUN, Project
from webots_corpus.mirrors import MirrorError, export, find_mirror, has_commit, read_file

#: Words of an import warning that says something of the world was lost (a dropped node, an
#: unknown one, a floor texture that could not be read).
LOST_WORDS = (*DROPPED_WORDS, "unknown", "left bare")
#: Wall-clock seconds a run may take beyond its simulated time before it is stopped.
GRACE_S = 30.0
#: Wall-clock seconds a stopped run has to write its outputs before it is killed.
INTERRUPT_GRACE_S = 5.0


@dataclass
class Row:
    """A project's line of the compatibility table."""

    project: Project
    result: str
    cause: str = ""
    checks: list[tuple[str, bool, str]] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    wall_s: float = 0.0


def _import(world: Path, controller: str) -> tuple[Any, dict[str, Any]]:
    from mazesim.webots import import_wbt

    world_obj, report = import_wbt(world, controller=controller)
    return world_obj, dict(report)


#: ``controller`` fields that name no controller.
NO_CONTROLLER = ("", "void", "<generic>", "<none>")


#: A world's declaration that its supervisor imports e-pucks.
_IMPORTS_E_PUCKS = re.compile(r'IMPORTABLE\s+EXTERNPROTO\s+"[^"]*/E-puck2?\.proto"')


def _runs_whole(project: Project, report: dict[str, Any], text: str = "") -> bool:
    """Whether the world (its import ``report`` and file ``text``) runs whole: a project in
    which several robots have a controller (Python, C or C++; a node that leaves its
    ``controller`` field out has its PROTO's default one), or whose world has no e-puck but
    declares the E-puck importable, or whose first controller is in a language mazesim does
    not run (the world's run says so of its robot, which stands still). A key script does not
    make it a run of one controller: the whole world's run types its keys on every
    controller's Keyboard, as Webots sends the keys typed with no robot selected to every
    robot, and the other robots' controllers run as Webots runs them; a project whose
    manifest says why (``alone``) runs its first controller alone."""
    from mazesim.webots.lockstep import controller_name

    robots = report.get("robots") or []
    running = [r for r in robots if controller_name(r) not in NO_CONTROLLER]
    if project.language not in RUN:
        return True
    if project.alone:
        return False
    no_e_puck = running and not any(r.get("profile") is not None for r in robots)
    return len(running) > 1 or bool(no_e_puck and _IMPORTS_E_PUCKS.search(text))


def _own_robot(summary: dict[str, Any], controller: str) -> dict[str, Any]:
    """The entry of a whole world's summary of the robot that ran ``controller`` (the first
    robot when none did)."""
    robots = [r for r in summary.get("robots") or [] if isinstance(r, dict)]
    for robot in robots:
        if Path(str(robot.get("controller") or "")).name == Path(controller).name:
            return robot
    return robots[0] if robots else {}


def _trajectory(path: Path, robot: str | None = None) -> np.ndarray:
    if not path.is_file():
        return np.zeros((0, 2))
    with path.open(encoding="utf-8") as handle:
        rows = [
            (float(r["x_m"]), float(r["y_m"]))
            for r in csv.DictReader(handle)
            if robot is None or r.get("robot") == robot
        ]
    return np.array(rows, dtype=np.float64).reshape(-1, 2)


def _robots_moving(summary: dict[str, Any], trajectory: Path) -> int | None:
    """How many of a whole world's robots moved: travelled more than 5 cm, or were put more
    than 5 cm from their start by a supervisor (a body a controller slides by its own
    ``translation`` moves in Webots too, though it travels nothing on its wheels)."""
    robots = summary.get("robots")
    if not isinstance(robots, list):
        return None
    moving = 0
    for robot in robots:
        if not isinstance(robot, dict):
            continue
        if float(robot.get("distance_m", 0)) > MOVED:
            moving += 1
        elif robot.get("name") is not None:
            path = _trajectory(trajectory, str(robot["name"]))
            moving += int(farthest_from_start(path) > MOVED)
    return moving


def _significant(warnings: list[str]) -> list[str]:
    """The warnings that say something of the world was lost (without the list of known PROTOs
    some of them end with)."""
    lost = [w for w in warnings if any(word in w.lower() for word in LOST_WORDS)]
    return [re.sub(r" \(known PROTOs: [^)]*\)", "", w) for w in lost]


@dataclass
class RunResult:
    """What ``mazesim webots run`` left: its exit status (None when it was stopped for taking
    too long), its standard output and the last error line of its standard error."""

    exit_status: int | None
    stdout: str
    last_error: str
    failure: str = ""


def _last_error(stderr: str) -> str:
    lines = [line.strip() for line in stderr.splitlines() if line.strip()]
    errors = [line for line in lines if re.match(r"^[\w.]*(Error|Exception)\b", line)]
    return errors[-1] if errors else ""


def _build_first(project: Project, root: Path) -> None:
    """Builds the project's C and C++ controllers into the build cache the run then takes them
    from, so that the run's wall-clock limit measures the simulation, not the compiler (a
    controller that does not build says so again in the run)."""
    from mazesim.errors import MazesimError
    from mazesim.webots.native_controller import build

    for controller in project.controllers:
        if Path(controller).suffix.lower() in (".c", ".cpp", ".cc", ".cxx"):
            try:
                build(root / controller)
            except MazesimError:
                pass


def _run(project: Project, root: Path, world: Path, out: Path, whole: bool) -> RunResult:
    """Runs the project's first controller, or the whole world."""
    _build_first(project, root)
    command = [
        sys.executable, "-m", "mazesim", "webots", "run", str(root / project.controllers[0]),
        "--world", str(world), "--seconds", f"{project.seconds:g}", "--out", str(out),
    ]  # fmt: skip
    if whole:
        command = [
            sys.executable, "-m", "mazesim", "webots", "run", str(world),
            "--seconds", f"{project.seconds:g}", "--out", str(out),
        ]  # fmt: skip
    if project.keys:
        keys = out.parent / "keys.txt"
        keys.write_text("\n".join(project.keys) + "\n", encoding="utf-8")
        command += ["--keys", str(keys)]
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONDONTWRITEBYTECODE="1")
    process = subprocess.Popen(
        command,
        cwd=root,
        env=env,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        start_new_session=True,
    )
    status: int | None
    try:
        stdout, stderr = process.communicate(timeout=project.seconds + GRACE_S)
        status = process.returncode
    except subprocess.TimeoutExpired:
        # Ctrl-C first: the run then writes its summary and trajectory as far as it got.
        os.killpg(process.pid, signal.SIGINT)
        try:
            stdout, stderr = process.communicate(timeout=INTERRUPT_GRACE_S)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            stdout, stderr = process.communicate()
        status = None
    except BaseException:  # interrupted: the run's own session would outlive the runner
        os.killpg(process.pid, signal.SIGKILL)
        raise
    text = stderr.decode("utf-8", "replace")
    failures = [line for line in text.splitlines() if line.startswith("mazesim: error: ")]
    failure = failures[-1].removeprefix("mazesim: error: ") if failures else ""
    return RunResult(status, stdout.decode("utf-8", "replace"), _last_error(text), failure)


def run_project(project: Project, mirrors: Path, work: Path, census: Census) -> Row:
    """Exports, imports, runs and checks one project (and counts its world in the census)."""
    started = time.monotonic()
    row = _run_project(project, mirrors, work, census)
    row.wall_s = time.monotonic() - started
    # Paths in the project's temporary export are named from the project's root, so that a
    # cause reads the same from one run to the next.
    root = work / project.name.replace("/", "+")
    row.cause = row.cause.replace(f"{root}{os.sep}", "")
    return row


def _run_project(project: Project, mirrors: Path, work: Path, census: Census) -> Row:
    git_dir = find_mirror(mirrors, project.repo)
    if git_dir is None:
        return Row(project, "skipped", f"no mirror of {project.repo} in {mirrors}")
    if not has_commit(git_dir, project.commit):
        return Row(project, "skipped", f"the mirror lacks commit {project.commit[:12]}")
    root = work / project.name.replace("/", "+")
    folders = [project.root, *(str(Path(c).parent) for c in project.controllers)]
    folders += list(project.exports)
    try:
        export(git_dir, project.commit, ["" if f == "." else f for f in folders], root)
        text = read_file(git_dir, project.commit, project.world).decode("utf-8", "replace")
    except MirrorError as error:
        return Row(project, "error", str(error))
    world = root / project.world
    controller = Path(project.controllers[0]).stem
    try:
        world_obj, report = _import(world, controller)
    except Exception as error:  # noqa: BLE001 - any import failure is the row's result
        census.add(f"{project.repo}:{project.world}", text, set(), set())
        if project.broken:
            return Row(project, "broken itself", project.broken)
        message = str(error).replace(f"{root}{os.sep}", "")
        return Row(project, "error", f"import: {type(error).__name__}: {message}")
    warnings = list(report.get("warnings", []))
    if project.language != "python" and project.broken:
        census.add(f"{project.repo}:{project.world}", text, *losses(warnings))
        return Row(project, "broken itself", project.broken, warnings=warnings)
    out = root.parent / f"{root.name}.out"
    whole = _runs_whole(project, report, text)
    run = _run(project, root, world, out, whole)
    summary: dict[str, Any] = {}
    if (out / "summary.json").is_file():
        summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    own: str | None = None
    exit_status = run.exit_status
    others = ""
    if whole:
        # The facts are the robot's that runs the project's first controller; the others'
        # failures are said in the cause.
        robot = _own_robot(summary, project.controllers[0])
        own = robot.get("name")
        summary["controller_error"] = robot.get("controller_error")
        if exit_status is not None:
            exit_status = int(robot.get("exit_status") or 0)
        failed = [r for r in summary.get("robots") or [] if r is not robot and r.get("exit_status")]
        if failed:
            first = failed[0]
            why = first.get("controller_error") or f"exit status {first.get('exit_status')}"
            others = f"robot {first.get('name')}: {why}"
    dropped, stood_in = losses(warnings, summary)
    census.add(f"{project.repo}:{project.world}", text, dropped, stood_in)
    if not summary and run.exit_status is not None and run.failure:
        # The run stopped before simulating (a controller that does not compile...).
        return Row(project, "error", f"run: {run.failure[:400]}", warnings=warnings)
    boxes = np.asarray(world_obj.wall_boxes(), dtype=np.float64).reshape(-1, 6)[:, :5]
    outcome = Outcome(
        exit_status=exit_status,
        error=str(summary.get("controller_error") or ""),
        stdout=run.stdout,
        path=_trajectory(out / "trajectory.csv", own),
        walls=boxes,
        floor=world_obj.floor_reflectance,
        robots_moving=_robots_moving(summary, out / "trajectory.csv"),
        wall_count=len(report.get("obstacles", [])),
    )
    checks = []
    for line in project.expect:
        ok, measured = check(parse_fact(line), outcome)
        checks.append((line, ok, measured))
    missing = [str(m) for m in summary.get("missing_features") or []]
    if whole:  # what the robot of the project's first controller lacks, as its run said
        missing = _world_missing(summary, robot)
    return _judge(project, checks, warnings, outcome, run, missing, others)


def _world_missing(summary: dict[str, Any], own: dict[str, Any]) -> list[str]:
    """What a whole world's run said at its start that the robot of the project's first
    controller lacks, else what the other robots' controllers lack (those robots then stand
    still, which the facts about the world's robots see), each statement once with the robots
    it concerns."""
    missing = [str(m) for m in own.get("missing_features") or []]
    if missing:
        return missing
    robots: dict[str, list[str]] = {}
    for other in summary.get("robots") or []:
        if isinstance(other, dict) and other is not own:
            for statement in other.get("missing_features") or []:
                names = robots.setdefault(str(statement), [])
                if str(other.get("name")) not in names:
                    names.append(str(other.get("name")))
    return [f"robot {', '.join(names)}: {statement}" for statement, names in robots.items()]


def _names_texture(statement: str, warning: str) -> bool:
    """Whether a run's missing-feature statement names the floor texture an import warning is
    about (the texture's URL in both)."""
    found = re.search(r"the floor texture (\S+), which", statement)
    return found is not None and f"{found.group(1)}:" in warning


def _judge(
    project: Project,
    checks: list[tuple[str, bool, str]],
    warnings: list[str],
    outcome: Outcome,
    run: RunResult,
    missing: list[str],
    others: str = "",
) -> Row:
    """The row of a run: pass, fail or timeout, or not run when the run said at its start what
    it lacks (its statement is the cause, so the table and the run agree), as it does of a
    first controller in a language mazesim does not run, whatever the facts."""
    failed = [f"{line} ({measured})" for line, ok, measured in checks if not ok]
    parts: list[str] = []
    unrun = project.language not in RUN
    if missing and (failed or run.exit_status is None or unrun):
        # A floor texture the run names as missing is not quoted again from the import.
        lost = [w for w in _significant(warnings) if not any(_names_texture(m, w) for m in missing)]
        cause = "missing: " + "; ".join(missing) + (f"; import: {lost[0]}" if lost else "")
        result = "broken itself" if project.broken else "not run"
        return Row(project, result, project.broken or cause, checks, warnings)
    stopped = run.exit_status is None
    if project.alone:
        parts.append(f"its first controller alone: {project.alone}")
    if stopped:
        parts.append(f"stopped after {project.seconds + GRACE_S:.0f} s of wall-clock time")
        if run.last_error:
            parts.append(f"its last error: {run.last_error}")
    if outcome.error:
        parts.append(f"controller: {outcome.error}")
    if others:
        parts.append(f"another controller failed: {others}")
    if failed:
        parts.append("expected " + "; ".join(failed))
    lost = _significant(warnings)
    if lost:
        parts.append(f"import: {lost[0]}" + (f" (+{len(lost) - 1} more)" if len(lost) > 1 else ""))
    if project.broken:
        return Row(project, "broken itself", project.broken, checks, warnings)
    result = "pass" if not failed and not stopped else ("timeout" if stopped else "fail")
    if result != "pass" and project.known:
        parts.append(f"known: {project.known}")
    return Row(project, result, "; ".join(parts), checks, warnings)
