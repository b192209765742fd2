"""Settings dataclasses refuse a value out of a field's declared range when they are made, and the
command line's options take the same ranges from the same fields (``mazesim._settings``).

``TrainSettings(envs=-1)`` was taken and failed inside numpy ("negative dimensions"),
``maze_pool=0`` inside ``max()``; ``higher_episodes=-3`` trained and saved a navigator; a NaN
reward of the flat baseline's ``FlatConfig`` was taken.
"""

from __future__ import annotations

import math
from dataclasses import Field, fields
from typing import Any

import pytest

from mazesim._settings import MAX_COUNT, RANGE_KEYS
from mazesim.benchmark.steady import BenchSettings
from mazesim.cli import build_parser
from mazesim.errors import InvalidArgumentError, WrongTypeError
from mazesim.learn.baseline import FlatConfig
from mazesim.learn.evaluate import EvalSettings
from mazesim.learn.higher_training import HigherTraining
from mazesim.learn.lower import LowerSettings
from mazesim.learn.train import TrainSettings
from mazesim.transfer.study import StudyOptions

SETTINGS = (
    TrainSettings,
    EvalSettings,
    LowerSettings,
    HigherTraining,
    FlatConfig,
    BenchSettings,
    StudyOptions,
)


def _ranged() -> list[tuple[type, Field[Any]]]:
    return [
        (kind, each)
        for kind in SETTINGS
        for each in fields(kind)
        if any(key in each.metadata for key in RANGE_KEYS)
    ]


def _outside(each: Field[Any]) -> list[Any]:
    meta, whole = each.metadata, type(each.default) is int
    step = 1 if whole else 1e-9
    values: list[Any] = []
    if "least" in meta:
        values.append(meta["least"] - step)
    if "most" in meta:
        values.append(meta["most"] + step)
    if "above" in meta:
        values.append(meta["above"])
    if not whole:
        values += [math.nan, math.inf]
    return values


def _inside(each: Field[Any]) -> list[Any]:
    meta = each.metadata
    values = [meta[key] for key in ("least", "most") if key in meta]
    if "above" in meta:
        values.append(meta["above"] + 1e-9)
    return values


def test_the_settings_of_training_and_evaluation_declare_their_ranges() -> None:
    named = {f"{kind.__name__}.{each.name}" for kind, each in _ranged()}
    for name in (
        "TrainSettings.envs",
        "TrainSettings.maze_pool",
        "TrainSettings.higher_episodes",
        "TrainSettings.checkpoint_seconds",
        "EvalSettings.mazes",
        "LowerSettings.gamma",
        "HigherTraining.max_steps",
        "FlatConfig.goal_reward",
        "BenchSettings.warmup_steps",
        "StudyOptions.episodes",
    ):
        assert name in named


@pytest.mark.parametrize(
    ("kind", "each"), _ranged(), ids=[f"{k.__name__}.{f.name}" for k, f in _ranged()]
)
def test_a_value_out_of_its_fields_range_is_refused_by_name(kind: type, each: Field[Any]) -> None:
    # (A seed past 64 bits is refused by the argument check of every public call, in its words.)
    for value in _outside(each):
        with pytest.raises(
            InvalidArgumentError, match=rf"{kind.__name__}\.(__init__: )?{each.name} "
        ):
            kind(**{each.name: value})
    for value in _inside(each):
        assert getattr(kind(**{each.name: value}), each.name) == value


def test_a_count_of_another_kind_is_a_type_error() -> None:
    with pytest.raises(WrongTypeError, match="num_envs"):
        LowerSettings(num_envs=2.0)  # type: ignore[arg-type]
    with pytest.raises(WrongTypeError, match="greedy_share"):
        HigherTraining(greedy_share="0.3")  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("command", "option", "refused", "taken"),
    [
        ("train", "--envs", "0", 1),
        ("train", "--envs", str(MAX_COUNT + 1), MAX_COUNT),
        ("train", "--steps", "2000000M", 500_000),
        ("eval", "--mazes", "10001", 10_000),
        ("eval", "--episodes", "0", 1),
        ("eval", "--max-steps", "0", 1),
        ("bench", "--blocks", "0", 1),
        ("bench", "--threads", "-1", 0),
    ],
)
def test_an_option_takes_its_fields_range(
    command: str, option: str, refused: str, taken: int, capsys: pytest.CaptureFixture[str]
) -> None:
    parser = build_parser()
    with pytest.raises(SystemExit):
        parser.parse_args([command, option, refused])
    assert f"argument {option}: expected a whole number" in capsys.readouterr().err
    args = parser.parse_args([command, option, str(taken)])
    assert getattr(args, option[2:].replace("-", "_")) == taken
