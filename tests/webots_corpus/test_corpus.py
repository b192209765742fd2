"""The compatibility corpus's manifest has its documented shape, and its runner's export, run,
fact checks, census and page work on a tiny project written here (a local git repository: no
network, no mirror of the corpus)."""

from __future__ import annotations

import math
import re
import shutil
import subprocess
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from webots_corpus.census import Census, losses, proto_instances
from webots_corpus.facts import Outcome, check, dark_fraction, min_gap, parse_fact
from webots_corpus.manifest import ManifestError, Project, load_manifest, parse_manifest
from webots_corpus.report import render
from webots_corpus.runner import _robots_moving, _runs_whole, _world_missing, run_project

DATA = Path(__file__).resolve().parents[1] / "data" / "webots_corpus"
COMMIT = "0123456789abcdef0123456789abcdef01234567"
PROJECT_TOML = f"""
[[project]]
name = "someone/demo"
repo = "someone/demo"
commit = "{COMMIT}"
world = "worlds/demo.wbt"
controllers = ["controllers/demo/demo.py"]
language = "python"
does = "drives"
seconds = 10
expect = ["exit 0", "travels 0.5"]
broken = ""
"""


def test_the_manifest_has_enough_projects_from_enough_repositories() -> None:
    projects = load_manifest()
    assert len(projects) >= 40
    assert len({p.repo for p in projects}) >= 25
    assert sum(p.language == "python" for p in projects) >= 25
    for project in projects:
        assert len(project.commit) == 40 and int(project.commit, 16) >= 0
        assert project.world.endswith(".wbt") and project.controllers and project.does
        assert project.broken or project.expect, project.name
        assert all(parse_fact(fact) for fact in project.expect)


def test_a_broken_field_is_required_and_facts_must_parse() -> None:
    assert parse_manifest(PROJECT_TOML)[0].expect == ("exit 0", "travels 0.5")
    cases = {
        'broken = ""\n': "expected the field 'broken'",
        f'commit = "{COMMIT}"': "expected commit 40 hex digits",
        '"travels 0.5"': "expected a number after travels",
        'language = "python"': "expected language in",
        "seconds = 10": "expected seconds in (0, 120]",
    }
    replacements = {
        'broken = ""\n': "",
        f'commit = "{COMMIT}"': 'commit = "abc123"',
        '"travels 0.5"': '"travels far"',
        'language = "python"': 'language = "fortran"',
        "seconds = 10": "seconds = 0",
    }
    for old, message in cases.items():
        with pytest.raises(ManifestError, match=re.escape(message)):
            parse_manifest(PROJECT_TOML.replace(old, replacements[old]))
    with pytest.raises(ManifestError, match="found twice"):
        parse_manifest(PROJECT_TOML + PROJECT_TOML)
    # Paths a project's build needs besides its folders: "" is the whole repository.
    exported = parse_manifest(
        PROJECT_TOML.replace('broken = ""\n', 'broken = ""\nexports = [""]\n')
    )
    assert exported[0].exports == ("",)
    with pytest.raises(ManifestError, match="expected exports a list of paths"):
        parse_manifest(PROJECT_TOML.replace('broken = ""\n', 'broken = ""\nexports = "src"\n'))


def _outcome(path: list[tuple[float, float]], **overrides: Any) -> Outcome:
    base = Outcome(
        exit_status=0,
        error="",
        stdout="ready\n",
        path=np.array(path, dtype=np.float64),
        walls=np.array([[0.5, 0.0, 0.02, 1.0, 0.0]]),  # a wall along x = 0.5
        floor=lambda x, y: 0.1 if abs(y) < 0.01 else 0.9,  # a dark line along y = 0
        wall_count=1,
    )
    return replace(base, **overrides)


