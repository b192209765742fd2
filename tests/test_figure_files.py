"""A figure is written in the format its suffix names (PNG, PDF, SVG; PNG without one), so a
name with another suffix (``x.txt``, ``plot.jpg``) is refused naming the suffixes it takes, by the
one figure saver (``mazesim._figures.save_figure``, which every figure of the package goes
through) and by the command-line options that name a figure, before anything runs or is
written."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

import mazesim
from mazesim._figures import save_figure
from mazesim.cli import main
from mazesim.plotting import save_trajectory_png


@pytest.mark.parametrize("name", ["x.txt", "plot.jpg", "p.json", "figure.svg.txt"])
def test_a_figure_named_with_another_suffix_is_refused_and_not_written(
    tmp_path: Path, name: str
) -> None:
    path = tmp_path / name
    with pytest.raises(
        mazesim.InvalidArgumentError, match=r"ending in \.png, \.pdf or \.svg .* found"
    ):
        save_trajectory_png(mazesim.World.builtin("arena"), [0.0, 0.1], [0.0, 0.1], path)
    assert not path.exists()


@pytest.mark.parametrize(
    ("name", "start"),
    [
        ("x.png", b"\x89PNG"),
        ("X.PNG", b"\x89PNG"),
        ("no-suffix", b"\x89PNG"),
        ("paper.pdf", b"%PDF"),
        ("paper.SVG", b"<?xml"),
    ],
)
def test_a_figure_is_written_in_the_format_its_suffix_names(
    tmp_path: Path, name: str, start: bytes
) -> None:
    """The same figure twice gives the same bytes: no creation date, no random SVG ids."""
    written = []
    for run in ("a", "b"):
        path = tmp_path / run / name
        path.parent.mkdir()
        save_trajectory_png(mazesim.World.builtin("arena"), [0.0, 0.1], [0.0, 0.1], path)
        written.append(path.read_bytes())
    assert written[0].startswith(start) and written[0] == written[1]


@pytest.mark.parametrize(
    "arguments",
    [["show", "arena", "-o", "arena.svg"], ["eval", "--episodes", "1", "--plot", "arena.pdf"]],
)
def test_a_figure_option_writes_a_pdf_or_svg(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, arguments: list[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    assert main([*arguments, *(["--max-steps", "10"] if arguments[0] == "eval" else [])]) == 0
    data = (tmp_path / arguments[-1]).read_bytes()
    assert data.startswith(b"<?xml" if arguments[-1].endswith(".svg") else b"%PDF")


@pytest.mark.parametrize(
    "arguments",
    [
        ["show", "arena", "-o", "x.txt"],
        ["eval", "--episodes", "1", "--max-steps", "10", "--plot", "p.json"],
    ],
)
def test_a_figure_option_with_another_suffix_is_refused_before_the_command_runs(
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
    arguments: list[str],
) -> None:
    monkeypatch.chdir(tmp_path)
    assert main(arguments) == 2
    error = capsys.readouterr().err
    assert "expected a figure file ending in .png, .pdf or .svg" in error, error
    assert "Traceback" not in error
    assert list(tmp_path.iterdir()) == []


def test_a_lone_surrogate_is_drawn_escaped_in_every_text_of_a_figure(tmp_path: Path) -> None:
    """A file name's undecodable byte reaches a title as a lone surrogate (``\\xff`` decodes to
    ``\\udcff``), which FreeType refused to lay out (a TypeError from matplotlib): every text of a
    figure (title, axis label, legend, annotation, and the tick labels matplotlib formats only
    while it draws, categories among them) is drawn with it escaped; the figure's own texts are
    left as they were."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    figure = Figure()
    axes, bars = figure.subplots(1, 2)
    axes.plot([0, 1], [0, 1], label="run \udcff")
    axes.set_title("world \udcff: controller \ud800")
    axes.set_xlabel("x \udc80 (m)")
    axes.set_xticks([0, 1], ["tick \udcfd", "1"])
    axes.legend()
    axes.annotate("goal \udfff", (0.5, 0.5))
    bars.bar(["group \udcfc", "b"], [1.0, 2.0])
    figure.suptitle("caf\u00e9 \udcfe")
    for name in ("figure.png", "figure.svg"):
        save_figure(figure, tmp_path / name)
    assert (tmp_path / "figure.png").read_bytes().startswith(b"\x89PNG")
    drawn = (tmp_path / "figure.svg").read_text(encoding="utf-8")
    for text in (
        "world \\xff: controller \\ud800",
        "x \\x80 (m)",
        "run \\xff",
        "goal \\udfff",
        "caf\u00e9 \\xfe",
        "tick \\xfd",
        "group \\xfc",
    ):
        assert text in drawn, text
    assert axes.get_title() == "world \udcff: controller \ud800"


