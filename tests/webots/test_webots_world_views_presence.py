"""The run file and the HTML replay of a world run in which a supervisor imports robots and
removes some mid-run (``robot_spawner.wbt``): each robot is in the run (format 1.2; 1.3 as it
holds the imported robots' own profiles) from the frame it was imported to the frame it was
removed, the replay draws it only then, and the other robots' recorded rays pass where it is not
(#33, #37)."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from mazesim.replay import load_run
from mazesim.replay.screenshot import chromium_problem
from mazesim_process import mazesim_command
from supervised_world import SWARM

#: The spawner's steps at which it imports new-a and new-b, removes new-b, removes first.
IMPORT_STEP, REMOVE_STEP, REMOVE_FIRST_STEP = 5, 40, 60


@pytest.fixture(scope="module")
def spawned(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    tmp_path = tmp_path_factory.mktemp("spawned")
    env = dict(os.environ, SWARM_LOG=str(tmp_path), MPLBACKEND="Agg")
    env.pop("SPAWN_NONE", None)
    out, record, page = tmp_path / "out", tmp_path / "run.json", tmp_path / "replay.html"
    result = mazesim_command(
        *("webots", "run", str(SWARM / "worlds" / "robot_spawner.wbt"), "--seconds", "3"),
        *("--out", str(out), "--record", str(record), "--html", str(page)),
        cwd=tmp_path,
        env=env,
    )
    assert result.returncode == 0, result.stderr
    summary = json.loads((out / "summary.json").read_text())
    return {"record": record, "page": page, "summary": summary}


def test_each_robot_is_in_the_run_from_its_import_to_its_removal(spawned: dict[str, Any]) -> None:
    values = json.loads(spawned["record"].read_text())
    # 1.3: the imported e-pucks drive with the PROTO's tilted rays, a profile the run holds.
    assert values["version"] == "1.3"
    run = load_run(spawned["record"])
    assert run.robots[1].robot_profile.distance_sensor_elevations() == [0.16] * 8
    presence = {robot.name: (robot.from_frame, robot.until_frame) for robot in run.robots}
    # Frame k is the state after k steps: a robot imported after step 5 is in frame 5 on, at
    # its import pose; one removed after step 40 has frame 40, where it was then, its last.
    assert presence == {
        "spawner": (0, None),
        "first": (0, REMOVE_FIRST_STEP),
        "new-a": (IMPORT_STEP, None),
        "new-b": (IMPORT_STEP, REMOVE_STEP),
    }
    by_name = {robot["name"]: robot for robot in spawned["summary"]["robots"]}
    step_s = run.control_step_ms / 1000.0
    for robot in run.robots:
        entry = by_name[robot.name]
        assert robot.from_frame * step_s == pytest.approx(entry["imported_at_s"] or 0.0)
        removed = None if robot.until_frame is None else robot.until_frame * step_s
        assert removed == pytest.approx(entry["removed_at_s"])
    # The others' rays are not cut by a robot where it is not: new-b stands still at its
    # import pose before frame 5 and where it was removed after frame 40.
    episode = run.episodes[0]
    tracks = dict(zip([robot.name for robot in run.robots], [episode, *episode.robots]))
    new_b = tracks["new-b"]
    assert np.array_equal(new_b.poses[:IMPORT_STEP], np.repeat(new_b.poses[:1], IMPORT_STEP, 0))


def test_a_run_file_of_robots_present_throughout_stays_version_1_1(tmp_path: Path) -> None:
    from mazesim.replay.run import RunRobot

    robots = [RunRobot("a", "e-puck"), RunRobot("b", "e-puck", 0, None)]
    assert all(robot.always_present for robot in robots)
    assert robots[1].as_json() == {
        "name": "b",
        "profile": "e-puck",
        "sensor_names": robots[1].sensor_names(),
    }
    late = RunRobot("c", "e-puck", 3, 7)
    assert not late.always_present
    assert [late.present(frame) for frame in (2, 3, 7, 8)] == [False, True, True, False]
    assert late.as_json()["from_frame"] == 3 and late.as_json()["until_frame"] == 7


@pytest.mark.skipif(
    chromium_problem() is not None,
    reason=f"browser tests of the HTML replay need Chromium: {chromium_problem()}",
)
def test_the_replay_draws_each_robot_only_while_it_is_in_the_world(
    browser: Any, spawned: dict[str, Any]
) -> None:
    run = load_run(spawned["record"])
    names = [robot.name for robot in run.robots]
    bodies = {name: "robot" if k == 0 else f"robot-{k}" for k, name in enumerate(names)}
    browser.get(spawned["page"].resolve().as_uri())
    slider = browser.find_element("id", "slider")

    def shown_at(frame: int) -> dict[str, bool]:
        browser.execute_script(
            "arguments[0].value = arguments[1]; arguments[0].dispatchEvent(new Event('input'));",
            slider,
            frame,
        )
        return {
            name: browser.find_element("id", body).get_attribute("visibility") == "visible"
            for name, body in bodies.items()
        }

    last = run.episodes[0].frames - 1
    assert shown_at(0) == {"spawner": True, "first": True, "new-a": False, "new-b": False}
    assert shown_at(IMPORT_STEP) == {name: True for name in names}
    assert shown_at(REMOVE_STEP + 1)["new-b"] is False
    assert shown_at(last) == {"spawner": True, "first": False, "new-a": True, "new-b": False}
    rows = browser.find_element("id", "robots").text
    assert rows.count("not in the world") == 2
    # A removed robot's trail ends where it left; one not yet imported has none.
    trail = browser.find_element("id", f"trail-{names.index('new-b')}")
    assert len(trail.get_attribute("points").split()) >= 2
    shown_at(0)
    assert trail.get_attribute("points") == ""
    assert [e for e in browser.get_log("browser") if e["level"] in ("SEVERE", "WARNING")] == []
