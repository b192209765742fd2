"""A controller that makes a ``Supervisor`` for a robot whose world node leaves ``supervisor``
FALSE has no supervisor powers, as in Webots: each supervisor function prints libController's
two error lines and answers as it does without a supervisor (#32, #33)."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import pytest
from test_webots_supervisor_tree import supervisor_of

import mazesim
from mazesim.webots import controller, prepare
from native_controllers import NEEDS_COMPILERS

#: An E-puck that leaves ``supervisor`` FALSE, and a box it could look up by its DEF name.
PLAIN = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 1 1 }
DEF GOAL Solid {
  translation 0.3 0.2 0.05
  children [ Shape { geometry DEF G Box { size 0.05 0.05 0.1 } } ]
  boundingObject USE G
}
DEF ME E-puck { translation -0.2 -0.1 0 controller "seeker" }
"""
#: The same world whose E-puck is a supervisor.
GRANTED = PLAIN.replace('controller "seeker"', 'controller "seeker" supervisor TRUE')

pytestmark = pytest.mark.usefixtures("fresh_robot")


def test_a_plain_robots_supervisor_finds_no_node_and_says_why(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    supervisor = supervisor_of(PLAIN, tmp_path)
    assert supervisor.getFromDef("GOAL") is None
    me = supervisor.getSelf()
    assert me is not None
    position = me.getPosition()
    assert len(position) == 3 and all(math.isnan(v) for v in position)
    assert me.getField("translation") is None
    assert supervisor.getSupervisor() is False
    errors = capsys.readouterr().err.splitlines()
    assert errors[:2] == [
        "Error: ignoring illegal call to wb_supervisor_node_get_from_def() in a 'Robot' "
        "controller.",
        "Error: this function can only be used in a 'Supervisor' controller.",
    ]
    assert "wb_supervisor_node_get_position()" in errors[4]
    assert "wb_supervisor_node_get_field()" in errors[6]


def test_a_plain_robots_supervisor_cannot_move_it_or_reset_the_world(tmp_path: Path) -> None:
    supervisor = supervisor_of(PLAIN, tmp_path)
    timestep = int(supervisor.getBasicTimeStep())
    supervisor.getSelf().getField("translation")  # None: nothing to set
    supervisor.simulationReset()
    supervisor.simulationQuit(3)
    assert supervisor.step(timestep) == 0
    assert supervisor._simulation.quit_status is None


def test_a_robot_the_world_makes_a_supervisor_keeps_its_powers(tmp_path: Path) -> None:
    supervisor = supervisor_of(GRANTED, tmp_path)
    goal = supervisor.getFromDef("GOAL")
    assert goal is not None and goal.getPosition()[:2] == pytest.approx([0.3, 0.2])
    assert supervisor.getSelf().getPosition()[:2] == pytest.approx([-0.2, -0.1])
    assert supervisor.getSupervisor() is True


def test_a_robot_of_a_mazesim_world_keeps_the_powers_its_controller_asks_for() -> None:
    """A mazesim world has no supervisor field to refuse them by."""
    prepare(mazesim.load_world("arena"), seconds=1.0, noise=False)
    controller.Robot.created = None
    supervisor = controller.Supervisor()
    assert supervisor.getSelf().getPosition() is not None
    assert not math.isnan(supervisor.getSelf().getPosition()[0])
    assert supervisor.getSupervisor() is True


def run_seeker(
    tmp_path: Path, world: str, source: str, suffix: str
) -> subprocess.CompletedProcess[str]:
    """``mazesim webots run`` of the seeker controller ``source`` on ``world``."""
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "seek.wbt").write_text(world)
    folder = tmp_path / "controllers" / "seeker"
    folder.mkdir(parents=True)
    (folder / f"seeker{suffix}").write_text(source)
    return subprocess.run(
        [sys.executable, "-m", "mazesim", "webots", "run", str(folder / f"seeker{suffix}"),
         "--world", str(tmp_path / "worlds" / "seek.wbt"), "--seconds", "0.2",
         "--out", str(tmp_path / "out"), "--no-progress"],
        capture_output=True, text=True, timeout=300, check=False,
    )  # fmt: skip


