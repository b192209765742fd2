"""Mutated Webots worlds run whole: each of ``MAZESIM_WORLD_RUNS`` cases (6 by default, more in
``make fuzz``) takes a world of the test corpus, changes a few of its bytes or numbers (a number
becomes 0, 1e308, -1, inf, nan...), and runs a controller that enables and reads every device
of the robot (``tests/data/controllers/device_probe.py``) for a few steps with
``mazesim webots run``. The run ends as a run or as one of mazesim's errors, said in one line;
no device call of the controller raises (Webots' device calls print their errors and return).
The import's own fuzz (test_wbt_import.py) stops at the import; these cases go on to the run,
where a saved wheel position of 1e308 once stopped the first step with OverflowError.
"""

from __future__ import annotations

import os
import random
import re
from pathlib import Path

import pytest

from mazesim_process import mazesim_command

WORLDS = sorted((Path(__file__).parents[1] / "data" / "webots-worlds").glob("*.wbt"))
PROBE = Path(__file__).parents[1] / "data" / "controllers" / "device_probe.py"
CASES = int(os.environ.get("MAZESIM_WORLD_RUNS", "6"))
SEED = int(os.environ.get("MAZESIM_WORLD_RUNS_SEED", "20261204"))
NUMBER = re.compile(rb"(?<![\w.])-?\d+(?:\.\d+)?(?:[eE]-?\d+)?")
EXTREMES = (b"0", b"-0", b"1e308", b"-1e308", b"1e-320", b"-1", b"100000", b"inf", b"nan", b"-5")
SNIPPETS = (b"}", b"{", b"]", b"[", b'"', b"\n", b"NULL ", b"1e999 ", b"-", b"\xff", b"E-puck { ")


def mutated(data: bytes, rng: random.Random) -> bytes:
    """``data`` with one to four changes: a number made extreme (most often), a byte flipped,
    a snippet inserted, a few bytes deleted."""
    out = bytearray(data)
    for _ in range(rng.randint(1, 4)):
        kind = rng.choice(("number", "number", "number", "flip", "snippet", "delete"))
        at = rng.randrange(len(out))
        if kind == "number":
            numbers = list(NUMBER.finditer(bytes(out)))
            found = rng.choice(numbers)
            out[found.start() : found.end()] = rng.choice(EXTREMES)
        elif kind == "flip":
            out[at] ^= rng.randint(1, 255)
        elif kind == "snippet":
            out[at:at] = rng.choice(SNIPPETS)
        else:
            del out[at : at + rng.randint(1, 30)]
    return bytes(out)


@pytest.mark.parametrize("case", range(CASES))
def test_a_mutated_world_runs_or_is_refused_in_one_line(case: int, tmp_path: Path) -> None:
    rng = random.Random(SEED * 1000 + case)
    source = rng.choice(WORLDS)
    world = tmp_path / source.name
    world.write_bytes(mutated(source.read_bytes(), rng))
    run = mazesim_command(
        "webots", "run", str(PROBE), "--world", str(world), "--seconds", "0.3",
        "--no-progress", "--out", str(tmp_path / "out"), cwd=tmp_path, timeout=120,
    )  # fmt: skip
    kept = f"case {case} (seed {SEED}) from {source.name}: rerun with MAZESIM_WORLD_RUNS_SEED"
    assert "Traceback" not in run.stderr, kept + "\n" + run.stderr[-3000:]
    assert "internal error" not in run.stderr, kept + "\n" + run.stderr[-3000:]
    if run.returncode == 0:
        assert "PROBE-DONE" in run.stdout, kept + "\n" + run.stdout[-2000:]
        raised = [line for line in run.stdout.splitlines() if line.startswith("PROBE-RAISED")]
        assert raised == [], kept
    else:
        assert run.returncode == 2, kept + "\n" + run.stderr[-3000:]
        assert run.stderr.splitlines()[-1].startswith("mazesim: error: "), kept
