"""A world's controller processes are forked from one template process that imported mazesim
once, and each behaves as a fresh process started for its controller would."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from mazesim.webots.lockstep import run_world

WORLD = """#VRML_SIM R2023b utf8
WorldInfo {
  basicTimeStep 32
}
RectangleArena {
  floorSize 2 2
}
E-puck {
  translation -0.5 0 0
  name "first"
  controller "probe"
  controllerArgs [ "alpha" "beta" ]
}
E-puck {
  translation 0 0 0
  name "second"
  controller "probe"
}
E-puck {
  translation 0.5 0 0
  name "crasher"
  controller "crasher"
}
"""

PROBE = """import atexit
import json
import os
import random
import sys

import numpy
from controller import Robot

import helper

robot = Robot()
name = robot.getName()
log = os.environ["PROBE_LOG"]
# Left open: a Python program's end flushes it.
unclosed = open(os.path.join(log, f"{name}.unclosed"), "w")
unclosed.write("flushed at the end")
atexit.register(lambda: open(os.path.join(log, f"{name}.atexit"), "w").close())
helper.COUNT += 1
steps = 0
while robot.step(32) != -1 and steps < 5:
    steps += 1
print(f"out of {name}")
print(f"err of {name}", file=sys.stderr)
with open(os.path.join(log, f"{name}.json"), "w") as file:
    json.dump(
        {
            "pid": os.getpid(),
            "parent": os.getppid(),
            "cwd": os.getcwd(),
            "argv": sys.argv,
            "path0": sys.path[0],
            "helper": helper.COUNT,
            "random": random.random(),
            "numpy_random": float(numpy.random.random()),
            "webots_home": "WEBOTS_HOME" in os.environ,
            "steps": steps,
        },
        file,
    )
"""

CRASHER = """import os

from controller import Robot

robot = Robot()
robot.step(32)
os._exit(7)
"""


@pytest.fixture(scope="module")
def probed(tmp_path_factory: pytest.TempPathFactory) -> tuple[object, Path, Path]:
    project = tmp_path_factory.mktemp("template")
    (project / "worlds").mkdir()
    (project / "worlds" / "probe.wbt").write_text(WORLD)
    probe = project / "controllers" / "probe"
    probe.mkdir(parents=True)
    (probe / "probe.py").write_text(PROBE)
    (probe / "helper.py").write_text("COUNT = 0\n")
    (project / "controllers" / "crasher").mkdir()
    (project / "controllers" / "crasher" / "crasher.py").write_text(CRASHER)
    log = tmp_path_factory.mktemp("probe-log")
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("PROBE_LOG", str(log))
        run = run_world(str(project / "worlds" / "probe.wbt"), seconds=1.0, noise=False)
    return run, log, probe


def _probes(log: Path) -> list[dict[str, object]]:
    return [json.loads((log / f"{name}.json").read_text()) for name in ("first", "second")]


def test_every_controller_process_is_forked_from_one_template(
    probed: tuple[object, Path, Path],
) -> None:
    _, log, _ = probed
    first, second = _probes(log)
    assert first["pid"] != second["pid"]
    assert first["parent"] == second["parent"], "both forked by the same template"
    assert first["parent"] != os.getpid(), "not started by the world's process itself"
    # The template has ended with the run.
    with pytest.raises(ProcessLookupError):
        os.kill(int(str(first["parent"])), 0)


def test_each_child_runs_its_controller_as_a_fresh_process_would(
    probed: tuple[object, Path, Path],
) -> None:
    run, log, probe = probed
    first, second = _probes(log)
    for seen in (first, second):
        assert seen["cwd"] == str(probe)
        assert seen["path0"] == str(probe)
        assert seen["helper"] == 1, "module-level state is each process's own"
        assert seen["webots_home"] is True
        assert seen["steps"] == 5
    assert first["argv"] == [str(probe / "probe.py"), "alpha", "beta"]
    assert second["argv"] == [str(probe / "probe.py")]
    # Random streams of their own, as fresh processes have.
    assert first["random"] != second["random"]
    assert first["numpy_random"] != second["numpy_random"]
    assert [r.exit_status for r in run.robots[:2]] == [0, 0]  # type: ignore[attr-defined]


def test_a_child_ends_as_a_python_program_ends(probed: tuple[object, Path, Path]) -> None:
    """Its atexit functions run and its open files are flushed before the run returns."""
    _, log, _ = probed
    for name in ("first", "second"):
        assert (log / f"{name}.atexit").exists()
        assert (log / f"{name}.unclosed").read_text() == "flushed at the end"


def test_a_child_that_dies_is_reported_and_the_others_go_on(
    probed: tuple[object, Path, Path],
) -> None:
    run, _, _ = probed
    crasher = run.robots[2]  # type: ignore[attr-defined]
    assert crasher.exit_status == 7, "its os._exit status"
    assert crasher.error.startswith("the Python controller's process exited with status 7 without")
    assert run.steps == 6  # type: ignore[attr-defined]


def test_controllers_print_on_the_worlds_own_output_unprefixed(
    tmp_path: Path, capfd: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """Each controller's lines come whole, even unbuffered and printing at the same time."""
    monkeypatch.setenv("PYTHONUNBUFFERED", "1")
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "w.wbt").write_text(WORLD.split("E-puck {")[0] + WORLD_ONE)
    (tmp_path / "controllers" / "talker").mkdir(parents=True)
    (tmp_path / "controllers" / "talker" / "talker.py").write_text(TALKER.replace("LINES", "50"))
    run = run_world(str(tmp_path / "worlds" / "w.wbt"), seconds=0.1, noise=False)
    assert [r.exit_status for r in run.robots] == [0, 0]
    out, err = capfd.readouterr()
    lines = 50 * ["one talks"] + 50 * ["two talks"]
    assert sorted(line for line in out.splitlines() if "talks" in line) == lines
    warnings = [line.replace("talks", "warns") for line in lines]
    assert sorted(line for line in err.splitlines() if "warns" in line) == warnings


