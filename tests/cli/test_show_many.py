"""``mazesim show`` takes several worlds (a folder of mazes, ``mazesim show mazes/*.toml``):
a picture each, named after each world; ``-o`` with several, or two worlds of one name, are
refused before any picture is written (#37)."""

from __future__ import annotations

from pathlib import Path

import pytest

import mazesim
from mazesim.cli import main


def _mazes(folder: Path, *seeds: int) -> list[str]:
    paths = []
    for seed in seeds:
        path = folder / f"maze{seed}.toml"
        mazesim.generate_maze(4, 4, seed=seed).save(str(path))
        paths.append(str(path))
    return paths


def test_several_worlds_each_get_their_picture(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    assert main(["show", *_mazes(tmp_path, 1, 2), "arena"]) == 0
    out = capsys.readouterr().out
    pictures = sorted(p.name for p in tmp_path.glob("*.png"))
    assert pictures == ["arena.png", "maze-4x4-seed1.png", "maze-4x4-seed2.png"], out
    assert out.count("wrote ") == 3
    assert "mazesim train --world" in out and "maze1.toml" in out and "maze2.toml" in out


def test_o_with_several_worlds_is_refused_before_anything_is_written(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    assert main(["show", "arena", "seed-maze", "-o", "x.png"]) == 2
    error = capsys.readouterr().err
    assert "expected one WORLD with -o" in error and "found 2 worlds" in error, error
    assert list(tmp_path.glob("*.png")) == []


def test_two_worlds_of_one_name_are_refused_before_anything_is_written(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    (first,) = _mazes(tmp_path, 1)
    (tmp_path / "copy").mkdir()
    second = tmp_path / "copy" / "maze1.toml"
    second.write_bytes(Path(first).read_bytes())
    assert main(["show", first, str(second)]) == 2
    error = capsys.readouterr().err
    assert "both named 'maze-4x4-seed1'" in error and "one at a time with -o" in error, error
    assert list(tmp_path.glob("*.png")) == []
