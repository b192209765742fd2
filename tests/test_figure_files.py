"""A figure is written as PNG whatever its file is named, so a name with another suffix
(``x.txt``, ``plot.pdf``) is refused naming the suffix it takes, by the one figure saver
(``mazesim._figures.save_png``, which every figure of the package goes through) and by the
command-line options that name a figure, before anything runs or is written (issue #15)."""

from __future__ import annotations

from pathlib import Path

import pytest

import mazesim
from mazesim.cli import main
from mazesim.plotting import save_trajectory_png


@pytest.mark.parametrize("name", ["x.txt", "plot.pdf", "p.json", "figure.png.svg"])
def test_a_figure_named_with_another_suffix_is_refused_and_not_written(
    tmp_path: Path, name: str
) -> None:
    path = tmp_path / name
    with pytest.raises(mazesim.InvalidArgumentError, match=r"ending in \.png .* found"):
        save_trajectory_png(mazesim.World.builtin("arena"), [0.0, 0.1], [0.0, 0.1], path)
    assert not path.exists()


@pytest.mark.parametrize("name", ["x.png", "X.PNG", "no-suffix"])
def test_a_png_name_or_one_without_a_suffix_is_written(tmp_path: Path, name: str) -> None:
    path = tmp_path / name
    save_trajectory_png(mazesim.World.builtin("arena"), [0.0, 0.1], [0.0, 0.1], path)
    assert path.read_bytes().startswith(b"\x89PNG")


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
    assert "expected a figure file ending in .png" in error and "Traceback" not in error, error
    assert list(tmp_path.iterdir()) == []
