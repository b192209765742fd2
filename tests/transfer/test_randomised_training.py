"""Issue 21: ``mazesim train --randomise``: each round's robots drawn from the spec's ranges,
deterministic under the seed, recorded with the navigator and checked on ``--resume``."""

from __future__ import annotations

import dataclasses
import json
import re
from pathlib import Path

import numpy as np
import pytest

from mazesim._core import RobotProfile
from mazesim.batch import RobotChoice
from mazesim.cli import main
from mazesim.errors import InvalidArgumentError, PolicyFormatError
from mazesim.learn.checkpoint import RunFolder
from mazesim.learn.tables import TrainedPolicy, load_policy
from mazesim.learn.train import train
from mazesim.transfer.randomise import parse_spec, robot_draw
from training_settings import TINY

SPEC = parse_spec("wheel_radius=0.95:1.05,ir_angle=0:15,wall_reflectance=0.2:1,slip=0:0.5")
OTHER = parse_spec("noise_scale=0.5:4,ir_offset=-10:10")


def _train(out: Path, spec: str = SPEC.text(), threads: int = 0) -> TrainedPolicy:
    settings = dataclasses.replace(TINY, randomise=spec)
    draw = robot_draw(parse_spec(spec), TINY.seed)
    policy = train(settings, RunFolder(out), threads=threads, robot=draw)
    assert policy is not None
    return policy


def _same_tables(first: TrainedPolicy, second: TrainedPolicy) -> bool:
    assert first.lower_q is not None and second.lower_q is not None
    assert first.higher_q is not None and second.higher_q is not None
    return bool(
        np.array_equal(first.lower_q, second.lower_q)
        and np.array_equal(first.higher_q, second.higher_q)
    )


def test_a_spec_reads_back_from_its_text() -> None:
    assert parse_spec(SPEC.text()) == SPEC
    assert SPEC.text().startswith("wheel_radius=0.95:1.05,ir_angle=0.0:15.0,")


def test_the_draw_perturbs_each_robot_and_each_round_but_the_first() -> None:
    draw = robot_draw(SPEC, seed=4)
    first, second = draw(0, 6), draw(1, 6)
    nominal = RobotProfile.builtin("seed")
    for profiles in (first, second):
        assert profiles[0].to_toml() == nominal.to_toml()
        radii = [p.wheel_radius for p in profiles[1:]]
        assert len(set(radii)) == len(radii)
        assert all(0.95 * nominal.wheel_radius <= r <= 1.05 * nominal.wheel_radius for r in radii)
        assert all(0.2 <= p.wall_reflectance <= 1.0 for p in profiles[1:])
    assert [p.to_toml() for p in first[1:]] != [p.to_toml() for p in second[1:]]
    # The same round gives the same robots (a resumed run draws them again).
    assert [p.to_toml() for p in draw(1, 6)] == [p.to_toml() for p in second]


def test_training_draws_every_round_and_the_higher_level_once(tmp_path: Path) -> None:
    calls: list[tuple[int, int]] = []
    draw = robot_draw(SPEC, TINY.seed)

    def recording(round_index: int, count: int) -> RobotChoice:
        calls.append((round_index, count))
        return draw(round_index, count)

    settings = dataclasses.replace(TINY, randomise=SPEC.text())
    train(settings, RunFolder(tmp_path / "run"), robot=recording)
    rounds = settings.lower().rounds
    lower_calls = [(k, settings.envs) for k in range(rounds)]
    assert calls == [*lower_calls, (rounds, settings.higher_envs)]


def test_randomised_training_is_deterministic_whatever_the_threads(tmp_path: Path) -> None:
    one = _train(tmp_path / "one", threads=1)
    two = _train(tmp_path / "two", threads=2)
    assert _same_tables(one, two)
    assert one.training["history"] == two.training["history"]
    # The robots reach the simulator: the seed robot alone learns other tables, and so do
    # other ranges.
    plain = train(TINY, RunFolder(tmp_path / "plain"))
    assert plain is not None and not _same_tables(one, plain)
    assert not _same_tables(one, _train(tmp_path / "other", spec=OTHER.text()))


def test_the_spec_is_saved_and_resume_refuses_another(tmp_path: Path) -> None:
    whole = _train(tmp_path / "whole")
    saved = json.loads((tmp_path / "whole" / "policy.json").read_text())
    assert saved["training"]["settings"]["randomise"] == SPEC.text()
    assert load_policy(tmp_path / "whole").training["settings"]["randomise"] == SPEC.text()

    parts = tmp_path / "parts"
    settings = dataclasses.replace(TINY, randomise=SPEC.text())
    draw = robot_draw(SPEC, TINY.seed)
    assert train(settings, RunFolder(parts), robot=draw, stop_after_rounds=1) is None
    other = dataclasses.replace(TINY, randomise=OTHER.text())
    with pytest.raises(PolicyFormatError, match="other settings"):
        train(other, RunFolder(parts, resume=True), robot=robot_draw(OTHER, TINY.seed))
    with pytest.raises(PolicyFormatError, match="other settings"):
        train(TINY, RunFolder(parts, resume=True))
    resumed = train(settings, RunFolder(parts, resume=True), robot=draw)
    assert resumed is not None and _same_tables(whole, resumed)


def test_ranges_and_a_draw_go_together(tmp_path: Path) -> None:
    with pytest.raises(InvalidArgumentError, match="expected a robot draw exactly with"):
        train(dataclasses.replace(TINY, randomise=SPEC.text()), RunFolder(tmp_path / "a"))
    with pytest.raises(InvalidArgumentError, match="expected a robot draw exactly with"):
        train(TINY, RunFolder(tmp_path / "b"), robot=robot_draw(SPEC, TINY.seed))
    assert not (tmp_path / "a").exists() and not (tmp_path / "b").exists()


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        (["--randomise", "wheel_radius=0.1:1"], r"axis 'wheel_radius': expected a level in \[0.5"),
        (
            ["--randomise", "latency=0:3"],
            "a property of the robot profile to be one of .*found 'latency'",
        ),
        (["--randomise", "wheel_radius"], "expected a TOML file or axis=low:high"),
        (["--randomise", "missing.toml"], "cannot read the randomisation file"),
        (["--randomise", "slip=0:0.5", "--flat"], "--randomise trains hierarchical navigators"),
    ],
)
def test_a_bad_spec_is_one_line_and_exit_2(
    arguments: list[str], message: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "run"
    code = main(["train", *arguments, "--out", str(out), "--no-progress"])
    error = capsys.readouterr().err
    assert code == 2
    assert error.startswith("mazesim: error: ") and error.count("\n") == 1, error
    assert re.search(message, error), error
    assert not out.exists()


def test_the_command_trains_with_the_spec_and_records_it(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    spec = tmp_path / "ranges.toml"
    spec.write_text("[randomise]\nslip = [0.0, 0.5]\nwall_reflectance = [0.4, 1.0]\n")
    out = tmp_path / "run"
    arguments = ["train", "--envs", "32", "--steps", "16000", "--seed", "3", "--no-progress"]
    assert main([*arguments, "--randomise", str(spec), "--out", str(out)]) == 0
    policy = load_policy(out)
    assert policy.training["settings"]["randomise"] == "wall_reflectance=0.4:1.0,slip=0.0:0.5"
    capsys.readouterr()
    assert main([*arguments, "--randomise", "slip=0:0.4", "--resume", "--out", str(out)]) == 2
    assert "the checkpoint is of a run with other settings" in capsys.readouterr().err
