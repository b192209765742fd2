"""Evaluation results in one shape: :class:`mazesim.learn.summary.Summary` is the only class that
holds what episodes measured, and :func:`~mazesim.learn.summary.summarise` the only code that
counts arrivals and bumps of episode results into shares and means.

The evaluator, the transfer study's cells, the chunks spread over Ray, a sweep's trainers and the
training run's last-episodes share all go through it; these tests read the tree so that a second
result class or a second success-rate computation fails them.
"""

from __future__ import annotations

import ast
from pathlib import Path

import mazesim
from mazesim.episodes import EpisodeResult
from mazesim.learn.summary import summarise
from mazesim.transfer.axes import Setting
from mazesim.transfer.result import Cell

ROOT = Path(mazesim.__file__).parent
#: The one module allowed to hold and compute measures.
SUMMARY_MODULE = Path("learn/summary.py")
#: Names of measures: a class with a field of one of these names is a result type.
MEASURE_NAMES = {
    "success_rate",
    "collision_free_rate",
    "mean_collisions",
    "contacts_per_episode",
    "mean_path_ratio",
    "path_ratio",
    "mean_steps",
}
#: What an episode result is counted by.
OUTCOME_ATTRIBUTES = {"arrived", "bumps"}
#: Calls that turn a sequence into a count, sum or mean.
AGGREGATES = {"sum", "len", "mean", "average", "count_nonzero"}

Comprehension = (ast.ListComp, ast.GeneratorExp, ast.SetComp)


def _reads_outcomes(node: ast.AST) -> bool:
    return any(
        isinstance(sub, ast.Attribute) and sub.attr in OUTCOME_ATTRIBUTES for sub in ast.walk(node)
    )


def _call_name(call: ast.Call) -> str:
    function = call.func
    if isinstance(function, ast.Attribute):
        return function.attr
    return function.id if isinstance(function, ast.Name) else ""


def result_types(path: Path, root: Path = ROOT) -> list[str]:
    """Classes of a file with a field named as a measure, as ``file:line Class.field``."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    found = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.ClassDef):
            continue
        for statement in node.body:
            if (
                isinstance(statement, ast.AnnAssign)
                and isinstance(statement.target, ast.Name)
                and statement.target.id in MEASURE_NAMES
            ):
                found.append(
                    f"{path.relative_to(root)}:{statement.lineno} {node.name}.{statement.target.id}"
                )
    return found


def outcome_counts(path: Path, root: Path = ROOT) -> list[str]:
    """Where a file counts episode outcomes itself: a comprehension over ``.arrived`` or
    ``.bumps`` handed to ``sum``/``len``/``mean``..., or one that keeps only arrivals."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    found = []
    for node in ast.walk(tree):
        places: list[ast.AST] = []
        if isinstance(node, ast.Call) and _call_name(node) in AGGREGATES:
            places = [arg for arg in node.args if isinstance(arg, Comprehension)]
        elif isinstance(node, Comprehension):
            places = [node] if any(map(_reads_outcomes, node.generators[0].ifs)) else []
        found += [
            f"{path.relative_to(root)}:{place.lineno} {ast.unparse(place)}"
            for place in places
            if _reads_outcomes(place)
        ]
    return sorted(set(found))


def _tree_files() -> list[Path]:
    return [path for path in sorted(ROOT.rglob("*.py")) if path.relative_to(ROOT) != SUMMARY_MODULE]


def test_summary_is_the_only_result_type() -> None:
    found = [place for path in _tree_files() for place in result_types(path)]
    assert not found, "result types beside learn.summary.Summary:\n" + "\n".join(found)
    assert result_types(ROOT / SUMMARY_MODULE) != []


def test_only_summarise_counts_arrivals_and_bumps() -> None:
    found = [place for path in _tree_files() for place in outcome_counts(path)]
    assert not found, "measures computed beside learn.summary.summarise:\n" + "\n".join(found)
    assert outcome_counts(ROOT / SUMMARY_MODULE) != []


def test_the_readers_find_a_second_result_type_and_computation(tmp_path: Path) -> None:
    sample = tmp_path / "sample.py"
    sample.write_text(
        "from dataclasses import dataclass\n"
        "@dataclass\nclass CellMeasure:\n    episodes: int\n    success_rate: float\n"
        "def measure(results):\n"
        "    rate = sum(r.arrived for r in results) / len(results)\n"
        "    kept = [r.steps for r in results if r.arrived]\n"
        "    bumps = float(np.mean([r.bumps for r in results]))\n"
        "    fine = {r.episode: r.arrived for r in results}\n"
        "    return rate, kept, bumps, fine\n"
    )
    assert result_types(sample, tmp_path) == ["sample.py:5 CellMeasure.success_rate"]
    assert [place.split(" ", 1)[0] for place in outcome_counts(sample, tmp_path)] == [
        "sample.py:7",
        "sample.py:8",
        "sample.py:9",
    ]


def test_a_transfer_cell_is_a_summary_under_the_study_keys() -> None:
    results = [
        EpisodeResult(world=0, episode=0, arrived=True, steps=120, bumps=0, contact_steps=0),
        EpisodeResult(world=0, episode=1, arrived=False, steps=400, bumps=2, contact_steps=5),
    ]
    summary = summarise(results, [60.0], "robust")
    cell = Cell(Setting.of({"noise_scale": 2.0}), summary).as_json()
    assert isinstance(cell.pop("setting"), dict) and isinstance(cell.pop("label"), str)
    assert cell == {
        "episodes": 2,
        "success_rate": 0.5,
        "contacts_per_episode": 1.0,
        "collision_free_rate": 0.5,
        "path_ratio": 2.0,
        "mean_steps": 120.0,
    }


def test_a_summary_of_several_worlds() -> None:
    results = [
        EpisodeResult(
            world=e % 2,
            episode=e,
            arrived=e % 3 != 0,
            steps=90 + e,
            bumps=e % 2,
            contact_steps=0,
            decisions=[(1, e % 4), (-1, 0)],
        )  # fmt: skip
        for e in range(6)
    ]
    summary = summarise(results, [45.0, 50.0], "truth")
    assert summary.world_success == [2 / 3, 2 / 3]
    assert summary.env_steps == sum(90 + e for e in range(6))
    assert list(summary.decisions) == ["+1", "-1"] and summary.decisions["-1"] == {"CC": 6}
    arrived = [(91, 50.0), (92, 45.0), (94, 45.0), (95, 50.0)]
    assert summary.mean_path_ratio == sum(s / d for s, d in arrived) / 4
