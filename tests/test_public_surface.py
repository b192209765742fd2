"""Every public entry point of mazesim, fed hostile values: huge lengths, nesting, non-finite and
extreme numbers, wrong types, special files. None may abort the process, hang past its bound
(Ctrl-C stops long work), or raise outside ``mazesim.MazesimError`` (gymnasium's own protocol
errors aside). The entry points come from the registry (``surface/registry.py``), which walks the
package and the command line, so a new one is covered without a new test.

``make test`` runs one hypothesis-drawn call per entry point of ``mazesim._core``, the ``mazesim``
namespace and the command line; ``make fuzz`` (``MAZESIM_SURFACE=all``, ``MAZESIM_SURFACE_CALLS``)
runs more calls over every module of the package; ``MAZESIM_SURFACE=mazesim.webots`` over the
modules whose names start so.
"""

from __future__ import annotations

import os
import random
from pathlib import Path
from typing import Any

from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

import mazesim
from mazesim._checks import is_public_module
from surface.registry import (
    INSTANCES,
    MUST_REFUSE,
    SKIPPED_MODULES,
    EntryPoint,
    can_make,
    cli_entry_points,
    instance_recipe,
    needs_instance,
    python_entry_points,
    refusals_of,
)
from surface.values import ABSURD, ARGUMENT_WORDS, BUILDERS, VALID
from surface.walk import walk

#: Calls per entry point, and which part of the surface (``core``: the compiled core, the
#: ``mazesim`` namespace and the command line; ``all``: every module too).
CALLS = int(os.environ.get("MAZESIM_SURFACE_CALLS", "1"))
PART = os.environ.get("MAZESIM_SURFACE", "core")
#: The seed of the calls' values (``MAZESIM_SURFACE_SEED``; else hypothesis draws it, the same
#: every run).
SEED = os.environ.get("MAZESIM_SURFACE_SEED", "")


def _makeable(owner: str) -> bool:
    import tempfile

    if owner not in _MADE:
        with tempfile.TemporaryDirectory() as tmp:
            _MADE[owner] = can_make(owner, mazesim.World.builtin("seed-maze"), Path(tmp))
    return _MADE[owner]


_MADE: dict[str, bool] = {}


def _in_part(entry: EntryPoint) -> bool:
    if PART not in ("all", "core"):  # a module's own, by its name (MAZESIM_SURFACE=mazesim.webots)
        if not entry.path.split(":")[0].startswith(PART):
            return False
    elif PART != "all" and not entry.path.startswith(("cli:", "mazesim._core:")):
        if entry.path.split(":")[0] not in ("mazesim", "mazesim.errors"):
            return False
    owner = needs_instance(entry)
    # test_every_method_has_a_way_to_make_its_instance says which cannot be made
    return owner is None or _makeable(owner)


def entry_points() -> list[EntryPoint]:
    return python_entry_points() + cli_entry_points()


def python_call(entry: EntryPoint, rng: random.Random) -> dict[str, Any]:
    """One call: every required parameter and one other (if any) given a hostile value."""
    keys = sorted(BUILDERS)
    optional = [p for p in entry.parameters if p not in entry.required]
    chosen = [*entry.required, *([rng.choice(optional)] if optional else [])]
    owner = needs_instance(entry)
    return {
        "path": entry.path,
        "instance": instance_recipe(owner) if owner else None,
        "positional": list(entry.positional),
        "args": {p: rng.choice(keys) for p in chosen},
    }


#: Name of a keyword no entry point takes.
UNKNOWN_KEYWORD = "not_a_parameter"


def arity_calls(entry: EntryPoint, rng: random.Random) -> list[dict[str, Any]]:
    """Calls with the wrong number of arguments: a required one left out, one positional value
    more than the entry point takes, a keyword it does not know (each where it applies). They
    must be refused with a ``MazesimError`` (``InvalidArgumentError``) like any other bad
    argument, for a compiled entry point as for one written in Python."""
    keys = sorted(BUILDERS)
    owner = needs_instance(entry)
    base = {
        "path": entry.path,
        "instance": instance_recipe(owner) if owner else None,
        "positional": list(entry.positional),
        "arity": True,
    }
    given = {p: rng.choice(keys) for p in entry.required}
    calls = []
    if entry.required:
        missing = entry.required[rng.randrange(len(entry.required))]
        calls.append({**base, "args": {p: k for p, k in given.items() if p != missing}})
    if not entry.any_positional:
        every = {p: rng.choice(keys) for p in entry.ordered}
        calls.append(
            {**base, "positional": list(entry.ordered), "args": every, "more": [rng.choice(keys)]}
        )
    if not entry.any_keyword:
        calls.append({**base, "args": {**given, UNKNOWN_KEYWORD: rng.choice(keys)}})
    return calls


