"""The PROTO engine: project PROTOs (plain, JavaScript and Lua templates), nested PROTOs, IS
fields, EXTERNPROTO by relative path and by URL (a 127.0.0.1 server, then the cache), an
unreachable URL, stand-ins for stock objects, CR line ends."""

from __future__ import annotations

import functools
import http.server
import json
import shutil
import threading
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from mazesim.webots.importer import import_wbt, import_wbt_text
from mazesim.webots.proto import ProtoUnavailableError
from mazesim_process import mazesim_command

pytest.importorskip("quickjs", reason="the PROTO engine's JavaScript templates need quickjs")
pytest.importorskip("lupa", reason="the PROTO engine's Lua templates need lupa")

DATA = Path(__file__).resolve().parents[1] / "data" / "webots-protos"


@pytest.fixture(autouse=True)
def _private_cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Each test downloads into its own cache, and never sees a Webots installation."""
    monkeypatch.setenv("MAZESIM_PROTO_CACHE", str(tmp_path / "cache"))
    monkeypatch.delenv("WEBOTS_HOME", raising=False)
    monkeypatch.delenv("MAZESIM_OFFLINE", raising=False)


def _offline_import(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, protos: list[str], nodes: str
) -> dict[str, Any]:
    """The import report of an R2023b world of ``nodes`` naming Webots' ``protos``
    (``solids/protos/SolidTorus``...) by EXTERNPROTO, offline: their stand-ins are taken."""
    monkeypatch.setenv("MAZESIM_OFFLINE", "1")
    head = "#VRML_SIM R2023b utf8\n" + "".join(
        f'EXTERNPROTO "webots://projects/objects/{proto}.proto"\n' for proto in protos
    )
    _, report = import_wbt_text(head + nodes, str(tmp_path / "offline.wbt"))
    return report


def _boxes(report: Mapping[str, Any]) -> list[tuple[list[float], list[float]]]:
    return [(o["center"], o["size"]) for o in report["obstacles"] if o["kind"] == "box"]


def test_project_protos_plain_javascript_lua_and_nested_are_expanded(
    capsys: pytest.CaptureFixture[str],
) -> None:
    _, report = import_wbt(DATA / "project" / "worlds" / "local.wbt")
    assert capsys.readouterr().out == "", "templates print to Webots' console, not stdout"
    assert set(report["protos"]["expanded"]) == {
        "BoxWall",
        "PillarRowJs",
        "PillarRowLua",
        "Corridor",
    }
    boxes = _boxes(report)
    # BoxWall through EXTERNPROTO "../protos/BoxWall.proto": its size field replaces the default.
    assert ([0.5, 0.0], [0.02, 0.6]) in boxes
    # PillarRowJs (found in protos/ without EXTERNPROTO): count 4 pillars, 0.2 m apart.
    circles = sorted(o["center"][0] for o in report["obstacles"] if o["kind"] == "circle")
    assert circles == pytest.approx([-0.5, -0.3, -0.1, 0.1])
    # PillarRowLua: its default count 2, 0.3 m apart.
    assert ([-0.5, -0.3], [0.04, 0.04]) in boxes and ([-0.2, -0.3], [0.04, 0.04]) in boxes
    # Corridor: two nested BoxWalls, width 0.4 apart, wallSize passed on through IS.
    assert ([0.0, -0.6], [1.0, 0.02]) in boxes and ([0.0, -1.0], [1.0, 0.02]) in boxes
    assert report["robot"] == {"x": 0.1, "y": 0.2, "yaw": 0.0}
    assert not any("unknown PROTO" in w for w in report["warnings"])


def test_warnings_keep_the_lines_of_the_file() -> None:
    _, report = import_wbt(DATA / "project" / "worlds" / "local.wbt")
    pillars = [w for w in report["warnings"] if '"pillars"' in w]
    assert pillars and all(w.startswith("line 14:") for w in pillars)


def _serve(folder: Path) -> Iterator[str]:
    class QuietHandler(http.server.SimpleHTTPRequestHandler):
        def log_message(self, format: str, *args: Any) -> None:
            pass

    handler = functools.partial(QuietHandler, directory=str(folder))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}"
    finally:
        server.shutdown()
        server.server_close()


@pytest.fixture
def remote(tmp_path: Path) -> Iterator[str]:
    folder = tmp_path / "served"
    shutil.copytree(DATA / "remote", folder)
    yield from _serve(folder)


def _url_world(url: str) -> str:
    return (
        "#VRML_SIM R2023b utf8\n"
        f'EXTERNPROTO "{url}/RemoteBox.proto"\n'
        "RemoteBox { translation 0.3 0.4 0.05 }\n"
    )


def test_externproto_url_is_downloaded_then_read_from_the_cache(
    remote: str, tmp_path: Path
) -> None:
    world = tmp_path / "project" / "worlds" / "remote.wbt"
    world.parent.mkdir(parents=True)
    world.write_text(_url_world(remote))
    _, first = import_wbt(world)
    assert first["protos"]["downloads"] == [
        f"{remote}/RemoteBox.proto",
        f"{remote}/RemotePart.proto",
    ]
    assert _boxes(first) == [([0.3, 0.4], [0.1, 0.1])]
    # The server is gone: the second run reads both files from the cache.
    (tmp_path / "served" / "RemoteBox.proto").unlink()
    _, second = import_wbt(world)
    assert second["protos"]["downloads"] == []
    assert len(second["protos"]["cache_hits"]) == 2
    assert _boxes(second) == _boxes(first)


def test_unreachable_url_fails_naming_the_url_and_what_to_do(tmp_path: Path) -> None:
    closed = next(_serve(tmp_path))  # a port that nothing listens on once the server stops
    url = f"{closed}/Missing.proto"
    text = f'#VRML_SIM R2023b utf8\nEXTERNPROTO "{url}"\nMissing {{ }}\n'
    with pytest.raises(ProtoUnavailableError) as error:
        import_wbt_text(text, str(tmp_path / "w.wbt"))
    message = str(error.value)
    assert url in message and "protos/ folder" in message and "WEBOTS_HOME" in message


def test_stock_object_without_a_file_gets_a_named_stand_in(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.setenv("MAZESIM_OFFLINE", "1")
    text = (
        "#VRML_SIM R2023b utf8\n"
        'EXTERNPROTO "webots://projects/objects/floors/protos/CircleArena.proto"\n'
        "CircleArena { radius 0.5 subdivision 16 }\n"
    )
    _, report = import_wbt_text(text, str(tmp_path / "arena.wbt"))
    assert "CircleArena" in report["protos"]["stand_ins"]
    assert any("stand-in" in w and "CircleArena" in w for w in report["warnings"])
    boxes = _boxes(report)
    assert len(boxes) == 16
    for centre, _ in boxes:
        assert (centre[0] ** 2 + centre[1] ** 2) ** 0.5 == pytest.approx(0.505, abs=1e-6)


def test_a_stock_object_without_a_file_or_a_stand_in_says_how_to_have_it_read(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    """Webots' own PROTO that cannot be read offline and has no stand-in: one warning for all its
    instances says why none is imported and where to put the file (it said only "an unknown
    PROTO", as for a type no file declares)."""
    monkeypatch.setenv("MAZESIM_OFFLINE", "1")
    url = "https://raw.githubusercontent.com/cyberbotics/webots/R2023a/projects/objects/solids/protos/SolidPipe.proto"
    text = (
        f'#VRML_SIM R2023b utf8\nEXTERNPROTO "{url}"\n'
        "SolidPipe { translation 0.2 0 0 }\nSolidPipe { translation -0.2 0 0 }\n"
        "E-puck { turretSlot [ SolidPipe { } ] }\n"
    )
    _, report = import_wbt_text(text, str(tmp_path / "pipes.wbt"))
    said = [w for w in report["warnings"] if "has no stand-in" in w]
    assert len(said) == 1, report["warnings"]
    assert "SolidPipe" in said[0] and url in said[0] and "its 3 instance(s)" in said[0]
    assert "protos/ folder" in said[0] and "WEBOTS_HOME" in said[0]
    assert "SolidPipe" not in report["protos"]["stand_ins"]
    # A type the core knows itself (Webots' Pi-puck board, in an e-puck's turret) gets none.
    url = "webots://projects/robots/gctronic/e-puck/protos/Pi-puck.proto"
    text = (
        f'#VRML_SIM R2023b utf8\nEXTERNPROTO "{url}"\nE-puck {{ turretSlot [ Pi-puck {{ }} ] }}\n'
    )
    _, report = import_wbt_text(text, str(tmp_path / "pi.wbt"))
    assert not any("Pi-puck" in w for w in report["warnings"]), report["warnings"]


def test_webots_home_is_searched_before_a_stand_in(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    home = tmp_path / "webots"
    protos = home / "projects" / "objects" / "floors" / "protos"
    protos.mkdir(parents=True)
    shutil.copy(DATA / "project" / "protos" / "BoxWall.proto", protos / "CircleArena.proto")
    (protos / "CircleArena.proto").write_text(
        (protos / "CircleArena.proto").read_text().replace("PROTO BoxWall", "PROTO CircleArena")
    )
    monkeypatch.setenv("WEBOTS_HOME", str(home))
    text = (
        "#VRML_SIM R2023b utf8\n"
        'EXTERNPROTO "webots://projects/objects/floors/protos/CircleArena.proto"\n'
        "CircleArena { }\n"
    )
    _, report = import_wbt_text(text, str(tmp_path / "arena.wbt"))
    assert report["protos"]["stand_ins"] == {}
    assert _boxes(report) == [([0.0, 0.0], [0.5, 0.02])]


def test_a_webots_library_proto_named_by_its_https_url_is_read_from_the_installation(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    """A world saved by Webots R2022b or later names a PROTO of Webots' library (a pallet
    mazesim has no stand-in for) by its URL in Webots' repository: offline, with Webots
    installed, its solids are obstacles, as a ``webots://`` URL's are; without Webots, the
    warning says it is not imported."""
    monkeypatch.setenv("MAZESIM_OFFLINE", "1")
    text = (
        "#VRML_SIM R2025a utf8\n"
        'EXTERNPROTO "https://raw.githubusercontent.com/cyberbotics/webots/R2025a/projects/'
        'objects/factory/pallet/protos/Pallet.proto"\n'
        "Pallet { translation 0.2 0.1 0 }\n"
    )
    _, without = import_wbt_text(text, str(tmp_path / "pallets.wbt"))
    assert _boxes(without) == []
    assert any("line 3: Pallet: an unknown PROTO: not imported" in w for w in without["warnings"])
    home = tmp_path / "webots"
    protos = home / "projects" / "objects" / "factory" / "pallet" / "protos"
    protos.mkdir(parents=True)
    wall = (DATA / "project" / "protos" / "BoxWall.proto").read_text()
    (protos / "Pallet.proto").write_text(wall.replace("PROTO BoxWall", "PROTO Pallet"))
    monkeypatch.setenv("WEBOTS_HOME", str(home))
    _, report = import_wbt_text(text, str(tmp_path / "pallets.wbt"))
    assert report["protos"]["expanded"] == {"Pallet": str(protos / "Pallet.proto")}
    assert _boxes(report) == [([0.2, 0.1], [0.5, 0.02])]
    assert not any("Pallet" in w for w in report["warnings"])


def test_cr_line_ends_import_like_lf() -> None:
    text = (DATA / "project" / "worlds" / "local.wbt").read_text()
    source = str(DATA / "project" / "worlds" / "local.wbt")
    _, lf = import_wbt_text(text, source)
    _, cr = import_wbt_text(text.replace("\n", "\r"), source)
    assert cr["obstacles"] == lf["obstacles"] and cr["robot"] == lf["robot"]
    assert len(cr["obstacles"]) == 9


def _project_proto(project: Path, name: str, text: str) -> None:
    """Writes the PROTO ``name`` in the project's ``protos/`` folder."""
    (project / "protos").mkdir(exist_ok=True)
    (project / "protos" / f"{name}.proto").write_text(text)


def test_template_error_names_the_proto(tmp_path: Path) -> None:
    _project_proto(
        tmp_path,
        "Broken",
        "#VRML_SIM R2023b utf8\nPROTO Broken [ ]\n"
        "{\n  %< undefinedName.call(); >%\n  Group { }\n}\n",
    )
    from mazesim.errors import WorldFormatError

    with pytest.raises(
        WorldFormatError, match=r"Broken.proto:1:1: its JavaScript template fails: ReferenceError"
    ):
        import_wbt_text("#VRML_SIM R2023b utf8\nBroken { }\n", str(tmp_path / "worlds" / "b.wbt"))


def test_floor_texture_url_is_fetched_through_the_cache(remote: str, tmp_path: Path) -> None:
    from PIL import Image

    grey = np.full((48, 64), 255, dtype=np.uint8)
    grey[:, 20:28] = 0  # a black band: a line to follow
    Image.fromarray(grey).save(tmp_path / "served" / "track.png")
    text = (
        "#VRML_SIM R2023b utf8\nRectangleArena {\n  floorSize 1.6 1.2\n  floorTileSize 1.6 1.2\n"
        "  floorAppearance PBRAppearance {\n    baseColorMap ImageTexture {\n"
        f'      url [ "{remote}/track.png" ]\n    }}\n  }}\n}}\n'
    )
    source = str(tmp_path / "worlds" / "floor.wbt")
    world, report = import_wbt_text(text, source)
    assert report["floor_paint"] > 0
    assert not [w for w in report["warnings"] if "texture" in w]
    # Column 24 of 64 across the 1.6 m floor: x = -0.8 + 24.5 / 64 * 1.6, on the black band.
    assert world.floor_reflectance(-0.8 + 24.5 / 64 * 1.6, 0.0) <= 0.2
    assert world.floor_reflectance(0.5, 0.0) > 0.8
    (tmp_path / "served" / "track.png").unlink()
    _, again = import_wbt_text(text, source)
    assert again["floor_paint"] == report["floor_paint"]


def test_unreachable_floor_texture_url_is_a_warning_naming_it(tmp_path: Path) -> None:
    closed = next(_serve(tmp_path))
    text = (
        "#VRML_SIM R2023b utf8\nRectangleArena { floorAppearance PBRAppearance { "
        f'baseColorMap ImageTexture {{ url [ "{closed}/gone.png" ] }} }} }}\n'
    )
    _, report = import_wbt_text(text, str(tmp_path / "w.wbt"))
    assert report["floor_paint"] == 0
    # Said once, with why, where the import said the file was not found.
    about = [w for w in report["warnings"] if "gone.png" in w]
    assert len(about) == 1, about
    assert f"{closed}/gone.png: cannot be downloaded" in about[0]
    assert about[0].endswith("the floor is left bare")


def test_a_run_says_at_its_start_which_floor_texture_it_could_not_download(
    tmp_path: Path,
) -> None:
    closed = next(_serve(tmp_path))
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "line.wbt").write_text(
        "#VRML_SIM R2023b utf8\nRectangleArena { floorAppearance PBRAppearance { "
        f'baseColorMap ImageTexture {{ url [ "{closed}/line.png" ] }} }} }}\nE-puck {{ }}\n'
    )
    (tmp_path / "still.py").write_text("from controller import Robot\nRobot().step(32)\n")
    result = mazesim_command(
        *("webots", "run", "still.py", "--world", "worlds/line.wbt", "--seconds", "0.1"),
        *("--out", "out", "--no-progress"),
        cwd=tmp_path,
    )
    assert result.returncode == 0, result.stderr
    statement = (
        f"the floor texture {closed}/line.png, which cannot be downloaded here and is not in "
        "the download cache (no network): the floor's paint is left out"
    )
    assert f"mazesim: missing: {statement}" in result.stderr.splitlines()
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["missing_features"] == [statement]


def test_balls_and_barrels_stand_in_with_their_documented_geometry(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.setenv("MAZESIM_OFFLINE", "1")
    base = "webots://projects/objects"
    text = (
        "#VRML_SIM R2023b utf8\n"
        f'EXTERNPROTO "{base}/balls/protos/SoccerBall.proto"\n'
        f'EXTERNPROTO "{base}/obstacles/protos/OilBarrel.proto"\n'
        f'EXTERNPROTO "{base}/drinks/protos/Can.proto"\n'
        "SoccerBall { translation 0.5 0 0.113 }\nOilBarrel { translation -1 0 0.44 }\n"
        "Can { translation 0 0.5 0.0611 }\nE-puck { }\n"
    )
    _, report = import_wbt_text(text, str(tmp_path / "objects.wbt"))
    assert set(report["protos"]["stand_ins"]) == {"SoccerBall", "OilBarrel", "Can"}
    # The ball (0.6 kg, 0.226 m across) and the can are movable bodies; the barrel a static disc.
    ball, can = report["bodies"]
    assert ball["center"] == [0.5, 0.0] and ball["radius"] == pytest.approx(0.113)
    assert ball["mass"] == pytest.approx(0.6)
    assert can["center"] == [0.0, 0.5] and can["radius"] == pytest.approx(0.03175)
    (barrel,) = report["obstacles"]
    assert barrel["center"] == [-1.0, 0.0] and barrel["radius"] == 0.305
    # Each is held by its PROTO instance's node (its expansion is on the instance's line).
    assert barrel["owners"] == [6] and barrel["walls"][0] == 0
    assert (ball["owners"], can["owners"]) == ([5], [7])
    # Each is recognised by a camera's Recognition node in the colours its Webots PROTO writes
    # (Can.proto, OilBarrel.proto, SoccerBall.proto): a follower recognising a leader's Can
    # found nothing where the stand-in had none.
    colours = {o["line"]: o["colors"] for o in report["recognition"]["objects"]}
    assert colours == {
        5: pytest.approx([1.0, 1.0, 1.0, 0.0, 0.0, 0.0]),
        6: pytest.approx([0.4, 0.1, 0.1]),
        7: pytest.approx([0.666667, 0.0, 0.0]),
    }


def test_a_solid_torus_stands_in_as_its_ring_of_spheres(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    """Webots' guide: a SolidTorus is physically a set of ``subdivision`` spheres; here of radius
    0.1 on a circle of radius 0.07 about its translation. One without a bounding object is no
    obstacle."""
    report = _offline_import(
        monkeypatch,
        tmp_path,
        ["solids/protos/SolidTorus"],
        "DEF Obs1 SolidTorus {\n  translation -0.5 0.75 0\n  majorRadius 0.07\n"
        "  minorRadius 0.1\n  subdivision 4\n}\n"
        "SolidTorus { translation 1 1 0 enableBoundingObject FALSE }\nE-puck { }\n",
    )
    assert set(report["protos"]["stand_ins"]) == {"SolidTorus"}
    circles = [(o["center"], o["radius"], o["owners"]) for o in report["obstacles"]]
    assert circles == [
        ([-0.43, 0.75], 0.1, [3]),
        ([-0.5, 0.82], 0.1, [3]),
        ([-0.57, 0.75], 0.1, [3]),
        ([-0.5, 0.68], 0.1, [3]),
    ]


def test_a_projects_robot_proto_is_the_robot_with_its_devices() -> None:
    _, report = import_wbt(DATA / "project" / "worlds" / "robot_proto.wbt")
    assert report["robot_model"] == "E-puck" and report["robot_line"] == 4
    assert report["robot"] == pytest.approx({"x": 0.3, "y": 0.1, "yaw": 1.5708})
    assert [d["name"] for d in report["extension_devices"]] == ["heading"]
    # The controller field given by the PROTO's default picks the robot for that controller.
    _, chosen = import_wbt(DATA / "project" / "worlds" / "robot_proto.wbt", "course_controller")
    assert chosen["robot"] == report["robot"]


def test_a_projects_own_e_puck_proto_adds_its_devices_to_the_e_puck(tmp_path: Path) -> None:
    """Webots reads the project's protos/E-puck.proto before its own: the devices it adds (a GPS,
    a Compass named otherwise) are found by getDevice, the stock ones are not doubled, and the
    world's lines keep their numbers."""
    (tmp_path / "protos").mkdir()
    (tmp_path / "protos" / "E-puck.proto").write_text(
        "#VRML_SIM R2021a utf8\n"
        "PROTO E-puck [\n  field SFVec3f translation 0 0 0\n  field SFBool kinematic FALSE\n]\n"
        "{\n%{ local k = fields.kinematic.value }%\nRobot {\n  translation IS translation\n"
        '  children [\n    DistanceSensor { name "ps0" }\n'
        '    DEF HERE GPS { name "gps" }\n    Compass { name "heading" }\n  ]\n}\n}\n'
    )
    text = (
        "#VRML_SIM R2021a utf8\n"
        'E-puck {\n  name "a"\n  translation 0.1 0 0.2\n  turretSlot [\n    Compass { }\n  ]\n}\n'
        'E-puck {\n  name "b"\n  translation 0.5 0 0.5\n}\n'
    )
    world = tmp_path / "worlds" / "own.wbt"
    world.parent.mkdir()
    world.write_text(text)
    _, report = import_wbt(world)
    assert sorted(d["name"] for d in report["extension_devices"]) == ["compass", "gps", "heading"]
    assert report["robot_line"] == 2
    said = [w for w in report["warnings"] if "project's own E-puck PROTO" in w]
    assert len(said) == 1 and 'GPS "gps", Compass "heading"' in said[0]
    # The other e-puck, without a turretSlot of its own, gets one.
    _, other = import_wbt(world, robot_line=9)
    assert sorted(d["name"] for d in other["extension_devices"]) == ["gps", "heading"]
    assert other["robot_line"] == 9


def test_a_projects_own_e_puck_protos_device_comments_do_not_swallow_the_world(
    tmp_path: Path,
) -> None:
    """Webots 8's E-puck.proto documents its radio's fields in ``#`` comments, one with an
    unclosed quote: the devices it adds are mounted on one line, where a comment would run over
    the rest of the instance and the world's next nodes."""
    (tmp_path / "protos").mkdir()
    (tmp_path / "protos" / "E-puck.proto").write_text(
        "#VRML_SIM V8.5 utf8\n"
        "PROTO E-puck [\n  field SFVec3f translation 0 0 0\n]\n{\nDifferentialWheels {\n"
        "  translation IS translation\n  children [\n"
        '    Emitter {\n      type "radio"  # or "serial" or "infra-red\n'
        "      range -1  # -1 or positive\n      channel 3\n"
        '      name "radio"  # the one the controller asks for\n    }\n'
        '    GPS { name "gps" }\n  ]\n}\n}\n'
    )
    text = (
        "#VRML_SIM V8.5 utf8\n"
        'E-puck {\n  translation 0.1 0 0.2\n  controller "brain"\n}\n'
        "PointLight {\n  location 0 10 0\n}\n"
    )
    world = tmp_path / "worlds" / "old.wbt"
    world.parent.mkdir()
    world.write_text(text)
    _, report = import_wbt(world)
    devices = {d["name"]: d for d in report["extension_devices"]}
    assert sorted(devices) == ["gps", "radio"]
    assert devices["radio"]["fields"]["channel"] == 3


def test_hidden_engine_state_in_an_instance_is_skipped(tmp_path: Path) -> None:
    protos = tmp_path / "protos"
    protos.mkdir()
    shutil.copy(DATA / "project" / "protos" / "BoxWall.proto", protos)
    shutil.copy(DATA / "project" / "protos" / "Corridor.proto", protos)
    text = (
        "#VRML_SIM R2023b utf8\n"
        "Corridor {\n  translation 0 0 0\n  hidden linearVelocity_0 0 0 0\n"
        "  wallSize 0.5 0.02 0.1\n}\n"
        "Pose { children [\n  BoxWall {\n    translation 0.4 0.4 0.05\n"
        "    hidden rotation_1 0 0 1 0.2\n  }\n] }\nE-puck { }\n"
    )
    _, report = import_wbt_text(text, str(tmp_path / "worlds" / "hidden.wbt"))
    assert not [w for w in report["warnings"] if "is not a field" in w], report["warnings"]
    assert len(_boxes(report)) == 3
    assert report["robot_line"] == 13  # the lines after the expansions are the file's


def test_maze_blocks_stand_in_as_thin_wall_boxes_of_their_length(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.setenv("MAZESIM_OFFLINE", "1")
    url = (
        "https://raw.githubusercontent.com/cyberbotics/webots/R2023b/projects/samples/"
        "robotbenchmark/maze_runner/protos/MazeBlock.proto"
    )
    text = (
        f'#VRML_SIM R2023b utf8\nEXTERNPROTO "{url}"\n'
        'MazeBlock { name "a" length 0.2 }\n'
        'MazeBlock { translation 0 -0.21 0 rotation 0 0 1 1.5708 name "b" }\n'
        "E-puck { translation 0.3 0 0 }\n"
    )
    _, report = import_wbt_text(text, str(tmp_path / "maze.wbt"))
    assert set(report["protos"]["stand_ins"]) == {"MazeBlock"}
    assert [(o["center"], o["size"], o["yaw"]) for o in report["obstacles"]] == [
        ([0.0, 0.0], [0.015, 0.2], 0.0),
        ([0.0, -0.21], [0.015, 0.1], 1.5708),
    ]


def test_a_maze_block_of_a_y_up_world_lies_along_the_file_s_x(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    # The course mazes of R2020a-R2021a (NUE) lie their unrotated blocks along the file's x, as
    # their own map files show; the stand-in laid them along z, 90 degrees off. The file's x
    # is mazesim's -y.
    monkeypatch.setenv("MAZESIM_OFFLINE", "1")
    text = (
        '#VRML_SIM R2021a utf8\nWorldInfo { coordinateSystem "NUE" }\n'
        "MazeBlock { translation 0.1 0 -0.2 length 0.4 }\nE-puck { }\n"
    )
    _, report = import_wbt_text(text, str(tmp_path / "maze.wbt"))
    [block] = report["obstacles"]
    assert block["center"] == pytest.approx([0.2, -0.1]) and block["yaw"] == 0.0
    assert block["size"] == pytest.approx([0.015, 0.4])


def test_a_webots_6_wood_box_stands_in_as_a_box_of_its_box_size(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    # A Webots 6 world's walls of WoodBox: dropped as an unknown PROTO, the e-puck drove
    # through them. Y-up: boxSize x, y (up), z; centred on its translation; density 100, so a
    # 10 cm cube of 0.1 kg is a body the robot pushes, the 0.6 m default a static box.
    monkeypatch.setenv("MAZESIM_OFFLINE", "1")
    text = (
        "#VRML_SIM V6.0 utf8\nWorldInfo { }\n"
        "WoodBox { translation 0 0.05 -0.3 boxSize 1 0.1 0.1 }\n"
        "WoodBox { translation 0.3 0.05 0 }\n"
        "WoodBox { translation -0.3 0.05 0 boxSize 0.1 0.1 0.1 }\n"
        "EPuck { }\n"
    )
    _, report = import_wbt_text(text, str(tmp_path / "woodbox.wbt"))
    assert set(report["protos"]["stand_ins"]) == {"WoodBox"}
    # The Y-up file's -z is mazesim's x, its -x mazesim's y.
    boxes = sorted((o["center"], o["size"]) for o in report["obstacles"])
    assert boxes == [([0.0, -0.3], [0.6, 0.6]), ([0.3, 0.0], [0.1, 1.0])]
    [body] = report["bodies"]
    assert body["center"] == [0.0, 0.3] and body["mass"] == pytest.approx(0.1)


def test_fridges_tables_and_chairs_stand_in_as_their_documented_body_and_legs(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    """A fridge is a 0.7 m box an e-puck drives around; a table is four legs it drives between
    (its top is above the robot), in the corners of the given size, feet and padding; a chair
    four static legs, with physics or not."""
    monkeypatch.setenv("MAZESIM_OFFLINE", "1")
    base = "webots://projects/objects"
    text = (
        "#VRML_SIM R2023b utf8\n"
        f'EXTERNPROTO "{base}/kitchen/fridge/protos/Fridge.proto"\n'
        f'EXTERNPROTO "{base}/tables/protos/Table.proto"\n'
        f'EXTERNPROTO "{base}/chairs/protos/Chair.proto"\n'
        "Fridge { translation 2 0 0 }\n"
        "Table { translation -1 0 0 size 0.8 0.6 0.7 feetSize 0.04 0.06 feetPadding 0.01 }\n"
        "Chair { translation 1 1 0 physics Physics { } }\n"
        "E-puck { }\n"
    )
    _, report = import_wbt_text(text, str(tmp_path / "kitchen.wbt"))
    assert set(report["protos"]["stand_ins"]) == {"Fridge", "Table", "Chair"}
    assert not report["bodies"]
    fridge, *legs = _boxes(report)
    assert fridge == ([2.0, 0.0], [0.7, 0.7])
    table = sorted((round(c[0], 6), round(c[1], 6)) for c, _ in legs[:4])
    # 0.4 - 0.01 - 0.02 across, 0.3 - 0.01 - 0.03 along.
    assert table == [(-1.37, -0.26), (-1.37, 0.26), (-0.63, -0.26), (-0.63, 0.26)]
    assert all(size == [0.04, 0.06] for _, size in legs[:4])
    chair = sorted((round(c[0], 6), round(c[1], 6)) for c, _ in legs[4:])
    assert chair == [(0.78, 0.78), (0.78, 1.22), (1.22, 0.78), (1.22, 1.22)]
    assert all(size == [0.06, 0.06] for _, size in legs[4:])


@pytest.mark.parametrize(
    ("proto", "ys", "xs"),
    [
        # Before R2022a a Table's default size is 1.8 x 0.74 x 1 (the height second): its legs
        # stand 1.8 m apart across and 1 m along, not 1 m and 1.8 m.
        ("Table", [-0.85, 0.85], [-0.45, 0.45]),
        # The desk of those releases is 1.2 m along its x: its legs 1.07 m apart there.
        ("Desk", [-0.535, 0.535], [-0.32, 0.32]),
    ],
)
def test_tables_and_desks_of_a_y_up_world_keep_their_y_up_layout(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, proto: str, ys: list[float], xs: list[float]
) -> None:
    monkeypatch.setenv("MAZESIM_OFFLINE", "1")
    text = (
        f'#VRML_SIM R2021a utf8\nWorldInfo {{ coordinateSystem "NUE" }}\n{proto} {{ }}\n'
        "E-puck { translation 0 0 2 }\n"
    )
    _, report = import_wbt_text(text, str(tmp_path / "old.wbt"))
    # The file's x (across) is mazesim's y, its z (along) mazesim's x.
    assert sorted({round(c[1], 6) for c, _ in _boxes(report)}) == ys
    assert sorted({round(c[0], 6) for c, _ in _boxes(report)}) == xs


def test_apartment_furniture_stands_in_as_what_reaches_below_the_robots_top(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    """A sofa and an armchair are their feet (the robot drives under the seat), a desk and a
    wooden chair their legs, a window the wall below its sill; with the long side of each where
    the PROTO puts it."""
    monkeypatch.setenv("MAZESIM_OFFLINE", "1")
    base = "webots://projects/objects"
    text = (
        "#VRML_SIM R2023b utf8\n"
        f'EXTERNPROTO "{base}/living_room_furniture/protos/Sofa.proto"\n'
        f'EXTERNPROTO "{base}/living_room_furniture/protos/Armchair.proto"\n'
        f'EXTERNPROTO "{base}/tables/protos/Desk.proto"\n'
        f'EXTERNPROTO "{base}/chairs/protos/WoodenChair.proto"\n'
        f'EXTERNPROTO "{base}/apartment_structure/protos/Window.proto"\n'
        "Sofa { translation 2 0 0 }\n"
        "Armchair { translation -2 0 0 rotation 0 0 1 1.5708 }\n"
        "Desk { translation 0 2 0 }\n"
        "WoodenChair { translation 0 -2 0 physics Physics { } }\n"
        'Window { translation 3 3 0 size 0.3 1 2.4 name "low" }\n'
        'Window { translation -3 3 0 bottomWallHeight 0 name "none" }\n'
        "E-puck { }\n"
    )
    _, report = import_wbt_text(text, str(tmp_path / "apartment.wbt"))
    assert set(report["protos"]["stand_ins"]) == {
        "Sofa",
        "Armchair",
        "Desk",
        "WoodenChair",
        "Window",
    }
    assert not report["bodies"]

    def near(x: float, y: float) -> list[tuple[tuple[float, float], tuple[float, float]]]:
        return sorted(
            ((round(c[0], 4), round(c[1], 4)), (round(s[0], 4), round(s[1], 4)))
            for c, s in _boxes(report)
            if abs(c[0] - x) < 1 and abs(c[1] - y) < 1
        )

    feet = [(0.1, 0.1)] * 4
    sofa = near(2, 0)
    assert [c for c, _ in sofa] == [(1.65, -0.75), (1.65, 0.75), (2.35, -0.75), (2.35, 0.75)]
    assert [s for _, s in sofa] == feet
    # Turned a quarter: its 0.8 m between feet now along x.
    armchair = near(-2, 0)
    assert [c for c, _ in armchair] == [(-2.4, -0.35), (-2.4, 0.35), (-1.6, -0.35), (-1.6, 0.35)]
    desk = near(0, 2)
    assert [c for c, _ in desk] == [(-0.32, 1.465), (-0.32, 2.535), (0.32, 1.465), (0.32, 2.535)]
    assert all(s == (0.046, 0.046) for _, s in desk)
    chair = near(0, -2)
    assert [c for c, _ in chair] == [
        (-0.178, -2.17),
        (-0.178, -1.815),
        (0.178, -2.17),
        (0.178, -1.815),
    ]
    assert near(3, 3) == [((3.0, 3.0), (0.3, 1.0))]
    assert near(-3, 3) == []
    # Nothing of them passes over the robot: the stand-ins keep only what it meets.
    assert not [w for w in report["warnings"] if "above the floor passes over" in w]


def test_a_cabinet_stands_in_as_the_envelope_of_its_frame(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    """A cabinet reaches from its origin forward by its depth, is as wide as its columns and
    frame and centred across; one hung on a wall (its rows above the robot) is not a wall."""
    report = _offline_import(
        monkeypatch,
        tmp_path,
        ["cabinet/protos/Cabinet"],
        'Cabinet { translation 1 0 0 name "default" }\n'
        'Cabinet { translation -1 0 0 rotation 0 0 1 3.14159 name "small" depth 0.3 '
        "outerThickness 0.02 rowsHeights [ 0.2 0.2 ] columnsWidths [ 0.5 ] "
        'layout [ "Shelf (1, 2, 1, 0)" ] handle CabinetHandle { } }\n'
        'Cabinet { translation 0 1 0.9 name "hung" }\n'
        "E-puck { }\n",
    )
    assert set(report["protos"]["stand_ins"]) == {"Cabinet"}
    default, small = _boxes(report)
    # 0.5 deep forward of (1, 0); 0.06 + 0.74 wide.
    assert default[0] == pytest.approx([1.25, 0.0]) and default[1] == pytest.approx([0.5, 0.8])
    # Turned to face -x: 0.3 deep toward -x; 0.04 + 0.5 wide.
    assert small[0] == pytest.approx([-1.15, 0.0], abs=1e-5)
    assert small[1] == pytest.approx([0.3, 0.54])


def test_the_world_parser_reads_any_depth_when_asked_and_skips_inline_proto_definitions() -> None:
    from mazesim.errors import WorldFormatError
    from mazesim.webots.proto.syntax import MAX_DEPTH, nodes_in_order, parse_nodes

    depth = 3000
    text = "Group { children [ " * depth + "DEF DEEP Solid { }" + " ] }" * depth
    with pytest.raises(WorldFormatError, match=f"expected nodes nested at most {MAX_DEPTH} deep"):
        parse_nodes(text)
    every = list(nodes_in_order(parse_nodes(text, max_depth=None)))
    assert len(every) == depth + 1 and every[-1].def_name == "DEEP"
    # A PROTO written in a world is a definition, not nodes of the world.
    world = 'PROTO Post [ field SFFloat h 1 ] { Solid { name "inside" } }\nSolid { name "post" }'
    (post,) = parse_nodes(world)
    assert post.field("name") is not None and post.field("name").string() == "post"


def test_a_template_reads_field_values_as_the_world_parser_does() -> None:
    from mazesim.webots.proto.syntax import parse_nodes
    from mazesim.webots.proto.values import field_value

    # A word that is no number stays a word in both: no hexadecimal without 0x.
    assert field_value("MFFloat", "[ 1 cafe 0x10 -2 ]") == [1.0, 16.0, -2.0]
    assert field_value("MFString", '[ "a b" cafe ]') == ["a b", "cafe"]
    assert field_value("SFBool", "true") is True and field_value("SFNode", "NULL") is None
    (solid,) = parse_nodes("Solid { name 0x10 cafe 1 }")
    assert [t.value() for t in solid.field("name").tokens] == [16.0]


def test_line_numbers_give_the_line_counting_each_line_end_before_the_position() -> None:
    """The bisection over a text's line ends gives every position the line that counting the
    line ends before it gives (a long world's nodes were each counted anew)."""
    text = "Robot {\n  children [\n\n    Solid { }\n  ]\n}\nWall { }"
    from mazesim.webots.proto.syntax import line_numbers

    line_at = line_numbers(text)
    for position in range(len(text) + 1):
        assert line_at(position) == text.count("\n", 0, position) + 1
    assert line_at(text.index("Wall")) == 7


def test_a_sample_world_of_a_webots_tree_reads_its_projects_protos_from_that_tree(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    """Webots' own sample worlds name their project's PROTOs by ``webots://`` URLs (the
    curriculum's Obstacle): a world inside a checkout of Webots' repository reads them from that
    tree, offline and without a Webots installation, rather than leaving them out."""
    monkeypatch.setenv("MAZESIM_OFFLINE", "1")
    curriculum = tmp_path / "webots" / "projects" / "samples" / "curriculum"
    (curriculum / "protos").mkdir(parents=True)
    (curriculum / "worlds").mkdir()
    (curriculum / "protos" / "Pillar.proto").write_text(
        "#VRML_SIM R2023b utf8\n"
        "PROTO Pillar [ field SFVec3f translation 0 0 0.025 ] {\n"
        "  Solid { translation IS translation\n"
        "    boundingObject Box { size 0.04 0.06 0.05 } }\n"
        "}\n"
    )
    world = curriculum / "worlds" / "pillar.wbt"
    world.write_text(
        "#VRML_SIM R2023b utf8\n"
        'EXTERNPROTO "webots://projects/samples/curriculum/protos/Pillar.proto"\n'
        "Pillar { translation 0.2 0.1 0.025 }\n"
    )
    _, report = import_wbt(world)
    assert report["protos"]["expanded"] == {"Pillar": str(curriculum / "protos" / "Pillar.proto")}
    assert _boxes(report) == [([0.2, 0.1], [0.04, 0.06])]
    assert not [w for w in report["warnings"] if "unknown PROTO" in w]


def test_an_is_naming_a_field_the_proto_does_not_declare_is_left_unlinked(
    tmp_path: Path,
) -> None:
    # A course's copy of Webots' R2020b RobotisLds01 gives a CapScrew `enablePhysics IS physics`
    # without declaring `physics`; Webots (WbNode::createProtoInstance: copyAliasValue finds no
    # parameter of that name) leaves the field unlinked and loads the world, the inner node
    # keeping its default. The import did the same, where it stopped with WorldFormatError.
    (tmp_path / "protos").mkdir()
    (tmp_path / "worlds").mkdir()
    (tmp_path / "protos" / "Post.proto").write_text(
        "#VRML_SIM R2023b utf8\nPROTO Post [\n  field SFVec3f translation 0 0 0\n"
        "  field SFVec3f side 0.1 0.1 0.1\n]\n{\n  Solid {\n    translation IS translation\n"
        "    name IS label\n    boundingObject Box { size IS side }\n  }\n}\n"
    )
    (tmp_path / "worlds" / "w.wbt").write_text(
        '#VRML_SIM R2023b utf8\nEXTERNPROTO "../protos/Post.proto"\nRectangleArena { }\n'
        "Post { translation 0.3 0 0 }\nE-puck { }\n"
    )
    _, report = import_wbt(tmp_path / "worlds" / "w.wbt")
    (post,) = [o for o in report["obstacles"] if o["center"] == [0.3, 0.0]]
    assert post["size"] == [0.1, 0.1]
    (said,) = [w for w in report["warnings"] if "IS label" in w]
    assert "Post has no field `label`; left unlinked, as in Webots" in said


def _fan(tmp_path: Path) -> None:
    """A procedural PROTO that holds two of itself, one level deeper each, down to depth 10."""
    _project_proto(
        tmp_path,
        "Fan",
        "#VRML_SIM R2023b utf8\n# template language: javascript\n"
        "PROTO Fan [ field SFInt32 depth 0 field SFInt32 side 0 ]\n{\n"
        "  %< const d = fields.depth.value; >%\n  Group { children [\n"
        "  %< if (d < 10) { >% Fan { depth %<= d + 1 >% side 0 } Fan { depth %<= d + 1 >%"
        " side %<= fields.side.value >% } %< } >%\n  ] }\n}\n",
    )


def test_instances_of_the_same_fields_share_one_template_run(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # 2,047 instances, 11 distinct field values (the depth): 11 template runs, each a process
    # of its own, not 2,047.
    from mazesim.webots.proto import expander, templates

    _fan(tmp_path)
    runs: list[str] = []
    evaluate = templates.evaluate_template

    def counted(*args: Any) -> str:
        runs.append(args[4])
        return evaluate(*args)

    monkeypatch.setattr(expander, "evaluate_template", counted)
    world = str(tmp_path / "worlds" / "w.wbt")
    _, report = import_wbt_text("#VRML_SIM R2023b utf8\nFan { }\n", world)
    assert len(runs) == 11
    assert not [w for w in report["warnings"] if "templates" in w]


def test_a_world_running_more_templates_than_the_limit_says_so(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from mazesim.webots.proto import expander

    _fan(tmp_path)
    monkeypatch.setattr(expander, "MAX_TEMPLATE_RUNS", 5)
    world = str(tmp_path / "worlds" / "w.wbt")
    _, report = import_wbt_text("#VRML_SIM R2023b utf8\nFan { side 1 }\n", world)
    said = [w for w in report["warnings"] if "more than 5 PROTO templates" in w]
    assert said == [
        "the world runs more than 5 PROTO templates (instances whose fields differ); the rest"
        " are not expanded"
    ]


@pytest.mark.parametrize("value", ["nan", "inf", "-1e400"])
def test_an_int32_field_that_is_no_whole_number_is_a_world_format_error(
    tmp_path: Path, value: str
) -> None:
    from mazesim.errors import WorldFormatError

    _fan(tmp_path)
    with pytest.raises(WorldFormatError, match="an SFInt32 field: expected a whole number"):
        import_wbt_text(
            f"#VRML_SIM R2023b utf8\nFan {{ depth {value} }}\n", str(tmp_path / "worlds" / "w.wbt")
        )


def test_a_texture_image_larger_than_mazesim_reads_is_a_warning(tmp_path: Path) -> None:
    # A 1-bit PNG of 8200 x 8200 pixels is a few kilobytes; read as grey levels it would take
    # half a gigabyte.
    from PIL import Image

    from mazesim.webots.importer import MAX_TEXTURE_PIXELS

    assert 8200 * 8200 > MAX_TEXTURE_PIXELS
    Image.new("1", (8200, 8200)).save(tmp_path / "huge.png")
    world = (
        "#VRML_SIM R2023b utf8\nRectangleArena { floorSize 1 1 floorAppearance PBRAppearance {"
        ' baseColorMap ImageTexture { url ["huge.png"] } } }\n'
    )
    _, report = import_wbt_text(world, str(tmp_path / "w.wbt"))
    said = [w for w in report["warnings"] if "huge.png" in w]
    assert len(said) == 1 and "8200 x 8200 pixels, more than the" in said[0], said
    assert report["floor_paint"] == 0


def test_a_world_s_expansions_are_bounded_in_characters(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    """300 instances of a PROTO of 0.9 MB ran for more than ten minutes: the expansions of one
    world make at most MAX_EXPANDED_TEXT characters, the rest left out with one warning; the
    ones within keep their own field values (a body's links are read once, for every
    instance)."""
    from mazesim.webots.proto import expander

    (tmp_path / "protos").mkdir()
    (tmp_path / "protos" / "Pillar.proto").write_text(
        "#VRML_SIM R2023b utf8\nPROTO Pillar [ field SFVec3f translation 0 0 0 ] {\n"
        "  Solid { translation IS translation children [ DEF S Shape { geometry Box "
        "{ size 0.05 0.05 0.1 } } ] boundingObject USE S }\n}\n"
    )
    pillars = "".join(f"Pillar {{ translation {0.1 * i:.1f} 0.3 0.05 }}\n" for i in range(6))
    world = tmp_path / "pillars.wbt"
    world.write_text(
        '#VRML_SIM R2023b utf8\nEXTERNPROTO "../protos/Pillar.proto"\n'
        "WorldInfo { basicTimeStep 32 }\n" + pillars
    )
    (tmp_path / "worlds").mkdir()
    world = world.rename(tmp_path / "worlds" / "pillars.wbt")
    _, report = import_wbt(world)
    assert sorted(round(o["center"][0], 3) for o in report["obstacles"]) == [
        0.0, 0.1, 0.2, 0.3, 0.4, 0.5,
    ]  # fmt: skip
    monkeypatch.setattr(expander, "MAX_EXPANDED_TEXT", 400)
    _, report = import_wbt(world)
    kept = len(report["obstacles"])
    assert 0 < kept < 6, report["obstacles"]
    said = [w for w in report["warnings"] if "expand to more than 400 characters" in w]
    assert len(said) == 1, report["warnings"]


@pytest.mark.parametrize("kind", ["character device", "folder"])
def test_an_externproto_that_is_no_regular_file_is_refused_as_what_it_is(
    tmp_path: Path, kind: str
) -> None:
    # A PROTO path that is a link to /dev/zero was said to be "no such file" (then looked for
    # in protos/): it exists, and is left out for what it is, with a warning that says so.
    (tmp_path / "worlds").mkdir()
    (tmp_path / "protos").mkdir()
    target = tmp_path / "protos" / "Zero.proto"
    if kind == "folder":
        target.mkdir()
    else:
        target.symlink_to("/dev/zero")
    world = tmp_path / "worlds" / "w.wbt"
    world.write_text('#VRML_SIM R2023b utf8\nEXTERNPROTO "../protos/Zero.proto"\nZero { }\n')
    _, report = import_wbt(world)
    said = " ".join(report["warnings"])
    assert "no such file" not in said and "expected a regular file" in said, said
