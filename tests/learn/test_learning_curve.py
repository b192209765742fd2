"""The learning curve (``mazesim.learn.learning_curve``): ``mazesim train`` writes a CSV file
always, TensorBoard with ``--tensorboard``."""

from __future__ import annotations

import csv
import importlib.util
import struct
from pathlib import Path

import pytest

from mazesim.cli import main
from mazesim.learn.checkpoint import RunFolder
from mazesim.learn.learning_curve import CSV_COLUMNS, CURVE_FILE, TENSORBOARD_FOLDER, LearningCurve
from mazesim.learn.train import train
from training_settings import TINY

HAS_TENSORBOARDX = importlib.util.find_spec("tensorboardX") is not None


def rows(folder: Path) -> list[dict[str, str]]:
    with (folder / CURVE_FILE).open(newline="") as handle:
        reader = csv.DictReader(handle)
        assert tuple(reader.fieldnames or ()) == CSV_COLUMNS
        return list(reader)


def test_training_writes_every_round_and_episode(tmp_path: Path) -> None:
    with LearningCurve(tmp_path) as curve:
        assert train(TINY, RunFolder(tmp_path), curve=curve) is not None
    written = rows(tmp_path)
    lower = [row for row in written if row["stage"] == "lower"]
    higher = [row for row in written if row["stage"] == "higher"]
    assert len(lower) + len(higher) == len(written)
    assert [int(row["index"]) for row in lower] == [1, 2, 3]
    assert [int(row["env_steps"]) for row in lower] == [64 * 500 * k for k in (1, 2, 3)]
    assert all(0.0 <= float(row["door_success_right"]) <= 1.0 for row in lower)
    assert float(lower[0]["epsilon"]) > float(lower[-1]["epsilon"])
    assert all(row["goal_rate"] == "" for row in lower)
    # A point each time episodes end (several may end on one step).
    ends = [int(row["index"]) for row in higher]
    assert ends == sorted(set(ends)) and ends[-1] == 4
    assert all(0.0 <= float(row["goal_rate"]) <= 1.0 for row in higher)
    assert all(row["epsilon"] == "" for row in higher)


def test_a_resumed_run_writes_the_whole_curve_again(tmp_path: Path) -> None:
    whole, parts = tmp_path / "whole", tmp_path / "parts"
    with LearningCurve(whole) as curve:
        train(TINY, RunFolder(whole), curve=curve)
    with LearningCurve(parts) as curve:
        assert train(TINY, RunFolder(parts), curve=curve, stop_after_rounds=1) is None
    assert [row["index"] for row in rows(parts)] == ["1"]
    with LearningCurve(parts) as curve:
        train(TINY, RunFolder(parts, resume=True), curve=curve)
    assert rows(parts) == rows(whole)


def scalars(folder: Path) -> dict[str, list[tuple[int, float]]]:
    """The scalars of the TensorBoard event files in ``folder`` (TFRecord: length, its CRC,
    the event, its CRC)."""
    from tensorboardX.proto import event_pb2

    found: dict[str, list[tuple[int, float]]] = {}
    for path in sorted(folder.glob("events.out.tfevents.*")):
        data = path.read_bytes()
        at = 0
        while at < len(data):
            (length,) = struct.unpack("<Q", data[at : at + 8])
            event = event_pb2.Event.FromString(data[at + 12 : at + 12 + length])
            at += 12 + length + 4
            for value in event.summary.value:
                found.setdefault(value.tag, []).append((event.step, value.simple_value))
    return found


@pytest.mark.skipif(not HAS_TENSORBOARDX, reason="tensorboardX is not installed")
def test_tensorboard_gets_the_same_values(tmp_path: Path) -> None:
    with LearningCurve(tmp_path, tensorboard=True) as curve:
        train(TINY, RunFolder(tmp_path), curve=curve)
    logged = scalars(tmp_path / TENSORBOARD_FOLDER)
    lower = [row for row in rows(tmp_path) if row["stage"] == "lower"]
    assert [step for step, _ in logged["lower/contact_share"]] == [1, 2, 3]
    assert [value for _, value in logged["lower/contact_share"]] == pytest.approx(
        [float(row["contact_share"]) for row in lower]
    )
    higher = [row for row in rows(tmp_path) if row["stage"] == "higher"]
    assert [step for step, _ in logged["higher/goal_rate"]] == [int(r["index"]) for r in higher]


@pytest.mark.skipif(HAS_TENSORBOARDX, reason="tensorboardX is installed")
def test_tensorboard_without_its_package_is_one_clear_error(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["train", "--tensorboard", "--out", str(tmp_path / "run")]) == 2
    assert "mazesim[tensorboard]" in capsys.readouterr().err
    assert not (tmp_path / "run").exists()


def test_a_missing_tensorboardx_is_named(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    import builtins

    real_import = builtins.__import__

    def without_tensorboardx(name: str, *args: object, **options: object) -> object:
        if name == "tensorboardX":
            raise ImportError("No module named 'tensorboardX'")
        return real_import(name, *args, **options)  # type: ignore[arg-type]

    monkeypatch.setattr(builtins, "__import__", without_tensorboardx)
    from mazesim.errors import MissingDependencyError

    with pytest.raises(MissingDependencyError, match=r"mazesim\[tensorboard\]"):
        LearningCurve(tmp_path / "run", tensorboard=True)
    assert not (tmp_path / "run").exists()
