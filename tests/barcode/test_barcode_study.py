"""The barcode reading study (report Fig. 4.3 and 4.5) and ``mazesim barcode-study``."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import mazesim
from mazesim.barcode.link import ROS_LINK_PERIODS, UnsyncedLink
from mazesim.barcode.study import (
    DEFAULT_SPEED,
    DEFAULT_THRESHOLDS,
    StudyResult,
    Tally,
    random_start_worlds,
    run_study,
)
from mazesim.cli import main
from mazesim.errors import InvalidArgumentError, UnknownNameError

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
TWICE_DEFAULT_SPEED = 2 * DEFAULT_SPEED


@pytest.fixture(scope="module")
def study() -> StudyResult:
    """The study's defaults (200 readings a setting, seed 0), with the speed study reduced to
    the default speed and twice it."""
    return run_study(
        readings=200, thresholds=DEFAULT_THRESHOLDS, speeds=(DEFAULT_SPEED, TWICE_DEFAULT_SPEED)
    )


def tallies(rows: list[Tally], decoder: str) -> list[Tally]:
    return [t for t in rows if t.decoder == decoder]


def test_every_reading_is_right_wrong_or_missed(study: StudyResult) -> None:
    for tally in study.by_threshold + study.by_speed:
        assert tally.readings == 200
        assert tally.right + tally.wrong + tally.missed == 200


def test_robust_reads_99_percent_right_at_the_default_speed(study: StudyResult) -> None:
    rows = tallies(study.by_threshold, "robust")
    assert [t.threshold_v for t in rows] == list(DEFAULT_THRESHOLDS)
    for tally in rows:
        assert tally.speed == DEFAULT_SPEED
        assert tally.share(tally.right) >= 0.99, tally
        assert tally.wrong == 0 and tally.spurious == 0, tally


def test_robust_reads_95_percent_right_at_twice_the_default_speed(study: StudyResult) -> None:
    (fast,) = [t for t in tallies(study.by_speed, "robust") if t.speed == TWICE_DEFAULT_SPEED]
    assert fast.share(fast.right) >= 0.95, fast


def test_alg7_reads_worse_at_higher_thresholds(study: StudyResult) -> None:
    rows = tallies(study.by_threshold, "alg7")
    thresholds = np.array([t.threshold_v for t in rows])
    failed = np.array([1.0 - t.share(t.right) for t in rows])
    wrong = np.array([t.share(t.wrong) for t in rows])
    # The report's Fig. 4.3: nearly all right at 1.2 and 1.4 V, fewer at higher thresholds.
    assert failed[0] < failed[-1] and wrong[0] < wrong[-1]
    assert np.polyfit(thresholds, failed, 1)[0] > 0.0
    assert np.polyfit(thresholds, wrong, 1)[0] > 0.0
    assert min(t.share(t.right) for t in rows[:2]) >= 0.9


def test_robust_beats_alg7_everywhere(study: StudyResult) -> None:
    rows = study.by_threshold + study.by_speed
    for alg7, robust in zip(tallies(rows, "alg7"), tallies(rows, "robust")):
        assert robust.right >= alg7.right and robust.wrong <= alg7.wrong


def test_json_object(study: StudyResult) -> None:
    document = json.loads(json.dumps(study.to_json()))
    assert {row["decoder"] for row in document["by_threshold"]} == {"alg7", "robust"}
    assert [row["threshold_v"] for row in document["by_threshold"][::2]] == list(DEFAULT_THRESHOLDS)
    assert [row["speed"] for row in document["by_speed"][::2]] == [3.14, 6.28]
    for row in document["by_threshold"] + document["by_speed"]:
        for key in ("right", "wrong", "missed"):
            assert 0.0 <= row[key] <= 1.0
        assert row["right"] + row["wrong"] + row["missed"] == pytest.approx(1.0)


@pytest.fixture(scope="module")
def ros_study() -> StudyResult:
    """Alg. 7 over the unsynchronised link of the report's ROS node, 200 readings a setting."""
    return run_study(
        readings=200,
        thresholds=(1.2, 2.0),
        speeds=(DEFAULT_SPEED / 2, DEFAULT_SPEED, TWICE_DEFAULT_SPEED),
        decoders=("alg7",),
        link="ros",
    )


def test_alg7_over_the_ros_link_reads_worse_at_higher_speeds(ros_study: StudyResult) -> None:
    # The report's Fig. 4.5: "with more speed the sensors do less reading". Below the default
    # speed the link loses little (over ten seeds 2.9 % wrong at half the default speed, 3.6 % at
    # it), too little to tell apart in 200 readings; above it whole bars go unseen.
    rows = ros_study.by_speed
    assert [t.speed for t in rows] == [DEFAULT_SPEED / 2, DEFAULT_SPEED, TWICE_DEFAULT_SPEED]
    wrong = [t.wrong for t in rows]
    right = [t.right for t in rows]
    assert max(wrong[0], wrong[1]) < wrong[2], rows
    assert min(right[0], right[1]) > right[2], rows
    assert rows[-1].share(rows[-1].wrong) >= 0.08, rows[-1]


def test_alg7_over_the_ros_link_reads_worse_at_a_higher_threshold(ros_study: StudyResult) -> None:
    low, high = ros_study.by_threshold
    assert (low.threshold_v, high.threshold_v) == (1.2, 2.0)
    assert high.right < low.right and high.wrong >= low.wrong, (low, high)
    assert ros_study.to_json()["link"] == "ros"


