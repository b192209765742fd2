"""The transfer study: deterministic under its seed, each cell independent of its batch mates, and
its JSON fits the documented schema."""

from __future__ import annotations

import copy
import json
from typing import Any

import pytest

from mazesim import load_world
from mazesim.errors import InvalidArgumentError, PolicyFormatError, UnknownNameError
from mazesim.learn.tables import TrainedPolicy, load_policy
from mazesim.transfer import (
    StudyOptions,
    StudyResult,
    check_study_json,
    parse_axes,
    run_study,
    study_size,
)
from mazesim.transfer.axes import Setting

#: A small study: two axes that need no change of the robot, few episodes, short episodes.
SMALL = StudyOptions(axes=parse_axes("latency,link"), episodes=3, max_steps=700, events="truth")


@pytest.fixture(scope="module")
def policy() -> TrainedPolicy:
    return load_policy(None)


def _study(policy: TrainedPolicy, options: StudyOptions = SMALL) -> StudyResult:
    return run_study(policy, load_world(policy.world_name), options)


@pytest.fixture(scope="module")
def small(policy: TrainedPolicy) -> StudyResult:
    return _study(policy)


def test_the_study_is_deterministic_under_its_seed(
    policy: TrainedPolicy, small: StudyResult
) -> None:
    again = _study(policy, StudyOptions(**{**SMALL.__dict__, "threads": 1}))
    assert json.dumps(again.as_json()) == json.dumps(small.as_json())
    other = _study(policy, StudyOptions(**{**SMALL.__dict__, "seed": 1}))
    assert json.dumps(other.as_json()) != json.dumps(small.as_json())


def test_the_grid_has_the_baseline_each_level_and_each_pair(small: StudyResult) -> None:
    assert small.baseline.setting == Setting()
    assert [cell.setting.label() for cell in small.single] == [
        "latency 1 steps",
        "latency 2 steps",
        "latency 3 steps",
        "link ros",
    ]
    assert len(small.pairs) == 1
    (pair,) = small.pairs
    assert pair.setting.axes == ("latency", "link")
    assert pair.setting.get("latency") == small.harshest["latency"]
    worst = min(
        (c for c in small.single if c.setting.axes == ("latency",)),
        key=lambda c: c.measure.success_rate,
    )
    assert small.harshest["latency"] == worst.setting.get("latency")
    assert all(cell.measure.episodes == SMALL.episodes for cell in [small.baseline, *small.pairs])
    assert study_size(SMALL) == (6, 18)


def test_a_cell_measures_the_same_whatever_shares_its_batch(
    policy: TrainedPolicy, small: StudyResult
) -> None:
    alone = _study(
        policy, StudyOptions(**{**SMALL.__dict__, "axes": parse_axes("latency"), "pairs": False})
    )
    assert alone.baseline.measure == small.baseline.measure
    assert [c.measure for c in alone.single] == [c.measure for c in small.single[:3]]


def test_the_baseline_of_the_shipped_navigator_arrives(small: StudyResult) -> None:
    measure = small.baseline.measure
    assert measure.success_rate == 1.0
    assert measure.mean_path_ratio is not None and 1.0 < measure.mean_path_ratio < 2.0
    assert measure.mean_steps is not None and measure.mean_steps < SMALL.max_steps


def test_three_steps_of_latency_cost_the_shipped_navigator(policy: TrainedPolicy) -> None:
    options = StudyOptions(
        axes=parse_axes("latency"), episodes=12, max_steps=1200, events="truth", pairs=False
    )
    result = _study(policy, options)
    late = result.single[-1]
    assert late.setting.get("latency") == 3.0
    assert late.measure.success_rate < result.baseline.measure.success_rate
    # Acting on stale readings also costs time: every episode's steps, arrived or not.
    assert late.measure.mean_steps_all > result.baseline.measure.mean_steps_all


def test_the_json_fits_the_schema(small: StudyResult) -> None:
    document = json.loads(json.dumps(small.as_json()))
    check_study_json(document)
    assert document["format"] == "mazesim-transfer-study"
    assert [axis["name"] for axis in document["axes"]] == ["latency", "link"]


def _broken(document: dict[str, Any], change: str) -> dict[str, Any]:
    broken = copy.deepcopy(document)
    if change == "share":
        broken["single"][0]["success_rate"] = 1.5
    elif change == "missing":
        del broken["baseline"]["contacts_per_episode"]
    elif change == "axis":
        broken["single"][0]["setting"] = {"warp_drive": 1.0}
    elif change == "extra":
        broken["seconds"] = 12.0
    elif change == "null":
        broken["baseline"]["success_rate"] = None
    return broken


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ("share", r"single\[0\].success_rate: expected a finite number in \[0, 1\], found"),
        ("missing", "expected a field baseline.contacts_per_episode"),
        ("axis", r"single\[0\].setting: expected only the fields"),
        ("extra", r"the document: expected only the fields .*found also \['seconds'\]"),
        ("null", "baseline.success_rate: expected a finite number"),
    ],
)
def test_a_document_off_the_schema_is_refused_naming_the_field(
    small: StudyResult, change: str, message: str
) -> None:
    with pytest.raises(InvalidArgumentError, match=message):
        check_study_json(_broken(small.as_json(), change))


def test_bad_options_are_refused(policy: TrainedPolicy) -> None:
    with pytest.raises(InvalidArgumentError, match="StudyOptions.episodes to be a whole number"):
        StudyOptions(axes=parse_axes("latency"), episodes=0)
    with pytest.raises(InvalidArgumentError, match="at least one axis"):
        _study(policy, StudyOptions(axes=()))
    with pytest.raises(UnknownNameError, match="expected events to be one of truth, robust"):
        StudyOptions(axes=parse_axes("latency"), events="psychic")
    with pytest.raises(PolicyFormatError, match="learned world 'seed-maze'"):
        run_study(policy, load_world("arena"), SMALL)
    flat = TrainedPolicy("flat", policy.world_name, policy.world_sha256, policy.checkpoint_ids)
    with pytest.raises(
        InvalidArgumentError, match="expected a hierarchical navigator, found a flat"
    ):
        _study(flat)


def test_the_harshest_level_is_the_least_successful_then_the_later_on_a_tie() -> None:
    from mazesim.learn.summary import Summary
    from mazesim.transfer.result import Cell
    from mazesim.transfer.study import _harshness

    def cell(level: float, success: float, contacts: float = 0.0) -> Cell:
        measure = Summary(10, success, contacts, 600.0, 1.2, 1.0, "robust")
        return Cell(Setting.of({"noise_scale": level}), measure)

    def harshest(cells: list[Cell]) -> object:
        return min(enumerate(cells), key=lambda item: _harshness(*item))[1].setting.get(
            "noise_scale"
        )

    assert harshest([cell(0.5, 1.0), cell(2.0, 0.9), cell(4.0, 1.0)]) == 2.0
    assert harshest([cell(0.5, 1.0), cell(2.0, 1.0), cell(4.0, 1.0)]) == 4.0
    assert harshest([cell(0.5, 1.0, 0.3), cell(2.0, 1.0), cell(4.0, 1.0)]) == 0.5
