"""Importing Webots .wbt worlds: the six real worlds of tests/data/webots-worlds, the CLI's JSON
layout, load_world on .wbt paths, and fuzzing with mutated real files."""

from __future__ import annotations

import json
import math
import os
import tempfile
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import mazesim
from mazesim.errors import MazesimError, MazesimIOError, WorldFormatError
from mazesim.webots import import_wbt, import_wbt_text
from mazesim_process import mazesim_command

CORPUS = Path(__file__).parents[1] / "data" / "webots-worlds"
LENGTH = 1e-3
ANGLE = 0.01

Box = tuple[tuple[float, float], tuple[float, float], float]

ARENA_2X2: list[Box] = [
    ((1.005, 0.0), (0.01, 2.0), 0.0),
    ((-1.005, 0.0), (0.01, 2.0), 0.0),
    ((0.0, 1.005), (2.02, 0.01), 0.0),
    ((0.0, -1.005), (2.02, 0.01), 0.0),
    ((-0.683174, 0.2), (0.1, 0.1), 0.5),
    ((0.35, 0.75), (0.1, 0.1), 4.96782),
    ((-0.35471, -0.5), (0.1, 0.1), 5.36782),
    ((0.36, 0.3), (0.1, 0.1), 5.36782),
    ((-0.66, 0.65), (0.1, 0.1), 5.36782),
]

#: file -> (expected boxes or their number, robot start (x, y, yaw), basic time step ms)
EXPECTED: dict[str, tuple[list[Box] | int, tuple[float, float, float], float]] = {
    "collision_avoidance.wbt": (
        [
            ((0.5, 0.0), (0.02, 0.98), 0.0),
            ((-0.5, 0.0), (0.02, 0.98), 0.0),
            ((0.0, -0.5), (0.02, 0.98), 1.5708),
            ((0.0, 0.5), (0.02, 0.98), 1.5708),
        ],
        (0.0, 0.0, 0.0),
        16.0,
    ),
    "advanced_path_planning.wbt": (
        [
            ((-0.205, -0.405), (0.63, 0.01), 0.0),
            ((-0.205, 0.105), (0.63, 0.01), 0.0),
            ((-0.515, -0.15), (0.01, 0.52), 0.0),
            ((0.105, -0.15), (0.01, 0.52), 0.0),
        ],
        (-0.04, -0.04, math.pi),
        16.0,
    ),
    "rats_life_benchmark.wbt": (54, (0.0, -0.05, math.pi), 20.0),
    "e-puck.R2023b.wbt": (ARENA_2X2, (0.0, 0.0, 1.57), 32.0),
    "e-puck.R2021c_NUE.wbt": (ARENA_2X2, (0.0, 0.0, 1.57), 32.0),
    "webots_ros2_epuck_world.wbt": (
        [
            ((0.755, 0.0), (0.01, 1.5), 0.0),
            ((-0.755, 0.0), (0.01, 1.5), 0.0),
            ((0.0, 0.755), (1.52, 0.01), 0.0),
            ((0.0, -0.755), (1.52, 0.01), 0.0),
            ((-0.265062, 0.13), (0.1, 0.1), 0.0),
            ((-0.115895, -0.36), (0.1, 0.1), 0.0),
            ((0.44, 0.12), (0.1, 0.1), 0.0),
            ((0.29726, -0.29), (0.1, 0.1), 0.0),
            ((-0.158467, 0.26), (0.1, 0.1), 0.0),
        ],
        (0.0530459, 0.00806403, 3.1415),
        20.0,
    ),
}


def corpus_file(name: str) -> Path:
    path = CORPUS / name
    assert path.is_file(), f"the Webots test corpus is missing: expected {path}"
    return path


def angle_gap(a: float, b: float, period: float) -> float:
    d = (a - b) % period
    return min(d, period - d)


def same_box(a: Box, b: Box) -> bool:
    (ca, sa, ya), (cb, sb, yb) = a, b
    if abs(ca[0] - cb[0]) > LENGTH or abs(ca[1] - cb[1]) > LENGTH:
        return False

    def sizes(p: tuple[float, float], q: tuple[float, float]) -> bool:
        return abs(p[0] - q[0]) <= LENGTH and abs(p[1] - q[1]) <= LENGTH

    straight = sizes(sa, sb) and angle_gap(ya, yb, math.pi) <= ANGLE
    turned = sizes(sa, (sb[1], sb[0])) and angle_gap(ya, yb + math.pi / 2, math.pi) <= ANGLE
    return straight or turned