def test_facts_measure_the_path_the_walls_and_the_floor() -> None:
    straight = _outcome([(0.0, 0.0), (0.1, 0.0), (0.2, 0.0), (0.3, 0.0)])
    assert check(parse_fact("travels 0.25"), straight) == (True, "travelled 0.30 m")
    assert not check(parse_fact("travels 0.35"), straight)[0]
    assert check(parse_fact("leaves_start 0.29"), straight)[0]
    assert not check(parse_fact("stays_near 0.2"), straight)[0]
    # The body (radius 0.037) is 0.5 - 0.01 - 0.3 - 0.037 = 0.153 m from the wall at its closest.
    assert math.isclose(min_gap(straight.path, straight.walls, 0.037), 0.153, abs_tol=1e-9)
    assert check(parse_fact("clearance 0.15"), straight)[0]
    assert not check(parse_fact("clearance 0.16"), straight)[0]
    touching = _outcome([(0.46, 0.0)])  # 0.49 - 0.46 < 0.037: inside the wall
    assert not check(parse_fact("clearance 0"), touching)[0]
    assert dark_fraction(straight.path, straight.floor) == 1.0
    off_line = _outcome([(0.0, 0.0), (0.0, 0.1), (0.0, 0.2), (0.0, 0.3)])
    assert check(parse_fact("on_dark 0.25"), off_line) == (True, "on dark floor 25% of steps")
    assert not check(parse_fact("on_dark 0.3"), off_line)[0]
    assert check(parse_fact("prints ready"), straight)[0]
    assert not check(parse_fact("prints steady"), straight)[0]
    assert not check(parse_fact("exit 0"), _outcome([], exit_status=1))[0]
    failed = _outcome([], error="ZeroDivisionError: division by zero")
    assert check(parse_fact("no_error"), failed) == (False, f"error: {failed.error}")
    assert check(parse_fact("robots 1"), straight)[0]
    assert not check(parse_fact("robots 2"), straight)[0]
    assert check(parse_fact("robots 2"), replace(straight, robots_moving=2))[0]
    with pytest.raises(ValueError, match="expected a kind among"):
        parse_fact("flies 2")


def test_the_census_finds_proto_instances_and_what_the_import_lost() -> None:
    text = (DATA / "worlds" / "corner.wbt").read_text(encoding="utf-8")
    found = [(i.type_name, i.line) for i in proto_instances(text)]
    assert found == [("RectangleArena", 5), ("WoodenBox", 6), ("Mystery", 7), ("E-puck", 8)]
    nested = 'Robot { children [ Gadget { slot [ Part { } ] } ] }\n"Fake {" # Comment {\n'
    assert [(i.type_name, i.parent_line) for i in proto_instances(nested)] == [
        ("Gadget", None),
        ("Part", 1),
    ]
    warnings = [
        "line 7: Mystery: an unknown PROTO: not imported (known PROTOs: ...)",
        "line 6: WoodenBox: an object with physics: imported as a static obstacle",
        "line 5: RectangleArena: replaced by a stand-in of its documented geometry",
    ]
    dropped, stood_in = losses(warnings, {"dropped": [{"line": 8, "type": "E-puck"}]})
    assert (dropped, stood_in) == ({7, 8}, {5})
    census = Census()
    census.add("w", text, dropped, stood_in)
    census.add("w", text, set(), set())  # a world is counted once
    assert census.types["Mystery"].dropped == 1 and census.types["WoodenBox"].imported == 1
    assert census.types["RectangleArena"].stood_in == 1
    assert census.coverage() == 0.5


def _mirror(tmp_path: Path, extra: dict[str, str] | None = None) -> tuple[Path, str]:
    """A mirror folder holding one repository, someone/tiny, of the tiny project (and the
    ``extra`` files, by path)."""
    work = tmp_path / "src"
    shutil.copytree(DATA, work)
    for name, text in (extra or {}).items():
        (work / name).parent.mkdir(parents=True, exist_ok=True)
        (work / name).write_text(text)
    git = ["git", "-C", str(work), "-c", "user.name=t", "-c", "user.email=t@example.org"]
    subprocess.run([*git, "init", "-q"], check=True)
    subprocess.run([*git, "add", "."], check=True)
    subprocess.run([*git, "commit", "-q", "-m", "tiny"], check=True)
    commit = subprocess.run(
        [*git, "rev-parse", "HEAD"], check=True, capture_output=True, text=True
    ).stdout.strip()
    mirrors = tmp_path / "mirrors"
    (mirrors / "someone+tiny").mkdir(parents=True)
    shutil.move(str(work / ".git"), str(mirrors / "someone+tiny" / "repo.git"))
    (mirrors / "someone+tiny" / "repo.git").rename(mirrors / "someone+tiny" / "repo")
    return mirrors, commit