WORLD_ONE = """E-puck {
  translation -0.5 0 0
  name "one"
  controller "talker"
}
E-puck {
  translation 0.5 0 0
  name "two"
  controller "talker"
}
"""

TALKER = """import sys

from controller import Robot

robot = Robot()
robot.step(32)
for _ in range(LINES):
    print(robot.getName(), "talks")
    print(robot.getName(), "warns", file=sys.stderr)
"""


PRELOADED_RUN = """import sys

from mazesim.webots.process_template import _preload

_preload()
before = set(sys.modules)
from mazesim.webots.importer import import_wbt
from mazesim.webots.runner import run_controller
from mazesim.webots.scene import read_scene

world, report = import_wbt(sys.argv[1])
with open(sys.argv[1], encoding="utf-8") as file:
    scene = read_scene(file.read(), report.get("robot_model"), report.get("robot_line"))
run = run_controller(sys.argv[2], world, seconds=0.1, report=dict(report), scene=scene)
print(run.exit_status, sorted(m for m in set(sys.modules) - before if m.startswith("mazesim")))
"""


def test_the_template_has_imported_every_module_a_controller_run_takes(tmp_path: Path) -> None:
    """A child imports none of mazesim's modules itself (the world import's PROTO engine, which
    it imports when first called, included): a controller's run after the template's imports
    adds none."""
    (tmp_path / "worlds").mkdir()
    world = tmp_path / "worlds" / "w.wbt"
    world.write_text(WORLD.split("E-puck {")[0] + WORLD_ONE)
    controller = tmp_path / "controllers" / "talker" / "talker.py"
    controller.parent.mkdir(parents=True)
    controller.write_text(TALKER.replace("LINES", "1"))
    done = subprocess.run(
        [sys.executable, "-c", PRELOADED_RUN, str(world), str(controller)],
        capture_output=True,
        text=True,
        check=True,
    )
    assert done.stdout.splitlines()[-1] == "0 []", done.stderr
