"""``mazesim show``: world previews with a legend, and the legends of trajectory pictures."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from matplotlib.figure import Figure

import mazesim
from mazesim.cli import main
from mazesim.learn.figures import decision_label
from mazesim.plotting import plot_world, trajectory_legend, world_legend_handles
from mazesim.replay.preview import load_with_warnings

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
WBT_FOLDER = Path(__file__).parents[1] / "data" / "webots-worlds"
WBT_FILES = sorted(WBT_FOLDER.glob("*.wbt"))


def png_size(path: Path) -> tuple[int, int]:
    data = path.read_bytes()
    assert data.startswith(PNG_MAGIC)
    return int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")


def test_show_renders_every_builtin_world(
    builtin_name: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = tmp_path / f"{builtin_name}.png"
    assert main(["show", builtin_name, "-o", str(path)]) == 0
    width, height = png_size(path)
    assert width > 800 and height > 400
    printed = capsys.readouterr().out
    assert f"wrote {path}\n" in printed and "importer warnings" not in printed


def test_show_writes_name_png_here_by_default(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    assert main(["show", "arena"]) == 0
    assert png_size(tmp_path / "arena.png")[0] > 0


@pytest.mark.parametrize(
    ("name", "picture"),
    [
        ("../escaped", "escaped.png"),
        ("", "named.png"),  # no name: the file's
        ("/tmp/a b", "a-b.png"),
        ("..", "world.png"),
    ],
)
def test_a_world_name_names_a_file_here_never_a_folder(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, name: str, picture: str
) -> None:
    here = tmp_path / "here"
    here.mkdir()
    monkeypatch.chdir(here)
    world = mazesim.World.from_toml(
        f'format = "mazesim-world"\nversion = 1\nname = {name!r}\n'.replace("'", '"')
    )
    world.save("named.toml")
    assert main(["show", "named.toml"]) == 0
    assert sorted(path.name for path in here.iterdir()) == sorted(["named.toml", picture])
    assert sorted(path.name for path in tmp_path.iterdir()) == ["here"]


def test_show_renders_a_world_file(tmp_path: Path) -> None:
    world_file = tmp_path / "maze.toml"
    mazesim.generate_maze(3, 4, seed=5).save(str(world_file))
    assert main(["show", str(world_file), "-o", str(tmp_path / "maze.png")]) == 0
    assert png_size(tmp_path / "maze.png")[0] > 0


def test_a_world_file_gets_no_importer_note_in_its_picture(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # A newcomer's hand-written .toml maze was drawn with "no importer warnings" beside it,
    # although nothing was imported; a .wbt world keeps its note, even with no warning.
    written: list[str] = []
    drawn = Figure.text

    def recording(self: Figure, x: float, y: float, text: str, **kwargs: object) -> object:
        written.append(text)
        return drawn(self, x, y, text, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(Figure, "text", recording)
    world_file = tmp_path / "maze.toml"
    mazesim.generate_maze(3, 3, seed=1).save(str(world_file))
    assert main(["show", str(world_file), "-o", str(tmp_path / "maze.png")]) == 0
    assert not any("importer" in text for text in written)
    assert main(["show", str(WBT_FILES[0]), "-o", str(tmp_path / "wbt.png")]) == 0
    assert any("importer warnings" in text for text in written)


@pytest.mark.parametrize("wbt", WBT_FILES, ids=[path.name for path in WBT_FILES])
def test_show_renders_every_real_webots_world(
    wbt: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    _, warnings = load_with_warnings(str(wbt))
    assert warnings is not None
    path = tmp_path / "world.png"
    assert main(["show", str(wbt), "-o", str(path)]) == 0
    assert png_size(path)[0] > 0
    assert f"({len(warnings)} importer warnings)" in capsys.readouterr().out


def test_the_real_webots_worlds_are_all_there() -> None:
    assert len(WBT_FILES) >= 6


def test_a_missing_world_is_a_clear_error(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["show", "no-such-world"]) == 2
    assert "no-such-world" in capsys.readouterr().err


def test_world_legend_names_what_is_drawn() -> None:
    labels = [
        handle.get_label() for handle in world_legend_handles(mazesim.load_world("seed-maze"))
    ]
    assert labels == [
        "walls",
        "floor paint (grey = reflectance)",
        "checkpoint (its id)",
        "start pose",
        "goal",
    ]
    arena = [handle.get_label() for handle in world_legend_handles(mazesim.load_world("arena"))]
    assert "goal" not in arena and "checkpoint (its id)" not in arena


def test_trajectory_legend_adds_the_paths_entries() -> None:
    world = mazesim.load_world("seed-maze")
    ax = Figure().add_subplot()
    plot_world(ax, world)
    extra = ax.plot([0.1, 0.2], [0.1, 0.2], label="path")
    trajectory_legend(ax, world, extra)
    legend = ax.get_legend()
    assert legend is not None
    assert [text.get_text() for text in legend.get_texts()][-1] == "path"


def test_decision_labels_cannot_be_read_as_checkpoint_ids() -> None:
    assert decision_label(3, 5, 2) == "D3: left turn at checkpoint +5"
    assert decision_label(1, -7, 0) == "D1: corridors and corners at checkpoint -7"
    assert decision_label(2, 4, 3) == "D2: straight on at checkpoint +4"


def test_trajectory_png_marks_collisions(tmp_path: Path) -> None:
    from mazesim.plotting import save_trajectory_png

    world = mazesim.load_world("arena")
    xs = np.linspace(0.0, 0.3, 20)
    save_trajectory_png(world, xs, xs, tmp_path / "a.png", collisions=[[0.1, 0.1], [0.2, 0.2]])
    save_trajectory_png(world, xs, xs, tmp_path / "b.png")
    assert png_size(tmp_path / "a.png") == png_size(tmp_path / "b.png")
    assert (tmp_path / "a.png").read_bytes() != (tmp_path / "b.png").read_bytes()
