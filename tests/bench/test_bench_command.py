"""``mazesim bench``: steady state after a warm-up, in blocks, per workload, as text or JSON."""

from __future__ import annotations

import json
import subprocess
import sys
from typing import Any

import pytest


def bench(*args: str, check: bool = True) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "mazesim", "bench", *args],
        capture_output=True,
        text=True,
        check=check,
    )


def bench_json(*args: str) -> dict[str, Any]:
    document: dict[str, Any] = json.loads(bench(*args, "--json").stdout)
    return document


def test_json_has_every_figure_and_the_settings() -> None:
    doc = bench_json("--envs", "1,8", "--blocks", "2", "--block-steps", "50", "--threads", "1")
    assert set(doc) >= {"settings", "machine", "results", "single_env_python_steps_per_s"}
    assert doc["settings"]["workload"] == "braitenberg" and doc["settings"]["mazes"] == "distinct"
    assert [r["settings"]["envs"] for r in doc["results"]] == [1, 8]
    for result in doc["results"]:
        assert result["warmup_steps_done"] == 1000
        assert [b["first_step"] for b in result["blocks"]] == [1000, 1050]
        assert result["env_steps_per_s"] > 0 and result["env_steps_per_cpu_s"] > 0
        assert 0.0 <= result["contact_share"] <= 1.0
        assert set(result["memory"]) == {"resident_bytes_per_env", "engine_bytes_per_env"}
        for block in result["blocks"]:
            assert block["env_steps"] == 50 * result["settings"]["envs"]
            assert block["wall_seconds"] > 0


def test_warm_up_and_blocks_follow_the_options() -> None:
    doc = bench_json(
        "--envs", "4", "--warmup", "1200", "--blocks", "3", "--block-steps", "40",
        "--episode-steps", "80",
    )  # fmt: skip
    (result,) = doc["results"]
    assert result["warmup_steps_done"] == 1200
    assert [b["first_step"] for b in result["blocks"]] == [1200, 1240, 1280]
    # 4 envs, 80-step episodes staggered by 20 steps: 2 resets in every 40 steps.
    assert [b["episodes_ended"] for b in result["blocks"]] == [2, 2, 2]


@pytest.mark.parametrize(
    ("workload", "low", "high"),
    [("braitenberg", 0.0, 0.1), ("contact", 0.35, 0.75), ("random", 0.0, 0.1)],
)
def test_every_workload_runs_and_reports_its_contact_share(
    workload: str, low: float, high: float
) -> None:
    doc = bench_json(
        "--envs", "32", "--workload", workload, "--blocks", "2", "--block-steps", "120"
    )  # fmt: skip
    assert doc["settings"]["workload"] == workload
    assert low <= doc["results"][0]["contact_share"] <= high


def test_shared_mazes_are_reported() -> None:
    doc = bench_json("--envs", "4", "--mazes", "shared", "--blocks", "1", "--block-steps", "20")
    assert doc["settings"]["mazes"] == "shared"
    assert doc["results"][0]["settings"]["mazes"] == "shared"


def test_one_and_many_steps_per_call_are_both_reported() -> None:
    doc = bench_json(
        "--envs", "1,8", "--steps-per-call", "1,100", "--blocks", "2", "--block-steps", "100"
    )  # fmt: skip
    assert doc["settings"]["steps_per_call"] == [1, 100]
    runs = [(r["settings"]["envs"], r["settings"]["steps_per_call"]) for r in doc["results"]]
    assert runs == [(1, 1), (1, 100), (8, 1), (8, 100)]
    for result in doc["results"]:
        assert [b["first_step"] for b in result["blocks"]] == [1000, 1100]
        assert result["env_steps_per_s"] > 0


def test_the_contact_workload_refuses_many_steps_per_call() -> None:
    done = bench("--workload", "contact", "--steps-per-call", "1,10", check=False)
    assert done.returncode == 2
    assert "contact workload runs one step per call" in done.stderr


def test_text_report_is_a_table_under_its_settings() -> None:
    out = bench("--envs", "2", "--blocks", "1", "--block-steps", "20", "--workload", "random")
    lines = out.stdout.splitlines()
    assert lines[0].startswith("workload random, distinct 5 x 5 mazes")
    assert "env-steps/s" in lines[1] and "per CPU-s" in lines[1] and "contact" in lines[1]
    assert "per call" in lines[1]
    assert lines[2].split()[:2] == ["2", "1"]
    assert "one env stepped from Python" in out.stdout


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--warmup", "999"], "at least 1000"),
        (["--workload", "push"], "invalid choice: 'push'"),
        (["--mazes", "some"], "invalid choice: 'some'"),
        (["--envs", "0,x"], "env counts"),
        (["--blocks", "0"], "at least 1"),
        (["--steps-per-call", "0"], "steps per call in [1,"),
    ],
)
def test_bad_options_exit_2_saying_what_was_expected(args: list[str], message: str) -> None:
    done = bench(*args, check=False)
    assert done.returncode == 2
    assert message in done.stderr
