"""``mazesim transfer-study`` end to end: a tiny study writes its JSON and heat maps, and bad
options are clear errors."""

from __future__ import annotations

import io
import json
from argparse import Namespace
from pathlib import Path

import pytest
from PIL import Image

from mazesim.cli import COMMANDS, build_parser, main
from mazesim.cli.transfer import AXIS_NAMES, run_transfer_study
from mazesim.transfer import AXIS_NAMES as STUDY_AXES
from mazesim.transfer import check_study_json
from mazesim.transfer.odometry import ODOMETRY_SOURCES

TINY = ["--axes", "latency,link", "--episodes", "2", "--max-steps", "600", "--events", "truth"]


def _args(*argv: str) -> Namespace:
    return build_parser("transfer-study").parse_args(["transfer-study", *argv])


def test_the_parser_knows_the_studys_axes_and_odometries() -> None:
    assert AXIS_NAMES == STUDY_AXES
    assert [_args("--odometry", name).odometry for name in ODOMETRY_SOURCES] == list(
        ODOMETRY_SOURCES
    )
    assert "transfer-study" in COMMANDS


def test_a_tiny_study_writes_json_and_heat_maps(tmp_path: Path) -> None:
    out = io.StringIO()
    args = _args(*TINY, "--out", str(tmp_path / "study"), "--no-progress", "--json")
    assert run_transfer_study(args, out) == 0
    printed = json.loads(out.getvalue())
    check_study_json(printed)
    written = json.loads((tmp_path / "study" / "transfer.json").read_text())
    assert written == printed
    assert [cell["label"] for cell in printed["single"]] == [
        "latency 1 steps",
        "latency 2 steps",
        "latency 3 steps",
        "link ros",
    ]
    assert len(printed["pairs"]) == 1 and printed["episodes"] == 2
    for picture in ("transfer_single.png", "transfer_pairs.png"):
        with Image.open(tmp_path / "study" / picture) as image:
            assert image.format == "PNG" and image.width > 300 and image.height > 200


def test_the_table_names_every_cell(tmp_path: Path) -> None:
    out = io.StringIO()
    args = _args(*TINY, "--no-pairs", "--out", str(tmp_path / "study"), "--no-progress")
    assert run_transfer_study(args, out) == 0
    text = out.getvalue()
    for label in ("baseline", "latency 3 steps", "link ros"):
        assert label in text
    assert "transfer_pairs.png" not in text and "transfer_single.png" in text
    assert not (tmp_path / "study" / "transfer_pairs.png").exists()


@pytest.mark.parametrize(
    ("episodes", "words"), [("1", "1 episode a cell"), ("2", "2 episodes a cell")]
)
def test_the_header_counts_episodes_in_words(tmp_path: Path, episodes: str, words: str) -> None:
    out = io.StringIO()
    argv = ["--axes", "latency", "--episodes", episodes, "--max-steps", "50", "--no-pairs"]
    args = _args(*argv, "--out", str(tmp_path / "study"), "--no-progress")
    assert run_transfer_study(args, out) == 0
    header = out.getvalue().splitlines()[0]
    assert f": {words}, seed 0" in header
    assert header.endswith("odometry from the wheel encoders")


def test_odometry_from_the_true_pose_is_a_choice_and_recorded(tmp_path: Path) -> None:
    out = io.StringIO()
    args = _args(*TINY, "--no-pairs", "--odometry", "truth", "--json", "--out", str(tmp_path))
    assert run_transfer_study(args, out) == 0
    assert json.loads(out.getvalue())["odometry"] == "truth"
    assert _args().odometry == "encoders"


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--axes", "latency,warp"], "argument --axes: expected axes among robot, wheel_radius"),
        (["--axes", ""], "argument --axes: expected axes among"),
        (["--episodes", "0"], "argument --episodes"),
        (["--events", "psychic"], "argument --events: invalid choice"),
        (["--odometry", "gyro"], "argument --odometry: invalid choice"),
        (["--threads", "-1"], "argument --threads"),
    ],
)
def test_bad_options_are_clear_errors(
    argv: list[str], message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["transfer-study", *argv]) == 2
    assert message in capsys.readouterr().err


def test_a_missing_policy_folder_is_a_one_line_error(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    code = main(["transfer-study", "--policy", str(tmp_path / "none"), "--out", str(tmp_path)])
    assert code == 2
    err = capsys.readouterr().err
    assert err.startswith("mazesim: error:") and "none" in err and len(err.splitlines()) == 1


def test_help_gives_examples(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["transfer-study", "--help"]) == 0
    text = capsys.readouterr().out
    assert "examples:" in text and "mazesim transfer-study --axes latency,link" in text
    assert "--no-progress" in text and "--policy DIR" in text
