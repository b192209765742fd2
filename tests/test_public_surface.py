"""Every public entry point of mazesim, fed hostile values: huge lengths, nesting, non-finite and
extreme numbers, wrong types, special files. None may abort the process, hang past its bound
(Ctrl-C stops long work), or raise outside ``mazesim.MazesimError`` (gymnasium's own protocol
errors aside). The entry points come from the registry (``surface/registry.py``), which walks the
package and the command line, so a new one is covered without a new test.

``make test`` runs one hypothesis-drawn call per entry point of ``mazesim._core``, the ``mazesim``
namespace and the command line; ``make fuzz`` (``MAZESIM_SURFACE=all``, ``MAZESIM_SURFACE_CALLS``)
runs more calls over every module of the package.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from surface.registry import (
    INSTANCES,
    EntryPoint,
    can_make,
    cli_entry_points,
    instance_recipe,
    needs_instance,
    python_entry_points,
)
from surface.values import ARGUMENT_WORDS, BUILDERS

HERE = Path(__file__).resolve().parent
#: Calls per entry point, and which part of the surface (``core``: the compiled core, the
#: ``mazesim`` namespace and the command line; ``all``: every module too).
CALLS = int(os.environ.get("MAZESIM_SURFACE_CALLS", "1"))
PART = os.environ.get("MAZESIM_SURFACE", "core")
#: Seconds the runner may take for all its calls (each has a 2 s Ctrl-C watchdog).
TIME_LIMIT = 600.0


def _makeable(owner: str) -> bool:
    import tempfile

    import mazesim

    if owner not in _MADE:
        with tempfile.TemporaryDirectory() as tmp:
            _MADE[owner] = can_make(owner, mazesim.World.builtin("seed-maze"), Path(tmp))
    return _MADE[owner]


_MADE: dict[str, bool] = {}


def _in_part(entry: EntryPoint) -> bool:
    if PART != "all" and not entry.path.startswith(("cli:", "mazesim._core:")):
        if entry.path.split(":")[0] not in ("mazesim", "mazesim.errors"):
            return False
    owner = needs_instance(entry)
    # test_every_method_has_a_way_to_make_its_instance says which cannot be made
    return owner is None or _makeable(owner)


def entry_points() -> list[EntryPoint]:
    return python_entry_points() + cli_entry_points()


def python_call(entry: EntryPoint) -> st.SearchStrategy[dict[str, Any]]:
    """One call: every required parameter and one other (if any) given a hostile value."""
    keys = st.sampled_from(sorted(BUILDERS))
    optional = [p for p in entry.parameters if p not in entry.required]
    chosen = st.sampled_from(optional).map(lambda p: [p]) if optional else st.just([])
    return st.tuples(
        st.fixed_dictionaries({p: keys for p in entry.required}),
        chosen,
        keys,
    ).map(
        lambda t: {
            "path": entry.path,
            "instance": instance_recipe(owner) if (owner := needs_instance(entry)) else None,
            "positional": list(entry.positional),
            "args": {**t[0], **{p: t[2] for p in t[1]}},
        }
    )


def cli_call(entry: EntryPoint) -> st.SearchStrategy[dict[str, Any]]:
    """One command line: its words, its positionals and one option given hostile words."""
    words = st.sampled_from(sorted(ARGUMENT_WORDS)).map(lambda k: "=" + k)
    command = entry.path[len("cli:") :].split()
    options = st.sampled_from(entry.options) if entry.options else st.none()

    def argv(positionals: list[str], option: Any, value: str) -> dict[str, Any]:
        extra = [] if option is None else [option[0], *([value] if option[1] else [])]
        return {"path": entry.path, "argv": [*command, *positionals, *extra]}

    return st.builds(
        argv,
        st.lists(words, min_size=len(entry.required), max_size=len(entry.required)),
        options,
        words,
    )


def call(entry: EntryPoint) -> st.SearchStrategy[dict[str, Any]]:
    return cli_call(entry) if entry.path.startswith("cli:") else python_call(entry)


def _in_part_of_its_class(entry: EntryPoint) -> bool:
    return PART == "all" or _in_part(EntryPoint(entry.path, ()))


def test_every_method_has_a_way_to_make_its_instance() -> None:
    missing = sorted(
        {
            owner
            for e in python_entry_points()
            if (owner := needs_instance(e)) and _in_part_of_its_class(e) and not _makeable(owner)
        }
    )
    assert not missing, f"add a way to make an instance of each to INSTANCES: {missing}"
    assert INSTANCES, "the compiled core's classes have their recipes"


def test_the_registry_finds_the_whole_surface() -> None:
    paths = {e.path for e in entry_points()}
    for expected in (
        "mazesim._core:Simulator.step",
        "mazesim._core:validate_codes",
        "mazesim:load_world",
        "cli:show",
        "cli:import-wbt",
    ):
        assert expected in paths
    assert len(paths) > 100


@settings(
    max_examples=1,
    derandomize=True,
    deadline=None,
    suppress_health_check=list(HealthCheck),
    database=None,
    phases=[Phase.explicit, Phase.generate],
)
@given(st.data())
def test_hostile_values_end_in_a_result_or_a_mazesim_error(
    tmp_path_factory: pytest.TempPathFactory, data: st.DataObject
) -> None:
    entries = [e for e in entry_points() if _in_part(e)]
    plans = [data.draw(call(e)) for e in entries for _ in range(CALLS)]
    plan_file = tmp_path_factory.mktemp("surface") / "plans.json"
    plan_file.write_text(json.dumps(plans), encoding="utf-8")
    try:
        done = subprocess.run(
            [sys.executable, "-m", "surface.runner", str(plan_file)],
            cwd=HERE,
            capture_output=True,
            text=True,
            timeout=TIME_LIMIT,
        )
        stdout, code = done.stdout, done.returncode
    except subprocess.TimeoutExpired as e:
        stdout = e.stdout.decode() if isinstance(e.stdout, bytes) else (e.stdout or "")
        code = None
    results = [
        json.loads(line[len("RESULT ") :])
        for line in stdout.splitlines()
        if line.startswith("RESULT ")
    ]
    failures = [f"{plans[r['index']]}: {r['what']}" for r in results if r["how"] == "escaped"]
    if "ALL DONE" not in stdout:
        last = len(results)
        how = "hung" if code is None else f"ended with exit {code}"
        failures.append(f"{plans[last] if last < len(plans) else '?'}: the process {how}")
    assert not failures, f"{len(failures)} of {len(plans)} calls:\n" + "\n".join(failures)
