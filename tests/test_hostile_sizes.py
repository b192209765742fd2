"""Sizes before allocation: a sequence, buffer or shape whose length is huge is refused with an
``InvalidArgumentError`` saying the bound and what was found, before anything is reserved. Each
entry point used to abort the process ("memory allocation of 32000000000 bytes failed"); the
cases run in a child process under a 4 GiB address-space cap (see ``hostile.py``)."""

from __future__ import annotations

import re
import subprocess
import sys
import textwrap

import pytest

from hostile import run_hostile

#: name -> (statement with `world`, `batch`, `HUGE` and `Shaped` in scope, what the message says)
CASES = {
    "batch seeds": (
        "_core.BatchSimulator(world, num_envs=2, seeds=HUGE)",
        r"seeds .*at most 2 .*1000000000 items",
    ),
    "run seeds": (
        "_core.RunSettings(seeds=HUGE)",
        r"seeds .*at most 16777216 .*1000000000 items",
    ),
    "motor gains": (
        "mazesim.DrivePerturbation(motor_gains=HUGE)",
        r"motor_gains .*at most 2 .*1000000000 items",
    ),
    "batch worlds": (
        "_core.BatchSimulator(worlds=HUGE)",
        r"worlds .*at most 16777216 .*1000000000 items",
    ),
    "batch robots": (
        "_core.BatchSimulator(world, num_envs=2, robot=HugeTuple())",
        r"robot .*at most 16777216 .*1000000000 items",
    ),
    "validate codes": (
        "mazesim.validate_codes(HUGE)",
        r"codes .*at most 4096 .*1000000000 items",
    ),
    "lower level states shape": (
        "_core.lower_level_states(Shaped())",
        r"observations of shape",
    ),
    "tabular table shape": (
        "_core.TabularSettings(Shaped())",
        r"table .*no usable shape",
    ),
    "train lower round crews": (
        "_core.train_lower_round(HUGE, ROUND, {}, 0, 0, 0, 0)",
        r"crews .*at most 16777216 .*1000000000 items",
    ),
    "lower round settings worlds": (
        "_core.LowerRoundSettings(SETTINGS, HUGE, np.zeros(2, np.int64), np.ones((4, 12), bool))",
        r"worlds .*at most 16777216 .*1000000000 items",
    ),
    "robot batch reset seeds": (
        "RobotBatch([world], [0, 0]).reset(seeds=HUGE)",
        r"seeds .*at most \d+ (values|items), found 1000000000",
    ),
    "robot batch worlds": (
        "RobotBatch(HUGE, [0, 0])",
        r"worlds .*at most 16777216 items, found 1000000000",
    ),
    "robot batch envs": (
        "RobotBatch([world], HUGE)",
        r"world_of_env .*at most \d+ (values|items), found 1000000000",
    ),
    "robot batch place": (
        "RobotBatch([world], [0, 0]).place(HUGE, HUGE, HUGE)",
        r"envs .*at most \d+ (values|items), found 1000000000",
    ),
}

BODY = """
import numpy as np
from mazesim.batch import RobotBatch
HUGE = range(10**9)
class HugeTuple(tuple):
    def __len__(self):
        return 10**9
class Shaped:
    shape = range(10**9)
    dtype = 'float32'
world = mazesim.World.builtin('seed-maze')
batch = _core.BatchSimulator(world, num_envs=2)
SETTINGS = {k: 0.5 for k in ('gamma', 'epsilon', 'rate_initial', 'rate_floor', 'rate_power',
    'progress_reward', 'collision_penalty', 'corridor_step_reward', 'door_step_reward',
    'heading_reward', 'door_success_reward', 'door_failure_reward', 'door_path_exit',
    'success_past_centre', 'success_across')}
SETTINGS.update(decision_steps=10, corridor_episode_steps=350)
ROUND = _core.LowerRoundSettings(
    SETTINGS, [world], np.zeros(2, np.int64), np.ones((4, 12), bool)
)
for name, statement in CASES.items():
    try:
        eval(statement)
        print('CASE', name, '|ACCEPTED')
    except mazesim.MazesimError as e:
        own = isinstance(e, mazesim.InvalidArgumentError)  # WrongTypeError is one
        kind = 'InvalidArgumentError' if own else type(e).__name__
        print('CASE', name, '|' + kind + ': ' + str(e).replace(chr(10), ' ')[:400])
"""


def test_huge_lengths_are_refused_before_allocation() -> None:
    statements = {name: statement for name, (statement, _) in CASES.items()}
    outcome = run_hostile(f"CASES = {statements!r}\n" + BODY)
    assert outcome.ok, outcome.describe()
    found = dict(
        line[len("CASE ") :].split(" |", 1)
        for line in outcome.stdout.splitlines()
        if line.startswith("CASE ")
    )
    assert sorted(found) == sorted(CASES), outcome.describe()
    for name, (_, says) in CASES.items():
        assert found[name].startswith("InvalidArgumentError: "), f"{name}: {found[name]}"
        assert re.search(says, found[name]), f"{name}: {found[name]}"


def test_a_robot_list_nested_deep_is_refused_without_overflowing_the_stack() -> None:
    # A list of robots is read one level deep: its items are names, paths or profiles, never
    # lists to look into (reading them as robot lists recursed until the stack overflowed).
    deep = "world = mazesim.World.builtin('seed-maze')\ndeep = []\nfor _ in range(100_000):\n"
    for call in (
        "_core.Simulator(world, robot=deep)",
        "_core.BatchSimulator(world, 1, robot=deep)",
    ):
        outcome = run_hostile(deep + "    deep = [deep]\n" + call + "\n")
        assert outcome.refused, f"{call}: {outcome.describe()}"
        assert "found a sequence" in outcome.stdout or "found a list" in outcome.stdout, (
            f"{call}: {outcome.stdout}"
        )


#: The patterns that match a quoted string in a text a user gives (a .wbt, a PROTO, a TOML
#: sweep file), by module and name.
QUOTED_PATTERNS = [
    ("mazesim.webots.proto.syntax", "_TOKEN"),
    ("mazesim.webots.proto.expander", "_COMMENT"),
    ("mazesim._toml", "_QUOTED"),
]


@pytest.mark.parametrize(("module", "name"), QUOTED_PATTERNS)
def test_a_long_quoted_string_is_matched_in_memory_of_its_own_size(module: str, name: str) -> None:
    # `"(?:[^"\\]|\\.)*"` kept about 120 bytes a character on the regex engine's stack: a .wbt of
    # one 50 MB string (within the 256 MiB a world may have) took more than 5 GB. The unrolled
    # pattern matches the same strings in constant memory: 10 MB within 400 MiB of heap.
    code = textwrap.dedent(
        f"""
        import importlib, resource
        pattern = getattr(importlib.import_module({module!r}), {name!r})
        text = '"' + "x" * 10_000_000 + '"'
        data = [int(line.split()[1]) << 10 for line in open("/proc/self/status")
                if line.startswith("VmData")][0]
        resource.setrlimit(resource.RLIMIT_DATA, (data + (400 << 20),) * 2)
        print(pattern.match(text).end())
        """
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=False
    )
    assert result.stdout.strip() == "10000002", result.stderr[-500:]
