"""Hostile inputs that mix things up (issue #15): a mazesim file of one kind given where another
kind is expected, a world saved under a name that reads back as another kind, and a cache folder
an environment variable places where a file is. Each is refused saying what it is and what to do,
not by the first field the other kind lacks or by a later step that cannot write."""

from __future__ import annotations

from pathlib import Path

import pytest

import mazesim
from mazesim.cli import main
from mazesim.errors import (
    InvalidArgumentError,
    MazesimIOError,
    PolicyFormatError,
    RunFormatError,
    UnknownNameError,
    WorldFormatError,
    WrongTypeError,
)
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
    assert "expected a Python, C, C++ or BotStudio controller" in said
    assert "found a TOML file (a mazesim world, given as --world" in said
    assert "NameError" not in said


class _BytesPath:
    """A path object whose ``__fspath__`` gives bytes."""

    def __fspath__(self) -> bytes:
        return bytes(WORLD)


@pytest.mark.parametrize("path", [bytes(WORLD), _BytesPath()], ids=["bytes", "bytes-pathlike"])
def test_every_path_argument_takes_the_same_paths(path: object) -> None:
    """``load_world`` read a path object giving bytes that ``World.load`` refused: every path
    argument now takes a str or an ``os.PathLike`` giving a str, and refuses bytes alike."""
    from mazesim.learn import load_policy
    from mazesim.replay import load_run

    for call in (
        mazesim.World.load,
        mazesim.load_world,
        mazesim.World.builtin("arena").save,
        load_run,
        load_policy,
    ):
        with pytest.raises(WrongTypeError, match=r"expected .*str (or|\|) os\.PathLike"):
            call(path)  # type: ignore[operator]


def test_a_json_loader_given_another_kind_of_file_names_it(tmp_path: Path) -> None:
    """The run and navigator readers said only "not JSON" of a world file."""
    from mazesim.learn import load_policy
    from mazesim.replay import load_run

    said = "found a mazesim world file: pass it as a world (`--world`"
    with pytest.raises(RunFormatError, match="expected a mazesim run") as refused:
        load_run(WORLD)
    assert said in str(refused.value)
    empty = tmp_path / "empty.json"
    empty.write_bytes(b"")
    with pytest.raises(RunFormatError, match="expected a mazesim run .*, found an empty file"):
        load_run(empty)
    navigator = tmp_path / "navigator"
    navigator.mkdir()
    (navigator / "policy.json").write_text(WORLD.read_text())
    with pytest.raises(PolicyFormatError, match="expected JSON metadata") as refused:
        load_policy(navigator)
    assert said in str(refused.value)
    with pytest.raises(PolicyFormatError, match="expected a navigator's folder") as refused:
        load_policy(WORLD)
    assert said in str(refused.value)


def test_a_sweep_file_that_is_another_kind_or_names_no_world_says_so(tmp_path: Path) -> None:
    from mazesim.distributed.config import load_sweep_config

    with pytest.raises(InvalidArgumentError, match="expected a sweep file") as refused:
        load_sweep_config(WORLD)
    assert "found a mazesim world file" in str(refused.value)
    sweep = tmp_path / "sweep.toml"
    sweep.write_text('[sweep]\n[grid]\nworld = "arnea"\n')
    with pytest.raises(UnknownNameError) as unknown:
        load_sweep_config(sweep)
    # The words of load_world and every other reader of a world's name.
    assert str(unknown.value).startswith(
        f"{sweep}: grid.world: no built-in world named 'arnea' and "
    )
    assert "(or a path to a .toml world file" in str(unknown.value)
    assert unknown.value.suggestion == "arena"


def test_a_sweep_files_world_not_found_is_looked_for_beside_the_sweep_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A world name that is neither built in nor a file beside the sweep file: the message said
    it was looked for in the current folder and meant none of the files beside the sweep file
    (#35)."""
    from mazesim.distributed.config import load_sweep_config

    (tmp_path / "sub").mkdir()
    (tmp_path / "elsewhere").mkdir()
    (tmp_path / "sub" / "mine.toml").write_text(WORLD.read_text())
    sweep = tmp_path / "sub" / "sweep.toml"
    monkeypatch.chdir(tmp_path / "elsewhere")
    for typed in ("mine", "mne.toml"):
        sweep.write_text(f'[sweep]\n[grid]\nworld = "{typed}"\n')
        with pytest.raises(UnknownNameError) as unknown:
            load_sweep_config(sweep)
        assert f"in {tmp_path / 'sub'};" in str(unknown.value)
        assert "elsewhere" not in str(unknown.value)
        assert unknown.value.suggestion == "mine.toml"


def test_a_proto_file_given_as_a_world_is_named_a_proto_file(tmp_path: Path) -> None:
    """A PROTO file imported as a world was an empty world, without a word."""
    proto = tmp_path / "Foo.proto"
    proto.write_text("#VRML_SIM R2023b utf8\nPROTO Foo [ ] { Solid { } }\n")
    with pytest.raises(WorldFormatError, match="found a Webots PROTO file"):
        import_wbt(str(proto))
