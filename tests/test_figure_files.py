"""A figure is written in the format its suffix names (PNG, PDF, SVG; PNG without one), so a
name with another suffix (``x.txt``, ``plot.jpg``) is refused naming the suffixes it takes, by the
one figure saver (``mazesim._figures.save_figure``, which every figure of the package goes
through) and by the command-line options that name a figure, before anything runs or is
written."""

from __future__ import annotations

from pathlib import Path

import pytest

import mazesim
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