def test_unsynced_link_wakes_each_node_after_one_to_three_steps() -> None:
    link = UnsyncedLink(50, seed=7)
    wakes = np.array([link.tick() for _ in range(300)])
    assert wakes.shape == (300, 50)
    for env in range(50):
        gaps = set(np.diff(np.flatnonzero(wakes[:, env])).tolist())
        assert gaps <= set(ROS_LINK_PERIODS) and len(gaps) > 1, gaps
    assert 0.4 < wakes.mean() < 0.6  # one wake-up every 2 steps on average
    again = UnsyncedLink(50, seed=7)
    np.testing.assert_array_equal(np.array([again.tick() for _ in range(300)]), wakes)
    with pytest.raises(InvalidArgumentError, match="at least one step"):
        UnsyncedLink(3, seed=0, periods=(0, 1))


def test_study_replays_from_its_seed() -> None:
    first = run_study(readings=20, thresholds=(1.6,), speeds=(), envs=8, seed=3)
    second = run_study(readings=20, thresholds=(1.6,), speeds=(), envs=8, seed=3)
    assert first.by_threshold == second.by_threshold


def test_random_starts_avoid_codes_and_walls() -> None:
    world = mazesim.load_world("seed-maze")
    worlds = random_start_worlds(world, 40, seed=1)
    starts = {w.start[:2] for w in worlds}
    assert len(starts) > 5
    codes = {cp["center"] for cp in world.checkpoints()}
    assert not starts & codes
    for start_world in worlds:
        sim = mazesim.Simulator(start_world, robot="seed", seed=0)
        # The clearance is reported up to 3 cm: no wall is near a cell's centre.
        assert sim.wall_clearance >= 0.0299
        assert start_world.checkpoints() == world.checkpoints()


def test_study_rejects_bad_arguments() -> None:
    with pytest.raises(UnknownNameError, match="alg7, robust"):
        run_study(readings=5, decoders=("alg8",))
    with pytest.raises(InvalidArgumentError, match="wheel speed"):
        run_study(readings=5, thresholds=(), speeds=(7.0,))
    with pytest.raises(UnknownNameError, match="lockstep, ros"):
        run_study(readings=5, link="udp")
    with pytest.raises(InvalidArgumentError, match="no barcode checkpoints"):
        run_study(mazesim.load_world("arena"), readings=5, thresholds=(1.4,), speeds=())


# --- the command line ---------------------------------------------------------------------


def test_cli_json_and_files(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "study"
    code = main(
        [
            "barcode-study",
            "--readings",
            "30",
            "--thresholds",
            "1.2,2.0",
            "--speeds",
            "6.28",
            "--envs",
            "16",
            "--seed",
            "4",
            "--out",
            str(out),
            "--json",
        ]
    )
    captured = capsys.readouterr()
    assert code == 0, captured.err
    document = json.loads(captured.out)
    assert [(r["decoder"], r["threshold_v"]) for r in document["by_threshold"]] == [
        ("alg7", 1.2),
        ("robust", 1.2),
        ("alg7", 2.0),
        ("robust", 2.0),
    ]
    assert [(r["decoder"], r["speed"]) for r in document["by_speed"]] == [
        ("alg7", 6.28),
        ("robust", 6.28),
    ]
    for row in document["by_threshold"] + document["by_speed"]:
        assert set(row) >= {"decoder", "right", "wrong", "missed"}
        assert all(0.0 <= row[key] <= 1.0 for key in ("right", "wrong", "missed"))
    assert sorted(p.name for p in out.iterdir()) == [
        "by_speed.csv",
        "by_speed.png",
        "by_threshold.csv",
        "by_threshold.png",
    ]
    assert (out / "by_threshold.png").read_bytes().startswith(PNG_MAGIC)
    table = (out / "by_threshold.csv").read_text().splitlines()
    assert table[0].startswith("decoder,threshold_v,speed,readings,right,wrong,missed")
    assert len(table) == 5 and table[1].startswith("alg7,1.2,3.14,30,")
    assert captured.err == ""  # no progress bar off a terminal


def test_cli_table(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    args = ["barcode-study", "--readings", "10", "--thresholds", "1.4", "--speeds", "3.14"]
    code = main([*args, "--decoders", "robust", "--envs", "8", "--out", str(tmp_path)])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    assert "by obstacle threshold" in captured.out and "by wheel speed" in captured.out
    assert "robust" in captured.out and "alg7" not in captured.out.split("wrote")[0]


@pytest.mark.parametrize(
    ("option", "value", "message"),
    [
        ("--speeds", "3,9", "speeds in (0, 6.28]"),
        ("--thresholds", "1.2,x", "comma-separated volts"),
        ("--decoders", "alg7,fast", "decoders among alg7, robust"),
        ("--readings", "0", "at least 1"),
        ("--link", "udp", "invalid choice: 'udp'"),
    ],
)
def test_cli_rejects_bad_options(
    option: str, value: str, message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["barcode-study", option, value]) == 2
    assert message in capsys.readouterr().err


def test_cli_help_in_a_subprocess(tmp_path: Path) -> None:
    result = subprocess.run(
        [sys.executable, "-m", "mazesim", "barcode-study", "--help"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    assert result.returncode == 0
    options = ("--readings", "--thresholds", "--speeds", "--decoders", "--link", "--out", "--json")
    for option in options:
        assert option in result.stdout
    assert (
        "barcode-study"
        in subprocess.run(
            [sys.executable, "-m", "mazesim", "--help"],
            cwd=tmp_path,
            capture_output=True,
            text=True,
            timeout=300,
            check=False,
        ).stdout
    )


def test_cli_unknown_world(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["barcode-study", "--world", "no-such-maze", "--out", str(tmp_path)]) == 2
    assert "no built-in world" in capsys.readouterr().err
