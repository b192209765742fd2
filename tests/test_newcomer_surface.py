"""What a newcomer meets first in a notebook or a shell: ``mazesim.<Tab>`` offers the API, and a
world or a simulator left as a cell's last line is drawn."""

from __future__ import annotations

import importlib
import io
from pathlib import Path

import pytest

import mazesim


@pytest.mark.parametrize(
    "name", ["mazesim", "mazesim.envs", "mazesim.learn", "mazesim.controllers"]
)
def test_tab_completion_offers_the_api_not_the_modules_own_imports(name: str) -> None:
    module = importlib.import_module(name)
    listed = dir(module)
    assert set(module.__all__) <= set(listed)
    for own_import in ("annotations", "os", "importlib", "sys"):
        assert own_import not in listed, f"dir({name}) offers {own_import}"
    assert listed == sorted(listed)


def test_tab_completion_offers_the_imported_submodules() -> None:
    import mazesim.envs  # noqa: F401

    assert "envs" in dir(mazesim) and "errors" in dir(mazesim)
    assert "__version__" in dir(mazesim) and "__doc__" in dir(mazesim)


def _picture(obj: object) -> tuple[int, int, bytes]:
    from PIL import Image

    ipython = pytest.importorskip("IPython.core.interactiveshell")
    shell = ipython.InteractiveShell.instance()
    shown, _ = shell.display_formatter.format(obj)
    data = shown["image/png"]
    with Image.open(io.BytesIO(data)) as image:
        return image.width, image.height, image.convert("RGB").tobytes()


def test_a_notebook_draws_a_world_and_a_simulator_not_their_repr() -> None:
    world = mazesim.load_world("seed-maze")
    width, height, drawn = _picture(world)
    assert (width, height) == (400, 400)
    sim = mazesim.Simulator(world, robot="e-puck", seed=0)
    at_start = _picture(sim)[2]
    for _ in range(100):
        sim.step(5.0, 5.0)
    moved = _picture(sim)[2]
    assert len({drawn, at_start, moved}) == 3  # the robot is drawn where it is
    assert repr(world).startswith("World(") and "\n" not in repr(world)


@pytest.mark.parametrize(
    ("argv", "told"),
    [
        (["worlds", "export", "seed-maze"], "did you mean '--export' for 'export'?"),
        (["demo", "seconds", "5"], "did you mean '--seconds' for 'seconds'?"),
        (["eval", "json"], "did you mean '--json' for 'json'?"),
        (["train", "world", "seed-maze"], "did you mean '--world' for 'world'?"),
        (["eval", "Episodes=3"], "did you mean '--episodes' for 'Episodes'?"),
        (["replay", "run.json", "-o", "x.html", "episode", "2"], "'--episode' for 'episode'"),
    ],
)
def test_an_option_typed_without_its_dashes_is_told_the_option(
    capsys: pytest.CaptureFixture[str], argv: list[str], told: str
) -> None:
    from mazesim.cli import main

    assert main(argv) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line.startswith(f"mazesim {argv[0]}: error: unrecognized arguments: "), line
    assert told in line, line


@pytest.mark.parametrize("argv", [["demo", "banana"], ["eval", "5"], ["worlds", "seed-maze"]])
def test_a_stray_word_like_no_option_is_told_none(
    capsys: pytest.CaptureFixture[str], argv: list[str]
) -> None:
    from mazesim.cli import main

    assert main(argv) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line.endswith(f"unrecognized arguments: {argv[1]}"), line


@pytest.mark.parametrize(
    ("argv", "told"),
    [
        (["show", "seed-maze", "out", "q.png"], "show: error: argument WORLD: 'out' is no file"),
        (["replay", "out", "-o", "x.html"], "replay: error: argument RUN: 'out' is no file"),
    ],
)
def test_an_option_without_dashes_taken_as_an_argument_is_told_the_option(
    capsys: pytest.CaptureFixture[str],
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    argv: list[str],
    told: str,
) -> None:
    from mazesim.cli import main

    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line == f"mazesim {told}; did you mean the option '--out'?", line
    assert list(tmp_path.iterdir()) == []  # nothing written
    # A file of that name is what was meant: it is taken, not refused.
    (tmp_path / "out").write_text("not a world\n", encoding="utf-8")
    assert main(argv) == 2
    assert "did you mean the option" not in capsys.readouterr().err


_WORLD = mazesim.load_world("arena")


@pytest.mark.parametrize(
    "call",
    [
        lambda given: mazesim.Simulator(given),
        lambda given: mazesim.Simulator(_WORLD).change_world(given),
        lambda given: mazesim.BatchSimulator(given, 2),
        lambda given: mazesim.BatchSimulator([_WORLD, given]),
        lambda given: mazesim.BatchSimulator(_WORLD, 2).set_world(0, given, 1),
    ],
    ids=["Simulator", "change_world", "BatchSimulator", "BatchSimulator list", "set_world"],
)
@pytest.mark.parametrize("given", ["seed-maze", Path("mazes/mine.toml")], ids=["name", "path"])
def test_a_world_name_or_path_where_a_world_goes_is_told_load_world(call, given) -> None:
    with pytest.raises(mazesim.WrongTypeError) as refused:
        call(given)
    message = str(refused.value)
    assert f"mazesim.load_world({given!r})" in message, message
    assert "expected" in message and "found a" in message, message
