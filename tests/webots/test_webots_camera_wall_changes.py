"""A camera follows the walls a supervisor changes, in a run of one controller and in a world
run, whichever robot's controller changes them; the live window of a world run draws them where
they are now (#32, #33)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest

from mazesim.webots.lockstep import run_world
from supervised_world import colour_share, project_of, supervisor_in

#: A red wall 0.15 m ahead of an e-puck "watcher" facing +x, and a second e-puck far away.
WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 2 2 }
DEF GATE Solid {
  translation 0.15 0 0.05
  children [
    Shape {
      appearance PBRAppearance { baseColor 1 0 0 }
      geometry DEF GATE_BOX Box { size 0.02 0.3 0.1 }
    }
  ]
  name "gate"
  boundingObject USE GATE_BOX
}
E-puck { translation 0 0 0 name "watcher" controller "WATCHER" supervisor TRUE }
E-puck { translation -0.6 -0.6 0 name "mover" controller "MOVER" supervisor TRUE }
"""

#: A green wall imported 0.15 m ahead of the watcher.
GREEN_WALL = (
    "Solid { translation 0.15 0 0.05 children [ Shape { appearance PBRAppearance { "
    'baseColor 0 1 0 } geometry DEF G Box { size 0.02 0.3 0.1 } } ] name \\"green\\" '
    "boundingObject USE G }"
)

#: What the mover does at its fifth step, by name.
CHANGES = {
    "move": 'robot.getFromDef("GATE").getField("translation").setSFVec3f([0.8, 0.8, 0.05])',
    "remove": 'robot.getFromDef("GATE").remove()',
    "import": (
        'robot.getFromDef("GATE").remove()\n'
        f'robot.getRoot().getField("children").importMFNodeFromString(-1, "{GREEN_WALL}")'
    ),
}

#: Records, at each step, the shares of the watcher's image in the wall's red and green.
WATCHER = """from controller import Supervisor

robot = Supervisor()
camera = robot.getDevice("camera")
camera.enable(32)
red = round(255 * 0.8)
with open(OUT, "w") as out:
    for _ in range(12):
        robot.step(32)
        image = camera.getImage()
        pixels = [image[i:i + 3] for i in range(0, len(image), 4)]
        reds = sum(1 for b, g, r in pixels if (r, g, b) == (red, 0, 0))
        greens = sum(1 for b, g, r in pixels if (r, g, b) == (0, red, 0))
        out.write(f"{reds / len(pixels)} {greens / len(pixels)}\\n")
"""

MOVER = """from controller import Supervisor

robot = Supervisor()
for _ in range(4):
    robot.step(32)
CHANGE
for _ in range(10):
    robot.step(32)
"""


def _shares(path: Path) -> list[tuple[float, float]]:
    lines = path.read_text().split()
    return [(float(a), float(b)) for a, b in zip(lines[::2], lines[1::2])]


def _project(tmp_path: Path, watcher: str, mover: str) -> Path:
    """A project of :data:`WORLD` with these two controllers; its world file."""
    text = WORLD.replace("WATCHER", "watcher").replace("MOVER", "mover")
    return project_of(tmp_path, "gate.wbt", text, {"watcher": watcher, "mover": mover})


@pytest.mark.parametrize("change", sorted(CHANGES))
def test_a_world_runs_camera_follows_another_robots_wall_changes(
    tmp_path: Path, change: str
) -> None:
    out = tmp_path / "shares.txt"
    watcher = WATCHER.replace("OUT", repr(str(out)))
    world = _project(tmp_path, watcher, MOVER.replace("CHANGE", CHANGES[change]))
    run = run_world(str(world), seconds=1.0, seed=1)
    assert [robot.exit_status for robot in run.robots] == [0, 0], run.robots
    shares = _shares(out)
    assert len(shares) == 12
    # The red wall fills the middle of the image until the mover's change.
    assert all(red > 0.2 for red, _ in shares[1:4]), shares
    assert all(red == 0.0 for red, _ in shares[6:]), shares
    green = change == "import"
    assert all((g > 0.2) == green for _, g in shares[6:]), shares