def test_a_trajectory_titled_after_an_undecodable_file_name_is_written(tmp_path: Path) -> None:
    path = tmp_path / "trajectory.svg"
    title = os.fsdecode(b"maze-\xff: avoid-collision")
    save_trajectory_png(mazesim.World.builtin("arena"), [0.0, 0.1], [0.0, 0.1], path, title=title)
    assert "maze-\\xff: avoid-collision" in path.read_text(encoding="utf-8")


def test_webots_run_of_a_controller_whose_file_name_is_undecodable_draws_its_picture(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The run's picture is titled after the controller's file name: one whose name holds a byte
    that is no UTF-8 (``\\xff``) ended the run with matplotlib's TypeError (exit 2)."""
    monkeypatch.chdir(tmp_path)
    name = os.fsdecode(b"\xff")
    Path(name).write_text(
        "from controller import Robot\nrobot = Robot()\nwhile robot.step(32) != -1:\n    pass\n",
        encoding="utf-8",
    )
    assert main(["webots", "run", name, "--no-noise", "--seconds", "1"]) == 0
    assert (tmp_path / "mazesim-webots" / "trajectory.png").read_bytes().startswith(b"\x89PNG")


def test_a_legend_beside_a_world_drawn_to_scale_is_written_whole(tmp_path: Path) -> None:
    """``tight_layout`` makes no room for a legend beside axes that keep their aspect (a world
    drawn to scale): the default world's trajectory picture was cut through its legend and its
    y label. The subplots are moved in to make room, at the figure's own size; a figure that
    fits is written as it was."""
    from matplotlib.figure import Figure
    from PIL import Image

    def picture(label: str, name: str) -> tuple[tuple[int, int], Figure]:
        figure = Figure(figsize=(4.0, 3.0), dpi=100)
        axes = figure.add_subplot()
        axes.plot([0, 1], [0, 1], label=label)
        axes.set_aspect("equal")
        axes.set_ylabel("y (m)")
        axes.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=7)
        save_figure(figure, tmp_path / name)
        with Image.open(tmp_path / name) as image:
            return image.size, figure

    size, figure = picture("floor paint (grey = reflectance)", "wide.png")
    drawn = figure.get_tightbbox()
    assert size == (400, 300)
    assert drawn.x0 >= 0.0 and drawn.y0 >= 0.0 and drawn.x1 <= 4.0 and drawn.y1 <= 3.0, drawn
    size, figure = picture("a", "fits.png")
    assert size == (400, 300) and figure.subplotpars.right > 0.7
    world = mazesim.World.builtin("seed-maze")
    for name in ("seed.png", "seed.svg"):
        save_trajectory_png(world, [0.0, 0.1], [0.0, 0.1], tmp_path / name)
    text = (tmp_path / "seed.svg").read_text(encoding="utf-8")
    width = float(text.split('width="', 1)[1].split("pt", 1)[0])
    with Image.open(tmp_path / "seed.png") as image:
        assert image.size[0] == 8 * 120 and width == 8 * 72, (image.size, width)
