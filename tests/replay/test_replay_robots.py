"""Runs of several robots: the demo's summary and picture, the run file (version 1.1, every
robot's track) and its checks, single-robot files unchanged, and the refused options."""

from __future__ import annotations

import gzip
import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from robots_world import THREE_ROBOTS, record_three_robots

import mazesim
from mazesim.cli import main
from mazesim.errors import RunFormatError
from mazesim.replay import load_run, save_run
from mazesim.replay.html import scene_of
from mazesim.replay.recorder import FleetRecorder
from mazesim.replay.run import run_from_json


@pytest.fixture(scope="module")
def three(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    return record_three_robots(tmp_path_factory.mktemp("three-robots"))


def test_the_demo_summary_and_run_cover_every_robot(three: dict[str, Path]) -> None:
    summary = json.loads((three["out"] / "summary.json").read_text())
    assert [robot["name"] for robot in summary["robots"]] == ["ann", "bob", "cy"]
    assert all(robot["distance_m"] > 0.05 for robot in summary["robots"])
    assert (three["out"] / "trajectory.png").stat().st_size > 1000
    run = load_run(three["run"])
    assert [(r.name, r.profile) for r in run.robots] == [
        ("ann", "e-puck"),
        ("bob", "e-puck"),
        ("cy", "e-puck2"),
    ]
    episode = run.episodes[0]
    assert len(episode.robots) == 2
    assert all(track.frames == episode.frames for track in episode.robots)
    # Each track ends where the simulator left its robot.
    for track, entry in zip([episode, *episode.robots], summary["robots"]):
        assert track.poses[-1, :2] == pytest.approx(entry["final_pose"][:2], abs=1e-4)
    # cy's readings are the e-puck2's: its ToF beside the eight proximity sensors.
    assert episode.robots[1].readings.shape[1] == episode.readings.shape[1] + 1
    assert episode.robots[0].wheel_speeds is not None
    values = json.loads(gzip.decompress(three["run"].read_bytes()))
    assert values["version"] == "1.1"


def test_the_same_seed_records_the_same_run(three: dict[str, Path], tmp_path: Path) -> None:
    again = record_three_robots(tmp_path)
    assert again["run"].read_bytes() == three["run"].read_bytes()


def test_a_run_of_several_robots_round_trips(three: dict[str, Path], tmp_path: Path) -> None:
    run = load_run(three["run"])
    save_run(run, tmp_path / "again.json.gz")
    assert (tmp_path / "again.json.gz").read_bytes() == three["run"].read_bytes()


def test_the_replay_scene_lists_every_robot(three: dict[str, Path]) -> None:
    scene = scene_of(load_run(three["run"]))
    assert [robot["robot_name"] for robot in scene["robots"]] == ["ann", "bob", "cy"]
    assert scene["robots"][2]["names"][-4:] == ["tof", "gs0", "gs1", "gs2"]


def test_a_run_of_one_robot_is_still_version_1_0_with_the_same_fields() -> None:
    simulator = mazesim.Simulator(mazesim.load_world("arena"), seed=1)
    recorder = FleetRecorder.of_simulator(simulator, "wander", seed=1)
    recorder.capture_simulator(simulator)
    recorder.acted(0, 1.0, 2.0)
    simulator.step(1.0, 2.0)
    recorder.capture_simulator(simulator)
    values = recorder.run("done").as_json()
    assert values["version"] == "1.0"
    assert list(values) == [
        "format",
        "version",
        "world",
        "robot",
        "controller",
        "seed",
        "control_step_ms",
        "sensor_names",
        "subtask_names",
        "reading_scale",
        "episodes",
    ]
    assert "robots" not in values["episodes"][0]
    assert "robots" not in scene_of(recorder.run("done"))


def _values(three: dict[str, Path]) -> Any:
    return json.loads(gzip.decompress(three["run"].read_bytes()))


@pytest.mark.parametrize(
    ("damage", "message"),
    [
        (lambda v: v.update(robots=v["robots"][:1]), "robots: expected a list of 2 to 64"),
        (
            lambda v: v["robots"][0].update(profile="e-puck2"),
            "robots\\[0\\].profile: expected the run's robot 'e-puck'",
        ),
        (
            lambda v: v["episodes"][0].update(robots=v["episodes"][0]["robots"][:1]),
            "episodes\\[0\\].robots: expected the tracks of the run's 2 other robots",
        ),
        (
            lambda v: v["episodes"][0]["robots"][1].update(
                frames=5,
                x=[0] * 5,
                y=[0] * 5,
                yaw=[0] * 5,
                readings=[[0]] * 5,
                rays=[[0]] * 5,
                contacts=[],
                events=[],
                wheel_speeds=[[0, 0]] * 5,
            ),
            "episodes\\[0\\].robots\\[1\\]: expected a track of",
        ),
        (
            lambda v: v["episodes"][0]["robots"][0].update(x="far"),
            "episodes\\[0\\].robots\\[0\\].x: expected a list of",
        ),
    ],
)
def test_a_damaged_run_of_several_robots_is_refused_naming_the_field(
    three: dict[str, Path], damage: Any, message: str
) -> None:
    values = _values(three)
    damage(values)
    with pytest.raises(RunFormatError, match=message):
        run_from_json(values, "run.json")


def test_a_1_0_reader_field_set_still_reads_robot_0(three: dict[str, Path]) -> None:
    # What a reader of 1.0 sees of a 1.1 file: the run without the robots fields, robot 0's.
    values = _values(three)
    del values["robots"]
    for episode in values["episodes"]:
        del episode["robots"]
    run = run_from_json(values)
    assert run.robots == [] and run.episodes[0].robots == []
    assert np.array_equal(run.episodes[0].poses, load_run(three["run"]).episodes[0].poses)


def test_the_live_view_of_several_robots_shows_them_all(
    three: dict[str, Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from mazesim.render.topdown import OTHER_ROBOT_RGB, TopDownRenderer
    from mazesim.replay.views import FleetLiveView

    args = ["demo", "--world", str(three["world"]), "--live", "--seconds", "1"]
    assert main([*args, "--out", str(tmp_path / "d")]) == 0  # headless here: it carries on
    assert "live view off" in capsys.readouterr().err
    world = mazesim.World.from_toml(THREE_ROBOTS)
    simulator = mazesim.Simulator(world, seed=0)
    view = FleetLiveView(world, simulator.robot, simulator.control_step_ms, "three")
    view.renderer = TopDownRenderer(world, simulator.robot)  # drawn even without a display
    states = [simulator.robot_state(i) for i in range(3)]
    view.show([state["pose"] for state in states], [False] * 3, "t 0.00 s")
    frame = view.live.last_frame
    assert frame is not None
    for rgb in OTHER_ROBOT_RGB[1:2]:
        assert np.all(frame == rgb, axis=2).sum() > 50


def test_the_video_draws_every_robot_in_its_own_colour(three: dict[str, Path]) -> None:
    from mazesim.render.topdown import OTHER_ROBOT_RGB
    from mazesim.replay.video import video_frames

    run = load_run(three["run"])
    last = run.episodes[0].frames - 1
    (image,) = video_frames(run, steps=range(last, last + 1))
    alone = load_run(three["run"])
    alone.episodes[0].robots = []
    (without,) = video_frames(alone, steps=range(last, last + 1))
    for rgb in OTHER_ROBOT_RGB[:2]:  # the first is also the rays' orange: count what is added
        added = np.all(image == rgb, axis=2).sum() - np.all(without == rgb, axis=2).sum()
        assert added > 50, f"no robot drawn in {rgb}"


def test_a_robots_rays_stop_at_the_other_robots_body() -> None:
    world = mazesim.World.from_toml(
        'format = "mazesim-world"\nversion = 1\n'
        '[[robots]]\nname = "west"\nx = -0.05\ny = 0.0\n'
        '[[robots]]\nname = "east"\nx = 0.05\ny = 0.0\nyaw = 3.141592653589793\n'
    )
    simulator = mazesim.Simulator(world, seed=0)
    recorder = FleetRecorder.of_simulator(simulator, "still", 0)
    recorder.capture_simulator(simulator)
    run = recorder.run()
    names = run.robots[0].sensor_names()
    reach = run.robot_profile.distance_sensor_range
    for track in (run.episodes[0], run.episodes[0].robots[0]):
        rays = dict(zip(names, track.rays[0]))
        # The front sensors, 17 degrees off the heading, meet the other body 2.6 cm of gap
        # between the rims away (about 4 cm along their rays), well within their 7 cm.
        assert 0.026 < rays["ps0"] < 0.05 and 0.026 < rays["ps7"] < 0.05
        assert rays["ps3"] == pytest.approx(reach, abs=1e-3)  # behind: nothing in range


def test_the_live_view_of_a_world_run_leaves_out_a_robot_a_supervisor_removed() -> None:
    from mazesim.cli.webots_world import WorldWatch
    from mazesim.render.topdown import OTHER_ROBOT_RGB, TopDownRenderer
    from mazesim.replay.views import FleetLiveView
    from mazesim.webots.robots_changed import RemovedRobot

    world = mazesim.World.from_toml(THREE_ROBOTS)
    simulator = mazesim.Simulator(world, seed=0)
    view = FleetLiveView(world, simulator.robot, simulator.control_step_ms, "three")
    view.renderer = TopDownRenderer(world, simulator.robot)  # drawn even without a display
    watch = WorldWatch(seed=0, record=False, live=True)
    watch.fleet, watch.view = object(), view

    class Here:
        def __init__(self, index: int) -> None:
            self.pose = tuple(simulator.robot_state(index)["pose"])
            self.colliding, self.time = False, 0.0

    removed = RemovedRobot.__new__(RemovedRobot)
    removed.pose, removed.colliding = Here(1).pose, False
    watch(world, [], [Here(0), removed, Here(2)], {})
    frame = view.live.last_frame
    assert frame is not None
    # Robot 1 is gone: robot 2 is the first other robot drawn, in the first other colour.
    assert np.all(frame == OTHER_ROBOT_RGB[0], axis=2).sum() > 50
    assert np.all(frame == OTHER_ROBOT_RGB[1], axis=2).sum() == 0