@pytest.mark.parametrize(("world", "ends"), [(PLAIN, "refused"), (GRANTED, "found")])
def test_a_run_of_a_plain_robots_supervisor_prints_webots_refusal(
    tmp_path: Path, world: str, ends: str
) -> None:
    """``mazesim webots run``: the controller's look-up by DEF name gives None, with Webots'
    lines on stderr, unless the world makes its robot a supervisor."""
    source = (
        "from controller import Supervisor\n"
        "s = Supervisor()\n"
        "s.step(32)\n"
        "print('found' if s.getFromDef('GOAL') is not None else 'refused')\n"
    )
    done = run_seeker(tmp_path, world, source, ".py")
    assert done.returncode == 0, done.stderr
    assert ends in done.stdout.splitlines()
    refusal = "in a 'Robot' controller." in done.stderr
    assert refusal is (ends == "refused")


@NEEDS_COMPILERS
@pytest.mark.usefixtures("own_cache")
@pytest.mark.parametrize(("world", "ends"), [(PLAIN, "refused"), (GRANTED, "found")])
def test_a_c_controller_of_a_plain_robot_is_refused_the_supervisor_functions(
    tmp_path: Path, world: str, ends: str
) -> None:
    """The C library serves a compiled controller's supervisor functions as Webots' does:
    NULL, with Webots' lines, unless the world makes its robot a supervisor."""
    done = run_seeker(
        tmp_path,
        world,
        "#include <stdio.h>\n#include <webots/robot.h>\n#include <webots/supervisor.h>\n"
        "int main() {\n  wb_robot_init();\n  wb_robot_step(32);\n"
        '  printf("%s\\n", wb_supervisor_node_get_from_def("GOAL") ? "found" : "refused");\n'
        "  wb_robot_cleanup();\n  return 0;\n}\n",
        ".c",
    )
    assert done.returncode == 0, done.stderr
    assert ends in done.stdout.splitlines()
    refusal = "ignoring illegal call to wb_supervisor_node_get_from_def()" in done.stderr
    assert refusal is (ends == "refused")


@NEEDS_COMPILERS
@pytest.mark.usefixtures("own_cache")
def test_a_c_controllers_vector_of_no_node_is_webots_nans_not_null(tmp_path: Path) -> None:
    """Webots' node getters give a vector of NaNs for a NULL node (libController's
    ``invalid_vector``), never NULL: a course supervisor that looks twenty boxes up by DEF names
    its world gives two of reads NaN for the others and goes on, where it crashed on NULL."""
    getters = {
        "position": "wb_supervisor_node_get_position(missing)[2]",
        "orientation": "wb_supervisor_node_get_orientation(missing)[8]",
        "pose": "wb_supervisor_node_get_pose(missing, NULL)[15]",
        "centre": "wb_supervisor_node_get_center_of_mass(missing)[2]",
        "velocity": "wb_supervisor_node_get_velocity(missing)[5]",
    }
    reads = "".join(
        f'  printf("{name} %s\\n", isnan({call}) ? "nan" : "number");\n'
        for name, call in getters.items()
    )
    done = run_seeker(
        tmp_path,
        GRANTED,
        "#include <math.h>\n#include <stdio.h>\n#include <webots/robot.h>\n"
        "#include <webots/supervisor.h>\n"
        "int main() {\n  wb_robot_init();\n  wb_robot_step(32);\n"
        '  WbNodeRef missing = wb_supervisor_node_get_from_def("NOWHERE");\n'
        f"{reads}"
        '  WbNodeRef box = wb_supervisor_node_get_from_def("GOAL");\n'
        "  const double *goal = wb_supervisor_node_get_position(box);\n"
        '  printf("goal %.2f %.2f\\n", goal[0], goal[1]);\n'
        "  wb_robot_cleanup();\n  return 0;\n}\n",
        ".c",
    )
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    read = [line for line in lines if line.split(" ")[0] in getters]
    assert read == [f"{name} nan" for name in getters]
    assert "goal 0.30 0.20" in lines
    assert "called with a NULL" in done.stderr