def cli_call(entry: EntryPoint, rng: random.Random) -> dict[str, Any]:
    """One command line: its words, its positionals and one option given hostile words."""
    words = ["=" + k for k in sorted(ARGUMENT_WORDS)]
    positionals = [rng.choice(words) for _ in entry.required]
    extra: list[str] = []
    if entry.options:
        option, takes_value = rng.choice(entry.options)
        extra = [option, *([rng.choice(words)] if takes_value else [])]
    return {"path": entry.path, "argv": [*entry.path[len("cli:") :].split(), *positionals, *extra]}


def refusal_calls(entry: EntryPoint) -> list[dict[str, Any]]:
    """The calls of the absurd values ``entry`` must refuse (``registry.MUST_REFUSE`` and
    ``registry.MUST_REFUSE_BY_PARAMETER``): one per value, the other parameters given their
    declared valid values."""
    owner = needs_instance(entry)
    calls = []
    for declared in refusals_of(entry):
        for name, keys in declared.absurd.items():
            for key in keys:
                calls.append(
                    {
                        "path": entry.path,
                        "instance": instance_recipe(owner) if owner else None,
                        "positional": list(entry.positional),
                        "args": {**declared.valid, name: key},
                        "must_refuse": True,
                        "must_list_names": key == "unknown_name",
                    }
                )
    return calls


#: Most characters a call may print, and most its error's message may hold, whatever it was
#: given: a value is quoted shortened to about 200 characters (``mazesim.errors._shortened``:
#: ``_shown`` for a repr, every word of a message past 200 characters), never whole, so a text
#: of a million characters makes a message of a line or two, not a flood (nor the 4,000
#: characters every message is cut to at the last).
MOST_PRINTED = 20_000
MOST_MESSAGE = 1_500


def long_text_calls(entry: EntryPoint) -> list[dict[str, Any]]:
    """One call with every required parameter given a long text (``long_str``): what it prints
    and the message it may raise must stay short (:data:`MOST_PRINTED`, :data:`MOST_MESSAGE`)."""
    if not entry.required or entry.path.startswith("cli:"):
        return []
    owner = needs_instance(entry)
    return [
        {
            "path": entry.path,
            "instance": instance_recipe(owner) if owner else None,
            "positional": list(entry.positional),
            "args": dict.fromkeys(entry.required, "long_str"),
        }
    ]


def failures_of(plans: list[dict[str, Any]], results: list[dict[str, Any]]) -> list[str]:
    """The calls that failed: those that escaped; those of a wrong number of arguments that ran;
    those of a value the entry point must refuse that it accepted (a call that returned, or a
    command that ended with exit 0); those that printed or raised a message longer than
    :data:`MOST_PRINTED` or :data:`MOST_MESSAGE` characters."""
    failures = []
    for plan, result in zip(plans, results):  # noqa: B905 - one result per plan
        ran = result["how"] == "ended" and result["what"] in ("returned", "exit 0")
        printed, message = result.get("printed", 0), result.get("message", 0)
        if result["how"] == "escaped":
            failures.append(f"{plan}: {result['what']}")
        elif printed > MOST_PRINTED or message > MOST_MESSAGE:
            failures.append(f"{plan}: printed {printed} characters, a message of {message}")
        elif plan.get("arity") and ran:
            failures.append(f"{plan}: {result['what']}")
        elif plan.get("must_refuse") and ran:
            failures.append(f"{plan}: accepted a value it must refuse")
        elif plan.get("must_list_names") and not _lists_names(result["what"]):
            failures.append(f"{plan}: refused an unknown name without the known ones")
    return failures


def _lists_names(what: str) -> bool:
    """Whether a refusal of an unknown name says which names are known."""
    return "UnknownNameError" in what or "one of" in what


def plans_of(entries: list[EntryPoint], seed: int, calls: int) -> list[dict[str, Any]]:
    """``calls`` hostile calls of each entry point. Each call's values come from its own stream,
    named by the seed, the entry point and the call's number: a call is the same whatever else is
    in the walk, and adding an entry point changes no other's calls."""
    plans = []
    for entry in entries:
        for number in range(calls):
            rng = random.Random(f"{seed}:{entry.path}:{number}")
            is_cli = entry.path.startswith("cli:")
            plans.append(cli_call(entry, rng) if is_cli else python_call(entry, rng))
        if not entry.path.startswith("cli:"):
            plans.extend(arity_calls(entry, random.Random(f"{seed}:{entry.path}:arity")))
        plans.extend(refusal_calls(entry))
        plans.extend(long_text_calls(entry))
    return plans


def _makeable_entry(entry: EntryPoint) -> bool:
    owner = needs_instance(entry)
    return owner is None or _makeable(owner)


