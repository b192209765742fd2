"""A recorded run holds the walls where a supervisor left them at each frame: the run file
(version 1.4, older files still read), the replay page, the video and the recorded rays
(#32, #33)."""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from mazesim.errors import RunFormatError
from mazesim.replay.html import scene_of
from mazesim.replay.run import RecordedRun, load_run, run_from_json, save_run
from mazesim.replay.screenshot import chromium_problem
from mazesim.replay.video import video_frames
from mazesim.webots.lockstep import run_world
from supervised_world import project_of, supervisor_in

#: An e-puck "watcher" facing a gate 0.08 m ahead (within its front sensors' 7 cm), a second
#: e-puck "mover" far away.
WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 2 2 }
DEF GATE Solid {
  translation 0.08 0 0.05
  children [ Shape { geometry DEF GATE_BOX Box { size 0.02 0.3 0.1 } } ]
  name "gate"
  boundingObject USE GATE_BOX
}
E-puck { translation 0 0 0 name "watcher" controller "still" }
E-puck { translation -0.6 -0.6 0 name "mover" controller "mover" supervisor TRUE }
"""

STILL = "from controller import Robot\nrobot = Robot()\nwhile robot.step(32) != -1:\n    pass\n"

#: Moves the gate 0.8 m away after its fourth step.
MOVER = """from controller import Supervisor

robot = Supervisor()
for _ in range(4):
    robot.step(32)
robot.getFromDef("GATE").getField("translation").setSFVec3f([0.8, 0.8, 0.05])
while robot.step(32) != -1:
    pass