def test_the_runner_exports_runs_and_checks_a_project(tmp_path: Path) -> None:
    mirrors, commit = _mirror(tmp_path)
    project = Project(
        name="someone/tiny",
        repo="someone/tiny",
        commit=commit,
        world="worlds/corner.wbt",
        controllers=("controllers/forward/forward.py",),
        language="python",
        does="drives forward",
        seconds=2.0,
        expect=(
            "exit 0",
            "no_error",
            "leaves_start 0.1",
            "clearance 0",
            "walls 4",
            "prints hello corpus",
            "travels 1.0",
        ),  # fmt: skip
        broken="",
    )
    census = Census()
    work = tmp_path / "work"
    row = run_project(project, mirrors, work, census)
    # Half speed for 2 s: 3.14 rad/s * 0.0205 m * 2 s = 0.13 m, far from 1 m.
    assert row.result == "fail", row
    assert [ok for _, ok, _ in row.checks] == [True] * 6 + [False]
    assert "expected travels 1.0 (travelled 0.1" in row.cause
    assert "line 7: Mystery" in " ".join(row.warnings)
    known = run_project(replace(project, known="turns too far"), mirrors, work, Census())
    assert known.result == "fail" and known.cause.endswith("; known: turns too far")
    assert census.types["Mystery"].dropped == 1 and census.types["E-puck"].imported == 1

    passing = run_project(
        replace(project, expect=project.expect[:-1], known="turns too far"), mirrors, work, Census()
    )
    assert passing.result == "pass" and "known" not in passing.cause
    assert passing.cause.startswith("import: line 7: Mystery")  # what the import lost
    c_project = replace(
        project,
        name="someone/tiny-cpp",
        language="cpp",
        controllers=("controllers/behaviour/behaviour.cpp",),
    )
    c_row = run_project(c_project, mirrors, work, Census())
    # The cause is what the run said at its start (summary.json's missing_features).
    assert c_row.result == "not run"
    assert c_row.cause.startswith(
        "missing: Webots C++ API header(s) mazesim does not provide: webots/Microphone.hpp"
    )
    assert "; import: line 7: Mystery" in c_row.cause
    broken = run_project(replace(c_project, broken="needs a door"), mirrors, work, Census())
    assert (broken.result, broken.cause) == ("broken itself", "needs a door")
    elsewhere = run_project(replace(project, repo="someone/else"), mirrors, work, Census())
    assert (elsewhere.result, elsewhere.cause[:27]) == ("skipped", "no mirror of someone/else i")
    page = render([row, passing, elsewhere], census, "2026-01-01", "abc", 1.0)
    assert "| fail |" in page and "| pass |" in page and "| skipped |" in page
    assert "| Mystery | 1 | 1 | 0 | 0 | 1 |" in page
    assert "Coverage: 3 of 4 instances import (75%)" in page


def test_a_controller_in_a_language_mazesim_does_not_run_is_a_row_not_run(tmp_path: Path) -> None:
    """Webots' MATLAB example worlds: the manifest takes a row whose controller is MATLAB (a
    language mazesim's runner names as one it does not run), and the row is not run, its cause
    what the run says, though its e-puck standing still holds its facts; a BotStudio automaton's
    row runs (mazesim.webots.botstudio)."""
    world = 'WorldInfo { }\nRectangleArena { }\nE-puck {\n  controller "blink"\n}\n'
    mirrors, commit = _mirror(
        tmp_path,
        {
            "worlds/automaton.wbt": "#VRML_SIM R2023b utf8\n" + world,
            "controllers/blink/blink.m": "% its code\n",
            "controllers/drive/drive.bsg": (
                "#botstudio 4.0\n#e-puck\n\nS;0;forward;0;0;1;" + "2;" * 10 + "100;100;\n"
            ),
        },
    )
    toml = PROJECT_TOML.replace('language = "python"', 'language = "matlab"')
    toml = toml.replace("controllers/demo/demo.py", "controllers/blink/blink.m")
    toml = toml.replace("worlds/demo.wbt", "worlds/automaton.wbt").replace(COMMIT, commit)
    project = replace(
        parse_manifest(toml.replace("someone/demo", "someone/tiny"))[0],
        seconds=0.5,
        expect=("stays_near 0.01",),
    )
    row = run_project(project, mirrors, tmp_path / "work", Census())
    assert [ok for _, ok, _ in row.checks] == [True]
    assert (row.result, row.cause) == (
        "not run",
        "missing: a MATLAB controller controllers/blink/blink.m, which mazesim does not run",
    )
    driving = replace(
        project,
        language="botstudio",
        controllers=("controllers/drive/drive.bsg",),
        expect=("leaves_start 0.03",),
    )
    row = run_project(driving, mirrors, tmp_path / "work2", Census())
    assert (row.result, [ok for _, ok, _ in row.checks]) == ("pass", [True])