def boxes_of(report: Any) -> list[Box]:
    found = []
    for obstacle in report["obstacles"]:
        if obstacle["kind"] != "box":
            continue
        found.append((tuple(obstacle["center"]), tuple(obstacle["size"]), obstacle["yaw"]))
    return found


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_corpus_world_imports_with_its_obstacles_and_pose(name: str) -> None:
    expected_boxes, (x, y, yaw), step = EXPECTED[name]
    world, report = import_wbt(corpus_file(name))
    found = boxes_of(report)
    if isinstance(expected_boxes, int):
        assert len(found) == expected_boxes
    else:
        assert len(found) == len(expected_boxes), found
        for box in expected_boxes:
            assert sum(same_box(f, box) for f in found) == 1, (box, found)
    robot = report["robot"]
    assert robot is not None
    assert abs(robot["x"] - x) <= LENGTH and abs(robot["y"] - y) <= LENGTH
    assert angle_gap(robot["yaw"], yaw, 2 * math.pi) <= ANGLE
    assert report["basic_time_step_ms"] == step
    assert world.basic_time_step_ms == step
    if len(report["obstacles"]) == len(found):
        assert len(world.wall_boxes()) == len(found)
    assert world.start == pytest.approx((robot["x"], robot["y"], robot["yaw"]))


def test_r2021c_nue_and_r2023b_give_the_same_world() -> None:
    old_world, old = import_wbt(corpus_file("e-puck.R2021c_NUE.wbt"))
    new_world, new = import_wbt(corpus_file("e-puck.R2023b.wbt"))
    for a, b in zip(boxes_of(old), boxes_of(new)):
        assert same_box(a, b), (a, b)
    assert old["robot"] == pytest.approx(new["robot"])
    assert old_world.start == pytest.approx(new_world.start)
    assert len(old_world.wall_boxes()) == len(new_world.wall_boxes())


def test_rats_life_maze_stays_in_its_area_and_runs_the_e_puck2() -> None:
    _, report = import_wbt(corpus_file("rats_life_benchmark.wbt"))
    for (cx, cy), _, _ in boxes_of(report):
        assert -0.35 - LENGTH <= cx <= 0.24 + LENGTH and -0.34 - LENGTH <= cy <= 0.27 + LENGTH
    assert (report["robot_model"], report["robot_profile"]) == ("e-puck2", "e-puck2")


def test_collision_avoidance_ball_is_a_movable_disc_the_robot_pushes() -> None:
    world, report = import_wbt(corpus_file("collision_avoidance.wbt"))
    assert [o["kind"] for o in report["obstacles"]] == ["box"] * 4
    # A 5 cm sphere of Webots' default density, 1000 kg/m^3: 0.52 kg.
    [ball] = report["bodies"]
    assert (ball["kind"], ball["center"], ball["radius"]) == ("circle", [0.2, 0.0], 0.05)
    assert ball["mass"] == pytest.approx(1000 * 4 / 3 * math.pi * 0.05**3)
    assert world.bodies() == [
        {
            "shape": "circle",
            "center": (0.2, 0.0),
            "radius": 0.05,
            "mass": ball["mass"],
            "friction": 1.0,  # Webots' default contact's coulombFriction
            "reflectance": 1.0,
        }
    ]
    assert not any('"ball": an object with physics' in w for w in report["warnings"])
    # The ball stands 0.15 m ahead: after 7.7 cm ps0 and ps7 see it 4 cm away.
    sim = mazesim.Simulator(world, noise=False)
    for _ in range(80):
        sim.step(3.0, 3.0)
    assert sim.distance_sensors()[[0, 7]].min() > 100.0
    assert sim.collisions == 0
    # Then the robot pushes it ahead.
    for _ in range(100):
        sim.step(3.0, 3.0)
    [(x, y, _)] = sim.body_poses()
    assert x > sim.pose[0] + 0.08 and abs(y) < 0.02
    sim.reset()
    assert sim.body_poses() == [(pytest.approx(0.2), 0.0, 0.0)]


