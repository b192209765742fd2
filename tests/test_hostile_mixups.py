"""Hostile inputs that mix things up (issue #15): a mazesim file of one kind given where another
kind is expected, a world saved under a name that reads back as another kind, and a cache folder
an environment variable places where a file is. Each is refused saying what it is and what to do,
not by the first field the other kind lacks or by a later step that cannot write."""

from __future__ import annotations

from pathlib import Path

import pytest

import mazesim
from mazesim.cli import main
from mazesim.errors import InvalidArgumentError, MazesimIOError, WorldFormatError
from mazesim.webots.importer import import_wbt
from mazesim.webots.native_controller import cache_folder
from mazesim.webots.proto import cache_dir, fetch_url

REPO = Path(__file__).resolve().parents[1]
WORLD = REPO / "worlds" / "arena.toml"
PROFILE = REPO / "robots" / "e-puck.toml"
RUN = '{\n  "format": "mazesim-run",\n  "version": "1.3"\n}\n'


def test_a_world_file_given_as_a_robot_is_named_a_world_file(
    capsys: pytest.CaptureFixture[str],
) -> None:
    said = "expected a robot profile, found a mazesim world file: pass it as a world (`--world`"
    with pytest.raises(
        WorldFormatError, match=r"arena\.toml:1:1: field `\(top level\)`"
    ) as refused:
        mazesim.RobotProfile.load(str(WORLD))
    assert said in str(refused.value)
    assert main(["eval", "--robot", str(WORLD)]) == 2
    assert said in capsys.readouterr().err


def test_a_profile_or_a_run_given_as_a_world_is_named_for_what_it_is(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(WorldFormatError, match="found a robot profile: pass it as a robot"):
        mazesim.load_world(PROFILE)
    assert main(["show", str(PROFILE)]) == 2
    assert "expected a mazesim world file, found a robot profile" in capsys.readouterr().err
    run = tmp_path / "run.json"
    run.write_text(RUN)
    with pytest.raises(WorldFormatError, match="found a recorded run: replay it with"):
        mazesim.load_world(run)
    with pytest.raises(
        WorldFormatError, match=r"expected a Webots world \(\.wbt\), found a mazesim"
    ):
        import_wbt(str(WORLD))


def test_a_world_is_saved_only_under_a_name_read_back_as_a_world(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    arena = mazesim.World.builtin("arena")
    for name in ("w.wbt", "w.png", "w"):
        with pytest.raises(InvalidArgumentError, match="expected a world file ending in .toml"):
            arena.save(tmp_path / name)
        assert not (tmp_path / name).exists()
    with pytest.raises(InvalidArgumentError, match="read back as a Webots world"):
        arena.save(str(tmp_path / "w.WBT"))
    arena.save(tmp_path / "w.TOML")
    assert mazesim.load_world(tmp_path / "w.TOML") == arena
    # A device is written into whatever its name (the export refused /dev/null for its name):
    # the full disk says so.
    with pytest.raises(MazesimIOError, match="No space left on device"):
        arena.save("/dev/full")
    assert main(["worlds", "--export", "arena", "-o", "/dev/full", "--force"]) == 2
    assert "/dev/full: cannot write the file: No space left on device" in capsys.readouterr().err
    assert main(["worlds", "--export", "arena", "-o", "/dev/null", "--force"]) == 0


def test_a_cache_variable_naming_a_file_is_refused_naming_the_variable(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    file = tmp_path / "cache"
    file.write_text("not a folder")
    monkeypatch.setenv("MAZESIM_OFFLINE", "1")
    monkeypatch.setenv("MAZESIM_PROTO_CACHE", str(file))
    with pytest.raises(MazesimIOError, match=r"\$MAZESIM_PROTO_CACHE names .* it is a file, not a"):
        fetch_url("https://example.invalid/Thing.proto")
    monkeypatch.setenv("MAZESIM_CACHE", str(file))
    with pytest.raises(MazesimIOError, match="but above it, .*cache, is a file, not a folder"):
        cache_folder()
    monkeypatch.setenv("MAZESIM_PROTO_CACHE", str(tmp_path / "new" / "protos"))
    assert cache_dir() == tmp_path / "new" / "protos"


def test_a_world_file_given_as_a_controller_is_not_run_as_python(
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert main(["webots", "run", str(WORLD), "--seconds", "1"]) == 2
    said = capsys.readouterr().err
    assert "expected a Python, C or C++ controller" in said
    assert "found a TOML file (a mazesim world, given as --world" in said
    assert "NameError" not in said