def test_a_whole_world_s_missing_features_are_its_own_robot_s_else_the_others_named() -> None:
    own = {"name": "referee", "missing_features": []}
    leader = {"name": "leader", "missing_features": ["Webots C API function(s): robot_step"]}
    follower = {"name": "follower", "missing_features": leader["missing_features"]}
    summary = {"robots": [own, leader, follower, {**follower}, {"name": "idle"}]}
    assert _world_missing(summary, own) == [
        "robot leader, follower: Webots C API function(s): robot_step"
    ]
    assert _world_missing(summary, leader) == ["Webots C API function(s): robot_step"]
    assert _world_missing({"robots": [own]}, own) == []


def test_a_project_with_a_key_script_runs_every_controller_its_world_starts() -> None:
    """A key script does not make a world of several controllers a run of its first alone:
    the whole world runs, the keys typed on every controller's Keyboard (a Pac-Man player and
    its three ghosts, a supervisor beside a keyboard-driven e-puck)."""
    project = replace(parse_manifest(PROJECT_TOML)[0], keys=("1 UP 3",))
    player = {"controller": "player", "model": "E-puck", "profile": "e-puck"}
    ghost = {**player, "controller": "ghost"}
    assert _runs_whole(project, {"robots": [player, ghost]})
    assert not _runs_whole(project, {"robots": [player, {**ghost, "controller": "<none>"}]})
    # A project whose manifest says why runs its first controller alone.
    assert not _runs_whole(replace(project, alone="too slow"), {"robots": [player, ghost]})


def test_a_robot_a_supervisor_slides_moves_though_it_travels_nothing(tmp_path: Path) -> None:
    trajectory = tmp_path / "trajectory.csv"
    rows = ["step,robot,x_m,y_m"]
    rows += [f"{i},npc,-0.25,{0.005 * i:.3f}" for i in range(20)]  # slid 9.5 cm
    rows += [f"{i},box,0.5,{0.001 * i:.3f}" for i in range(20)]  # slid 1.9 cm
    trajectory.write_text("\n".join(rows) + "\n")
    summary = {
        "robots": [
            {"name": "e-puck", "distance_m": 0.6},
            {"name": "npc", "distance_m": 0.0},
            {"name": "box", "distance_m": 0.0},
        ]
    }
    assert _robots_moving(summary, trajectory) == 2
    assert _robots_moving({}, trajectory) is None


def test_the_committed_table_holds_the_acceptance_rule() -> None:
    """docs/webots-compat.md, as the last full corpus run wrote it: every project of the
    manifest has a row that is a pass, a run that said at its start what is missing (not run,
    quoting it), broken in Webots too, or without a mirror; none times out or errs, and a row
    that fails ends with what is known of why (the manifest's ``known``), and the page's counts
    name the failures; and the PROTO census covers at least 95 % of the instances."""
    page = (Path(__file__).resolve().parents[2] / "docs" / "webots-compat.md").read_text(
        encoding="utf-8"
    )
    rows = {}
    for line in page.splitlines():
        cells = [c.strip() for c in line.strip("|").split(" | ")]
        found = re.match(r"\[([^\]]+)\]\(https://github\.com/", cells[0])
        if found and len(cells) == 4:
            rows[found.group(1)] = (cells[2], cells[3])
    assert {p.name for p in load_manifest()} <= set(rows)
    allowed = {"pass", "not run", "broken itself", "skipped"}
    unknown = {
        name: r
        for name, r in rows.items()
        if r[0] not in allowed and not (r[0] == "fail" and "known: " in r[1])
    }
    assert unknown == {}
    failures = sum(result == "fail" for result, _ in rows.values())
    assert failures == 0 or f"{failures} fail" in page
    assert all(
        cause.startswith("missing: ") for result, cause in rows.values() if result == "not run"
    )
    coverage = re.search(r"Coverage: (\d+) of (\d+) instances import", page)
    assert coverage is not None
    assert int(coverage.group(1)) >= 0.95 * int(coverage.group(2))