def test_devices_in_the_turret_slot_are_listed() -> None:
    _, report = import_wbt(corpus_file("advanced_path_planning.wbt"))
    [display] = report["extension_devices"]
    assert display["type"] == "Display"
    assert (display["name"], display["slot"]) == ("display", "turretSlot")
    assert display["fields"] == {"width": 42.0, "height": 30.0}
    # webots_ros2's e-puck carries a Pi-puck extension board: its three RGB LEDs.
    _, ros2 = import_wbt(corpus_file("webots_ros2_epuck_world.wbt"))
    assert not any("Pi-puck" in w for w in ros2["warnings"])
    leds = [d["name"] for d in ros2["extension_devices"] if d["type"] == "LED"]
    assert leds == ["pi-puck led 0", "pi-puck led 1", "pi-puck led 2"]


def test_load_world_reads_wbt_paths() -> None:
    path = corpus_file("collision_avoidance.wbt")
    world = mazesim.load_world(path)
    assert world == import_wbt(path)[0]
    assert world.name == "collision_avoidance"
    assert mazesim.load_world(str(path)).basic_time_step_ms == 16.0


def test_text_import_and_errors_carry_line_and_column() -> None:
    world, report = import_wbt_text(
        "#VRML_SIM R2023b utf8\nSolid { translation 0 0 0.05 boundingObject Cylinder "
        "{ radius 0.05 height 0.1 } }\n",
        "round.wbt",
    )
    (circle,) = report["obstacles"]
    assert circle == {
        "kind": "circle",
        "center": [0.0, 0.0],
        "radius": 0.05,
        "owners": [2],  # the Solid on line 2 holds it
        "walls": [0, len(world.wall_boxes())],  # a ring of walls, the world's first
        "reflectance": 1.0,  # no appearance: white
    }
    assert report["robot"] is None
    assert world.name == "round"
    assert len(world.wall_boxes()) >= 8
    with pytest.raises(WorldFormatError) as caught:
        import_wbt_text("#VRML_SIM R2023b utf8\nSolid {\n  size 1 ]\n}\n", "bad.wbt")
    assert (caught.value.line, caught.value.column) == (3, 10)
    assert caught.value.source == "bad.wbt"
    assert str(caught.value).startswith("bad.wbt:3:10:")
    with pytest.raises(MazesimIOError):
        import_wbt(CORPUS / "no-such-world.wbt")


def test_cli_json_layout(tmp_path: Path) -> None:
    result = mazesim_command(
        "import-wbt", str(corpus_file("collision_avoidance.wbt")), "--json", cwd=tmp_path
    )
    assert result.returncode == 0, result.stderr
    report = json.loads(result.stdout)
    assert set(report) == {
        "obstacles",
        "sensed_only",
        "bodies",
        "robot",
        "basic_time_step_ms",
        "warnings",
        "one_controller_warnings",
        "robot_model",
        "robot_line",
        "robot_profile",
        "robots",
        "extension_devices",
        "missing_devices",
        "floor_textures",
        "wall_textures",
        "floor_paint",
        "floor_marks",
        "protos",
        "recognition",
    }
    assert report["recognition"] == {"cameras": [], "objects": []}
    (robot,) = report["robots"]
    keys = {"pose", "model", "profile", "controller", "name", "def_name", "line", "y_up"}
    keys |= {"node_type", "model_field"}
    assert set(robot) == keys
    assert robot["line"] == report["robot_line"]
    assert robot["y_up"] is False, "an E-puck PROTO node of R2022a on stands Z-up"
    assert set(report["protos"]) == {"expanded", "stand_ins", "cache_hits", "downloads"}
    for obstacle in report["obstacles"]:
        if obstacle["kind"] == "box":
            assert set(obstacle) == {
                "kind",
                "center",
                "size",
                "yaw",
                "owners",
                "walls",
                "reflectance",
            }
            assert len(obstacle["center"]) == 2 and len(obstacle["size"]) == 2
        else:
            assert set(obstacle) == {"kind", "center", "radius", "owners", "walls", "reflectance"}
    assert (report["robot_model"], report["robot_profile"]) == ("E-puck", "e-puck")
    assert report["extension_devices"] == [] and report["floor_textures"] == []
    assert set(report["robot"]) == {"x", "y", "yaw"}
    assert report["basic_time_step_ms"] == 16.0
    assert all(isinstance(w, str) for w in report["warnings"])
    round_world = tmp_path / "round.wbt"
    round_world.write_text(
        "#VRML_SIM R2023b utf8\nSolid { translation 0.1 0 0.05 boundingObject "
        "Cylinder { radius 0.02 height 0.1 } }\n"
    )
    report = json.loads(
        mazesim_command("import-wbt", str(round_world), "--json", cwd=tmp_path).stdout
    )
    assert report["robot"] is None
    assert report["obstacles"] == [
        {
            "kind": "circle",
            "center": [0.1, 0.0],
            "radius": 0.02,
            "owners": [2],
            "walls": [0, 11],
            "reflectance": 1.0,
        }
    ]