def test_a_world_runs_camera_follows_its_own_supervisors_wall_move(tmp_path: Path) -> None:
    out = tmp_path / "shares.txt"
    own = WATCHER.replace("OUT", repr(str(out))).replace(
        "        robot.step(32)\n",
        "        robot.step(32)\n        if _ == 4:\n            " + CHANGES["move"] + "\n",
    )
    world = _project(tmp_path, own, "from controller import Robot\nRobot().step(32)\n")
    run = run_world(str(world), seconds=1.0, seed=1)
    assert run.robots[0].exit_status == 0, run.robots[0].error
    shares = _shares(out)
    assert all(red > 0.2 for red, _ in shares[1:4]) and all(r == 0.0 for r, _ in shares[6:])


def test_a_camera_alone_in_its_world_follows_a_wall_its_supervisor_moves(tmp_path: Path) -> None:
    text = WORLD.replace(
        'E-puck { translation -0.6 -0.6 0 name "mover" controller "MOVER" supervisor TRUE }\n', ""
    ).replace('controller "WATCHER"', 'controller "<extern>"')
    supervisor = supervisor_in(tmp_path, text)
    camera = supervisor.getDevice("camera")
    camera.enable(32)
    red = (round(255 * 0.8), 0, 0)
    supervisor.step(32)
    assert colour_share(camera, red) > 0.2
    supervisor.getFromDef("GATE").getField("translation").setSFVec3f([0.8, 0.8, 0.05])
    supervisor.step(32)
    assert colour_share(camera, red) == 0.0


def test_the_live_window_of_a_world_run_draws_the_walls_where_a_supervisor_moved_them(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from mazesim.cli.webots_world import WorldWatch

    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    still = "from controller import Robot\nrobot = Robot()\nwhile robot.step(32) != -1:\n    pass\n"
    world = _project(tmp_path, still, MOVER.replace("CHANGE", CHANGES["move"]))
    watch = WorldWatch(1, record=False, live=True)
    gates: list[tuple[float, float]] = []

    def observe(*state: Any) -> None:
        watch(*state)
        boxes = np.asarray(watch.view.world.wall_boxes()).reshape(-1, 6)
        (gate,) = [b for b in boxes if np.allclose(sorted(b[2:4]), (0.02, 0.3))]
        gates.append((round(float(gate[0]), 3), round(float(gate[1]), 3)))

    run_world(str(world), seconds=0.5, seed=1, observer=observe)
    # The window draws the gate where the file has it, then where the mover put it.
    assert gates[0] == (0.15, 0.0) and gates[-1] == (0.8, 0.8), gates


def test_the_live_window_of_a_controller_run_draws_the_walls_where_its_supervisor_moved_them(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import argparse

    from mazesim.replay.views import DeferredWatch
    from mazesim.webots.simulation import observing_steps

    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    text = WORLD.replace(
        'E-puck { translation -0.6 -0.6 0 name "mover" controller "MOVER" supervisor TRUE }\n', ""
    ).replace('controller "WATCHER"', 'controller "<extern>"')
    watch = DeferredWatch(argparse.Namespace(live=True), "watcher", 1)
    with observing_steps(watch):
        supervisor = supervisor_in(tmp_path, text)
        supervisor.step(32)
        supervisor.getFromDef("GATE").getField("translation").setSFVec3f([0.8, 0.8, 0.05])
        supervisor.step(32)
        supervisor.step(32)
    assert watch.watch is not None
    boxes = np.asarray(watch.watch.world.wall_boxes()).reshape(-1, 6)
    (gate,) = [b for b in boxes if np.allclose(sorted(b[2:4]), (0.02, 0.3))]
    assert (round(float(gate[0]), 3), round(float(gate[1]), 3)) == (0.8, 0.8)