"""

#: The gate's place in the file and where the mover puts it.
BEFORE, AFTER = (0.08, 0.0), (0.8, 0.8)


def _gate(boxes: Any) -> tuple[float, float]:
    """Where the gate (the one 0.02 x 0.3 box) stands among wall boxes."""
    (gate,) = [b for b in np.asarray(boxes) if np.allclose(sorted(b[2:4]), (0.02, 0.3))]
    return round(float(gate[0]), 3), round(float(gate[1]), 3)


@pytest.fixture(scope="module")
def recorded(tmp_path_factory: pytest.TempPathFactory) -> RecordedRun:
    """A world run of :data:`WORLD` recorded as ``--record`` records it."""
    from mazesim.cli.webots_world import WorldWatch

    folder = tmp_path_factory.mktemp("gate")
    world = project_of(folder, "gate.wbt", WORLD, {"still": STILL, "mover": MOVER})
    watch = WorldWatch(1, record=True)
    run_world(str(world), seconds=0.5, seed=1, noise=False, observer=watch)
    run: RecordedRun = watch.fleet.run("0.5 s")
    return run


def test_a_recorded_world_run_holds_the_walls_a_supervisor_moved_from_that_frame_on(
    recorded: RecordedRun,
) -> None:
    episode = recorded.episodes[0]
    assert _gate(recorded.world.wall_boxes()) == BEFORE, "the run's world is the file's"
    ((frame, boxes),) = episode.walls
    assert 4 <= frame <= 6 and _gate(boxes) == AFTER, episode.walls
    assert episode.walls_at(frame - 1) is None and _gate(episode.walls_at(frame)) == AFTER
    assert all(not track.walls for track in episode.robots), "the run's walls are robot 0's"
    # The watcher's front rays meet the gate until it moves, then reach their whole range.
    front = [recorded.robot_profile.distance_sensor_names.index(n) for n in ("ps0", "ps7")]
    reach = recorded.robot_profile.distance_sensor_range
    assert np.all(episode.rays[: frame - 1, front] < reach - 0.01), episode.rays[:, front]
    assert np.allclose(episode.rays[frame:, front], reach), episode.rays[:, front]


def test_the_run_file_keeps_the_walls_changes_as_version_1_4(
    recorded: RecordedRun, tmp_path: Path
) -> None:
    path = tmp_path / "run.json"
    save_run(recorded, path)
    values = json.loads(path.read_text())
    assert values["version"] == "1.4"
    again = load_run(path)
    ((frame, boxes),) = again.episodes[0].walls
    assert frame == recorded.episodes[0].walls[0][0] and _gate(boxes) == AFTER


def test_a_run_whose_walls_stand_still_is_written_as_before(recorded: RecordedRun) -> None:
    values = recorded.as_json()
    del values["episodes"][0]["walls"]
    still = run_from_json(values, "still")
    # The world's e-pucks carry the profile their PROTO makes, which the run holds: 1.3.
    assert still.as_json()["version"] == "1.3"
    assert "walls" not in still.as_json()["episodes"][0]


@pytest.mark.parametrize(
    ("walls", "message"),
    [
        ([[3, []], [3, []]], r"walls\[1\]\[0\]: expected a whole number in \[4, "),
        ([[0, [[0, 0, -5, 5, 0]]]], r"walls\[0\]\[1\]: expected a list of at most"),
        # A row of the wrong width is named by its index.
        ([[0, [[0, 0, 5]]]], r"walls\[0\]\[1\]\[0\]: expected a row of 5 numbers"),
        ([[10_000, []]], r"walls\[0\]\[0\]: expected a whole number in \[0, "),
        ([3, []], r"walls\[0\]: expected a pair \[frame, wall boxes\]"),
    ],
)
def test_a_malformed_walls_change_is_refused_naming_its_field(
    recorded: RecordedRun, walls: Any, message: str
) -> None:
    values = recorded.as_json()
    values["episodes"][0]["walls"] = walls
    with pytest.raises(RunFormatError, match=message):
        run_from_json(values, "bad.json")


def test_the_video_draws_the_gate_where_it_stands_at_each_frame(recorded: RecordedRun) -> None:
    from mazesim.render.topdown import WALL_RGB, TopDownRenderer

    episode = recorded.episodes[0]
    frame = episode.walls[0][0]
    first, last = (video_frames(recorded, steps=range(f, f + 1)) for f in (0, episode.frames - 1))
    before, after = next(first), next(last)
    # The pixel of the gate's place in the file is a wall's before the move, not after; the
    # pixel of its new place the other way round.
    renderer = TopDownRenderer(recorded.world, recorded.robot_profile)
    for (x, y), drawn_before in ((BEFORE, True), (AFTER, False)):
        # The renderer's pixel of a world point (its private mapping).
        column = int(round(renderer._x0 + x * renderer.scale))
        row = int(round(renderer._y0 - (y + 0.1) * renderer.scale))
        assert bool(np.all(before[row, column] == WALL_RGB)) is drawn_before, (x, y)
        assert bool(np.all(after[row, column] == WALL_RGB)) is not drawn_before, (x, y)
    assert frame < episode.frames - 1


def test_the_replay_page_holds_each_walls_change(recorded: RecordedRun) -> None:
    scene = scene_of(recorded)
    ((frame, boxes),) = scene["run"]["episodes"][0]["walls"]
    assert frame == recorded.episodes[0].walls[0][0]
    assert _gate(np.asarray(boxes, dtype=np.float64) * 1e-4) == AFTER


def test_a_recorded_controller_run_holds_the_walls_its_supervisor_moved(tmp_path: Path) -> None:
    from mazesim.replay.views import DeferredWatch
    from mazesim.webots.simulation import observing_steps

    text = WORLD.replace(
        'E-puck { translation -0.6 -0.6 0 name "mover" controller "mover" supervisor TRUE }\n', ""
    ).replace('controller "still"', 'controller "<extern>" supervisor TRUE')
    path = tmp_path / "run.json"
    args = argparse.Namespace(record=str(path), html=None, video=None, live=False)
    watch = DeferredWatch(args, "mover", 1)
    with observing_steps(watch):
        supervisor = supervisor_in(tmp_path, text)
        supervisor.step(32)
        supervisor.getFromDef("GATE").getField("translation").setSFVec3f([0.8, 0.8, 0.05])
        supervisor.step(32)
        supervisor.step(32)
    watch.finish()
    run = load_run(path)
    assert _gate(run.world.wall_boxes()) == BEFORE, "the run's world is the file's"
    ((frame, boxes),) = run.episodes[0].walls
    assert frame == 1 and _gate(boxes) == AFTER


def _drawn_wall_places(driver: Any) -> set[tuple[float, float]]:
    """The centres of the walls the page draws (their rects' translations, y flipped)."""
    places = set()
    for rect in driver.find_elements("css selector", "#walls rect"):
        shift = rect.get_attribute("transform").split("translate(")[1].split(")")[0]
        x, y = (float(v) for v in shift.split(","))
        places.add((round(x, 3), round(-y, 3)))
    return places


@pytest.mark.skipif(
    chromium_problem() is not None,
    reason=f"the page is drawn by Chromium: {chromium_problem()}",
)
def test_the_replay_page_draws_the_gate_where_it_stands_at_the_frame_shown(
    recorded: RecordedRun, tmp_path: Path, browser: Any
) -> None:
    from mazesim.replay.html import write_html

    page = tmp_path / "run.html"
    write_html(recorded, page)
    browser.get(page.resolve().as_uri())
    browser.get_log("browser")
    slider = browser.find_element("id", "slider")
    places = []
    for frame in (0, recorded.episodes[0].frames - 1, 0):
        browser.execute_script(
            "arguments[0].value = arguments[1]; arguments[0].dispatchEvent(new Event('input'));",
            slider,
            frame,
        )
        places.append(_drawn_wall_places(browser))
    assert BEFORE in places[0] and AFTER not in places[0], places[0]
    assert AFTER in places[1] and BEFORE not in places[1], places[1]
    assert places[2] == places[0], "back to the start, the walls of the file"
    assert [e for e in browser.get_log("browser") if e["level"] == "SEVERE"] == []
