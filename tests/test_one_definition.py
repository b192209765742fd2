"""Settings with one definition: the step limit is typed once, every other default refers to it."""

from __future__ import annotations

import argparse
import ast
import dataclasses
from pathlib import Path

import mazesim
from mazesim.benchmark import BenchSettings
from mazesim.cli import bench
from mazesim.episodes import MAX_STEPS

ROOT = Path(mazesim.__file__).parent
#: Names under which a default step limit is given.
STEP_LIMIT_NAMES = {"max_steps", "episode_steps", "higher_max_steps"}
#: Files with a step limit of their own, not the navigator's: the one definition of theirs.
OWN_LIMITS = {
    Path("benchmark/steady.py"): "BenchSettings.episode_steps, the bench's reset length",
}


def literal_step_limits(path: Path, root: Path = ROOT) -> list[str]:
    """Where a file types a step limit as a number: a parameter's, a field's or a key's default."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    found = []

    def check(name: str, value: ast.expr | None, line: int) -> None:
        if name in STEP_LIMIT_NAMES and isinstance(value, ast.Constant):
            if isinstance(value.value, int) and not isinstance(value.value, bool):
                found.append(f"{path.relative_to(root)}:{line} {name} = {value.value}")

    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            args = node.args
            positional = [*args.posonlyargs, *args.args]
            pairs = list(zip(positional[len(positional) - len(args.defaults) :], args.defaults))
            pairs += [(a, d) for a, d in zip(args.kwonlyargs, args.kw_defaults) if d is not None]
            for arg, default in pairs:
                check(arg.arg, default, default.lineno)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            check(node.target.id, node.value, node.lineno)
        elif isinstance(node, ast.Dict):
            for key, value in zip(node.keys, node.values):
                if isinstance(key, ast.Constant) and isinstance(key.value, str):
                    check(key.value, value, value.lineno)
        elif isinstance(node, ast.Call):
            for keyword in node.keywords:
                if keyword.arg == "default" and node.args:
                    first = node.args[0]
                    if isinstance(first, ast.Constant) and isinstance(first.value, str):
                        check(first.value.lstrip("-").replace("-", "_"), keyword.value, node.lineno)
    return found


def test_the_step_limit_is_typed_only_in_episodes() -> None:
    typed = [
        place
        for path in sorted(ROOT.rglob("*.py"))
        if path.relative_to(ROOT) not in OWN_LIMITS
        for place in literal_step_limits(path)
    ]
    assert not typed, "step limits typed again instead of read from episodes.MAX_STEPS:\n" + (
        "\n".join(typed)
    )


def test_the_step_limit_is_defined_once() -> None:
    tree = ast.parse((ROOT / "episodes.py").read_text(encoding="utf-8"))
    definitions = [
        node
        for node in tree.body
        if isinstance(node, ast.Assign)
        and any(isinstance(t, ast.Name) and t.id == "MAX_STEPS" for t in node.targets)
    ]
    assert len(definitions) == 1
    assert isinstance(definitions[0].value, ast.Constant)
    assert definitions[0].value.value == MAX_STEPS


def test_the_reader_finds_a_typed_limit(tmp_path: Path) -> None:
    sample = tmp_path / "sample.py"
    sample.write_text(
        "from dataclasses import dataclass\n"
        "def run(world, *, max_steps=4000): ...\n"
        "@dataclass\nclass Cells:\n    max_steps: int = 2000\n"
        "DEFAULTS = {'episode_steps': 300}\n"
        "def parser(p):\n    p.add_argument('--max-steps', type=int, default=10)\n"
        "def fine(*, max_steps=MAX_STEPS): ...\n"
    )
    found = literal_step_limits(sample, tmp_path)
    assert [place.split(" ", 1)[1] for place in found] == [
        "max_steps = 4000",
        "max_steps = 2000",
        "episode_steps = 300",
        "max_steps = 10",
    ]


def test_the_bench_command_reads_its_defaults_from_bench_settings() -> None:
    parser = argparse.ArgumentParser()
    bench.register(parser.add_subparsers())
    args = parser.parse_args(["bench"])
    settings = BenchSettings()
    renamed = {"warmup_steps": "warmup"}
    for field in dataclasses.fields(BenchSettings):
        if field.name == "envs":
            continue
        value = getattr(args, renamed.get(field.name, field.name))
        expected = getattr(settings, field.name)
        assert value == ([expected] if field.name == "steps_per_call" else expected), field.name


def test_the_bench_options_are_written_once_in_bench_settings() -> None:
    parser = argparse.ArgumentParser()
    bench.register(parser.add_subparsers())
    (command,) = (
        action.choices["bench"]
        for action in parser._actions
        if isinstance(action, argparse._SubParsersAction)
    )
    helps = {action.dest: action.help or "" for action in command._actions}
    documented = [f for f in dataclasses.fields(BenchSettings) if "help" in f.metadata]
    assert len(documented) >= 6
    for field in documented:
        assert helps[field.name].startswith(field.metadata["help"]), field.name
