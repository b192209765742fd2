"""``mazesim bench`` runs the canonical workload and reports in the documented layout."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np

from mazesim.bench import braitenberg, braitenberg_one, measure


def test_bench_json_layout() -> None:
    done = subprocess.run(
        [sys.executable, "-m", "mazesim", "bench", "--envs", "1,8", "--steps", "20", "--json"],
        capture_output=True,
        text=True,
        check=True,
    )
    report = json.loads(done.stdout)
    assert set(report) >= {"workload", "results"}
    assert [r["envs"] for r in report["results"]] == [1, 8]
    for r in report["results"]:
        assert set(r) == {"envs", "env_steps_per_s", "bytes_per_env"}
        assert r["env_steps_per_s"] > 0
        assert r["bytes_per_env"] > 0


def test_bench_rejects_bad_env_lists() -> None:
    done = subprocess.run(
        [sys.executable, "-m", "mazesim", "bench", "--envs", "0,x"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode == 2
    assert "env counts" in done.stderr


def test_vector_and_scalar_braitenberg_agree() -> None:
    rng = np.random.default_rng(0)
    ps = rng.uniform(60, 1500, size=(50, 8)).astype(np.float32)
    out = braitenberg(ps, np.zeros((50, 2), np.float32))
    for row, (left, right) in zip(ps, out):
        expected = np.clip(braitenberg_one(row.tolist()), -6.28, 6.28)
        assert np.allclose([left, right], expected, atol=1e-4)


def test_measure_steps_every_env() -> None:
    result = measure(envs=4, steps=10, threads=1)
    assert result["envs"] == 4 and result["steps"] == 10
    assert result["env_steps_per_s"] > 0