def test_cli_summary_and_world_file(tmp_path: Path) -> None:
    out = tmp_path / "arena.toml"
    result = mazesim_command(
        "import-wbt", str(corpus_file("e-puck.R2021c_NUE.wbt")), "--out", str(out), cwd=tmp_path
    )
    assert result.returncode == 0, result.stderr
    assert "9 boxes, 0 circles" in result.stdout
    assert "robot              E-puck (simulated as e-puck)" in result.stdout
    assert "yaw 1.5700 rad" in result.stdout
    assert out.is_file()
    saved = mazesim.load_world(out)
    assert saved == import_wbt(corpus_file("e-puck.R2021c_NUE.wbt"))[0]
    moved = mazesim_command("import-wbt", str(corpus_file("collision_avoidance.wbt")), cwd=tmp_path)
    assert "movable bodies     1\n" in moved.stdout
    assert "an object with physics" not in moved.stdout


def test_cli_errors_are_one_line_with_exit_2(tmp_path: Path) -> None:
    bad = tmp_path / "bad.wbt"
    bad.write_text("#VRML_SIM R2023b utf8\nSolid { translation 1 2 3\n")
    result = mazesim_command("import-wbt", str(bad), cwd=tmp_path)
    assert result.returncode == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("mazesim: error: ")
    assert f"{bad}:3:1:" in lines[0]
    missing = mazesim_command("import-wbt", str(tmp_path / "none.wbt"), cwd=tmp_path)
    assert missing.returncode == 2 and "Traceback" not in missing.stderr


SNIPPETS = [
    b"{",
    b"}",
    b"[",
    b"]",
    b'"',
    b"#",
    b"\n",
    b"DEF A ",
    b"USE A ",
    b"USE WALL_SHAPE ",
    b"hidden ",
    b"NULL ",
    b"1e999 ",
    b"-",
    b"\xff",
    b"\x00",
    b"Transform { scale 0 0 0 ",
]


@st.composite
def mutated_world(draw: st.DrawFn) -> bytes:
    names = sorted(p.name for p in CORPUS.glob("*.wbt"))
    data = bytearray(corpus_file(draw(st.sampled_from(names))).read_bytes())
    for _ in range(draw(st.integers(1, 6))):
        at = draw(st.integers(0, len(data)))
        kind = draw(st.sampled_from(["flip", "truncate", "insert", "snippet", "delete"]))
        if kind == "flip" and at < len(data):
            data[at] ^= draw(st.integers(1, 255))
        elif kind == "truncate":
            del data[at:]
        elif kind == "insert":
            data[at:at] = draw(st.binary(min_size=1, max_size=6))
        elif kind == "snippet":
            data[at:at] = draw(st.sampled_from(SNIPPETS))
        elif kind == "delete":
            del data[at : at + draw(st.integers(1, 50))]
    return bytes(data)


def check_import(call: Any) -> None:
    try:
        world, report = call()
    except WorldFormatError as error:
        assert error.line is not None and error.line >= 1
        assert error.column is not None and error.column >= 1
    except MazesimError:
        pass
    else:
        assert len(world.wall_boxes()) >= len(report["obstacles"])


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(mutated_world())
def test_mutated_files_raise_only_located_mazesim_errors(data: bytes) -> None:
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "mutated.wbt")
        with open(path, "wb") as handle:
            handle.write(data)
        check_import(lambda: import_wbt(path))
    text = data.decode("utf-8", errors="surrogateescape")
    check_import(lambda: import_wbt_text(text, "mutated.wbt"))