def test_every_method_has_a_way_to_make_its_instance() -> None:
    """Every public class whose methods are entry points, in every module (whatever part of the
    surface the walk calls), has an instance recipe: its own in INSTANCES or the generic one."""
    missing = sorted(
        {
            owner
            for e in python_entry_points()
            if (owner := needs_instance(e)) and not _makeable(owner)
        }
    )
    assert not missing, f"add a way to make an instance of each to INSTANCES: {missing}"
    assert INSTANCES, "the compiled core's classes have their recipes"


def _modules_on_disk() -> list[str]:
    """Every public module of the package, found from its files (not through the registry)."""

    root = Path(mazesim.__file__).resolve().parent
    names = []
    for file in sorted(root.rglob("*.py")):
        parts = ("mazesim", *file.relative_to(root).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        name = ".".join(parts)
        if is_public_module(name) and not name.startswith(SKIPPED_MODULES):
            names.append(name)
    return names


def test_every_checked_function_is_in_the_registry() -> None:
    """Every function and method the import hook checks, in every public module found on disk,
    is an entry point of the registry (an inherited method counts in the class it is defined
    in, whose instance comes from one of its implementations)."""
    import importlib
    import inspect

    from mazesim.errors import MissingDependencyError

    paths = {e.path for e in python_entry_points()}
    missing = []
    for name in _modules_on_disk():
        try:
            module = importlib.import_module(name)
        except MissingDependencyError:
            continue  # an optional extra that is not installed
        for member, obj in vars(module).items():
            if getattr(obj, "__module__", None) != name or member.startswith("_"):
                continue
            if getattr(obj, "__mazesim_checked__", False) and f"{name}:{member}" not in paths:
                missing.append(f"{name}:{member}")
            if inspect.isclass(obj) and any(
                getattr(raw, "__mazesim_checked__", False) for raw in vars(obj).values()
            ):
                for method, raw in vars(obj).items():
                    target = getattr(raw, "__func__", raw)
                    checked = getattr(target, "__mazesim_checked__", False)
                    path = f"{name}:{member}.{method}"
                    if checked and not method.startswith("_") and path not in paths:
                        missing.append(path)
    assert not missing, f"checked but never walked: {missing}"


def test_only_the_one_marker_marks_a_function_as_checked() -> None:
    """A hot path leaves the surface's check through ``_hot_paths.checks_own_arguments``, whose
    thin wrapper still turns a call of the wrong arity into a MazesimError: a module's own marker
    (setting the attribute by hand, as the camera's pixel accessors once did) let Python's bare
    TypeError through. The marker's name is written in ``_hot_paths.py`` alone."""
    package = Path(mazesim.__file__).parent
    marker = "_".join(("", "", "mazesim", "checked", "", ""))
    marking = [
        str(path.relative_to(package))
        for path in package.rglob("*.py")
        if path.name != "_hot_paths.py" and marker in path.read_text("utf-8")
    ]
    assert not marking, f"mark hot paths with mazesim._hot_paths.checks_own_arguments: {marking}"


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
@given(st.integers(0, 2**32 - 1))
def test_hostile_values_end_in_a_result_or_a_mazesim_error(drawn_seed: int) -> None:
    seed = int(SEED) if SEED else drawn_seed
    plans = plans_of([e for e in entry_points() if _in_part(e)], seed, CALLS)
    results = walk(plans)
    failures = failures_of(plans, results)
    assert not failures, f"seed {seed}: {len(failures)} of {len(plans)} calls:\n" + "\n".join(
        failures
    )


def test_every_declared_refusal_names_an_entry_point_and_its_values() -> None:
    """Each entry of ``MUST_REFUSE`` is an entry point of the registry, its parameters are the
    entry point's, and its values are known keys: a declaration cannot go stale unnoticed."""
    entries = {e.path: e for e in entry_points()}
    for path, declared in MUST_REFUSE.items():
        assert path in entries, path
        for refusal in declared:
            names = {*refusal.valid, *refusal.absurd}
            assert names <= set(entries[path].parameters), (path, names)
            assert set(entries[path].required) <= names, (path, entries[path].required)
            assert set(refusal.valid.values()) <= set(VALID), path
            for keys in refusal.absurd.values():
                assert set(keys) <= set(ABSURD) | set(BUILDERS), path


def test_an_absurd_value_accepted_in_silence_is_a_failure() -> None:
    """The walk counts a must-refuse call that returned (or a command that ended with exit 0) as
    a failure, and its refusal as none; other calls that return are results."""
    refused = {"how": "refused", "what": "mazesim.errors.InvalidArgumentError: expected ..."}
    returned = {"how": "ended", "what": "returned"}
    must = {"path": "p", "args": {}, "must_refuse": True}
    assert failures_of([must], [returned]) == [f"{must}: accepted a value it must refuse"]
    assert failures_of([must], [refused]) == []
    assert failures_of([{"path": "p", "args": {}}], [returned]) == []
    # An unknown name is refused naming the known ones.
    named = {**must, "must_list_names": True}
    bare = {"how": "refused", "what": "mazesim.errors.InvalidArgumentError: unknown task"}
    listed = {"how": "refused", "what": "mazesim.errors.UnknownNameError: no task 'x'; ..."}
    assert failures_of([named], [bare]) == [
        f"{named}: refused an unknown name without the known ones"
    ]
    assert failures_of([named], [listed]) == []


def test_a_flood_of_output_or_a_message_quoting_a_value_whole_is_a_failure() -> None:
    """The walk counts a call that printed more than MOST_PRINTED characters, or raised a
    message longer than MOST_MESSAGE, as a failure, however it ended."""
    plan = {"path": "p", "args": {"name": "long_str"}}
    flood = {"how": "ended", "what": "returned", "printed": 10**6}
    quoted = {"how": "refused", "what": "mazesim.errors.UnknownNameError: ...", "message": 10**5}
    assert len(failures_of([plan, plan], [flood, quoted])) == 2
    assert failures_of([plan], [{**flood, "printed": 100}]) == []


def test_every_text_parameter_quotes_a_long_text_shortened() -> None:
    """Every entry point of a walk is given a text of 100,000 characters for its required
    parameters (long_text_calls): Webots' getDevice, whose "not found" line quoted it whole,
    and the compiled core's lookups by name among them."""
    wanted = ("mazesim.webots.robot:Robot.getDevice", "mazesim._core:World.builtin")
    entries = [e for e in entry_points() if e.path in wanted]
    plans = [plan for entry in entries for plan in long_text_calls(entry)]
    assert len(plans) == len(wanted)
    failures = failures_of(plans, walk(plans))
    assert not failures, "\n".join(failures)


def test_the_declared_refusals_are_refused() -> None:
    """Every value of ``MUST_REFUSE`` is refused by its entry point (whatever part of the
    surface the walk calls)."""
    entries = [e for e in entry_points() if refusals_of(e) and _makeable_entry(e)]
    plans = [plan for entry in entries for plan in refusal_calls(entry)]
    assert len(plans) >= len(MUST_REFUSE)
    by_parameter = [e.path for e in entries if e.path not in MUST_REFUSE]
    assert "mazesim.webots.camera:Camera.enable" in by_parameter, by_parameter
    failures = failures_of(plans, walk(plans))
    assert not failures, "\n".join(failures)


def _name_checks() -> list[tuple[str, str, str]]:
    """Each parameter of a function of the package that the function checks as a registered
    name (its value passed to ``mazesim.errors._known_name``): (file, parameter, annotation)."""
    import ast

    root = Path(mazesim.__file__).parent
    found = []
    for path in sorted(root.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for function in ast.walk(tree):
            if not isinstance(function, (ast.FunctionDef, ast.AsyncFunctionDef)):
                continue
            arguments = function.args
            every = [*arguments.posonlyargs, *arguments.args, *arguments.kwonlyargs]
            annotated = {a.arg: ast.unparse(a.annotation) if a.annotation else "" for a in every}
            for call in ast.walk(function):
                if (
                    isinstance(call, ast.Call)
                    and getattr(call.func, "id", None) == "_known_name"
                    and call.args
                    and isinstance(call.args[0], ast.Name)
                    and call.args[0].id in annotated
                ):
                    name = call.args[0].id
                    found.append((str(path.relative_to(root)), name, annotated[name]))
    return found


def test_every_parameter_checked_as_a_registered_name_is_annotated_as_one() -> None:
    """A parameter whose value a function checks as a registered name is annotated
    ``RegisteredName``, so that the walk gives it a name no registry holds (by its annotation,
    whatever it is called): a new function's name parameter is fuzzed by construction."""
    checks = _name_checks()
    assert len(checks) >= 8, checks
    unannotated = [c for c in checks if "RegisteredName" not in c[2]]
    assert not unannotated, unannotated


def test_the_walk_finds_name_parameters_by_their_annotation() -> None:
    """The registry reads the annotation: parameters of any name (``reward_type``, ``events``,
    ``name``) are walked as names, and one of a name it once listed but of another type (an
    array of ``events``) is not."""
    named = {e.path: set(e.named) for e in python_entry_points() if e.named}
    assert named.get("mazesim.envs.goal:MazeGoalEnv") == {"reward_type", "render_mode"}, named
    assert named.get("mazesim.transfer.axes:axis_named") == {"name"}, named
    assert named.get("mazesim.episodes:EpisodeBatch") == {"events"}, sorted(named)
    assert not any(
        path.startswith("mazesim.replay.navigator:") and "events" in names
        for path, names in named.items()
    )
    entries = {e.path: e for e in python_entry_points()}
    refused = refusals_of(entries["mazesim.transfer.axes:axis_named"])
    assert [r.absurd for r in refused] == [{"name": ("unknown_name",)}]
