"""No function of the core or the binding takes more than eight parameters (``self`` counted, as
clippy's ``too_many_arguments`` counts): a function that needs more takes a settings struct. The
limit holds for what Python sees too: every function and method of the binding's stub
(``python/mazesim/_core.pyi``, which stubtest keeps equal to the compiled signatures) counts its
parameters the same way, ``self``, ``cls``, ``*args`` and ``**kwargs`` included.

The sources are read with a small scanner of Rust's tokens (comments, strings, raw strings,
character literals and lifetimes skipped), so that a signature split over lines, with generics,
closures' types or attributes among its parameters, counts right. ``clippy.toml`` sets the same
limit for ``cargo clippy``, and no source may switch the lint off.
"""

from __future__ import annotations

import ast
import functools
import re
from dataclasses import dataclass
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
#: The crates whose functions are counted.
SOURCES = (REPO / "crates" / "mazesim-core" / "src", REPO / "crates" / "mazesim-py" / "src")
#: The stub of the binding: the signatures Python sees.
STUB = REPO / "python" / "mazesim" / "_core.pyi"
#: Most parameters a function may take.
LIMIT = 8


@dataclass(frozen=True)
class Signature:
    """One ``fn`` of a source: where it is, its name and how many parameters it takes."""

    path: Path
    line: int
    name: str
    parameters: int

    def __str__(self) -> str:
        return f"{self.path.relative_to(REPO)}:{self.line}: fn {self.name} ({self.parameters})"


#: The start of a comment, string or character literal (a lifetime or label is none).
SKIPPED = re.compile(
    r"""(?P<line>//[^\n]*)
    |(?P<block>/\*)
    |(?P<raw>(?<![\w])b?r(?P<hashes>\#*)")
    |(?P<string>b?"(?:\\.|[^"\\])*")
    |(?P<char>b?'(?:\\(?:u\{[0-9a-fA-F]+\}|x[0-9a-fA-F]{2}|.)|[^\\'\n])')""",
    re.S | re.X,
)


@functools.cache
def code_of(text: str) -> str:
    """``text`` with its comments, strings and character literals blanked out (each character
    but newlines replaced by a space, so that offsets and line numbers stay), lifetimes kept."""
    out = []
    position = 0
    while match := SKIPPED.search(text, position):
        start, end = match.start(), match.end()
        if match.group("block"):
            depth = 1
            while depth and end < len(text):
                if text.startswith("/*", end):
                    depth, end = depth + 1, end + 2
                elif text.startswith("*/", end):
                    depth, end = depth - 1, end + 2
                else:
                    end += 1
        elif match.group("raw"):
            closing = '"' + match.group("hashes")
            found = text.find(closing, end)
            end = len(text) if found < 0 else found + len(closing)
        out.append(text[position:start])
        out.append(re.sub(r"[^\n]", " ", text[start:end]))
        position = end
    out.append(text[position:])
    return "".join(out)


#: A function's name after ``fn`` (not a function pointer type such as ``fn(u32) -> u32``).
FN = re.compile(r"\bfn\s+([A-Za-z_][A-Za-z0-9_]*)\s*")
OPENING = {"(": ")", "[": "]", "{": "}", "<": ">"}


def closing_of(code: str, start: int, opening: str) -> int:
    """The index of the bracket that closes the one at ``start``; ``->`` is no closing angle
    bracket."""
    closing = OPENING[opening]
    depth, k = 0, start
    while k < len(code):
        c = code[k]
        if c == opening:
            depth += 1
        elif c == closing and not (c == ">" and code[k - 1] == "-"):
            depth -= 1
            if depth == 0:
                return k
        k += 1
    raise ValueError(f"unbalanced {opening!r} at offset {start}")


def parameter_count(parameters: str) -> int:
    """How many parameters the text between a signature's parentheses holds: its top-level
    commas (a trailing one aside), generics, tuples, closures' types and attributes ignored."""
    depth = 0
    items, current = [], []
    k = 0
    while k < len(parameters):
        c = parameters[k]
        if c == "-" and parameters.startswith("->", k):
            current.append("->")
            k += 2
            continue
        if c in "([{<":
            depth += 1
        elif c in ")]}>":
            depth -= 1
        if c == "," and depth == 0:
            items.append("".join(current))
            current = []
        else:
            current.append(c)
        k += 1
    items.append("".join(current))
    # An attribute alone (`#[pyo3(from_py_with = ...)] x: T` keeps its own item) is no parameter.
    return sum(1 for item in items if re.sub(r"#\s*\[.*?\]", "", item, flags=re.S).strip())


def signatures(path: Path) -> list[Signature]:
    """Every named ``fn`` of the Rust source ``path`` with its parameter count."""
    text = path.read_text()
    code = code_of(text)
    found = []
    for match in FN.finditer(code):
        k = match.end()
        if k < len(code) and code[k] == "<":
            k = closing_of(code, k, "<") + 1
            while k < len(code) and code[k].isspace():
                k += 1
        if k >= len(code) or code[k] != "(":
            continue
        end = closing_of(code, k, "(")
        line = code.count("\n", 0, match.start()) + 1
        count = parameter_count(code[k + 1 : end])
        found.append(Signature(path, line, match.group(1), count))
    return found


def rust_sources() -> list[Path]:
    """Every ``.rs`` file of the counted crates."""
    return sorted(p for root in SOURCES for p in root.rglob("*.rs"))


def test_no_function_takes_more_than_eight_parameters() -> None:
    wide = [s for p in rust_sources() for s in signatures(p) if s.parameters > LIMIT]
    assert not wide, f"functions of more than {LIMIT} parameters:\n" + "\n".join(map(str, wide))


def stub_signatures(text: str) -> list[tuple[str, int, int]]:
    """(qualified name, line, parameter count) of every function and method of the stub text
    ``text``: positional-only, positional, keyword-only, ``*args`` and ``**kwargs`` each count."""
    found = []

    def visit(body: list[ast.stmt], owner: str) -> None:
        for node in body:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                a = node.args
                count = len(a.posonlyargs) + len(a.args) + len(a.kwonlyargs)
                count += (a.vararg is not None) + (a.kwarg is not None)
                found.append((owner + node.name, node.lineno, count))
            elif isinstance(node, ast.ClassDef):
                visit(node.body, f"{owner}{node.name}.")

    visit(ast.parse(text).body, "")
    return found


def test_no_function_python_sees_takes_more_than_eight_parameters() -> None:
    wide = [
        f"{STUB.relative_to(REPO)}:{line}: def {name} ({count})"
        for name, line, count in stub_signatures(STUB.read_text())
        if count > LIMIT
    ]
    assert not wide, f"functions of more than {LIMIT} parameters:\n" + "\n".join(wide)


def test_the_stub_scanner_counts_every_kind_of_parameter() -> None:
    text = (
        "def f(a, /, b, *args, c, **kwargs) -> None: ...\n"
        "class C:\n"
        "    def __new__(cls, x: int = 0) -> C: ...\n"
        "    @property\n"
        "    def p(self) -> int: ...\n"
    )
    assert stub_signatures(text) == [("f", 1, 5), ("C.__new__", 3, 2), ("C.p", 5, 1)]
    names = {name for name, _, _ in stub_signatures(STUB.read_text())}
    assert {"generate_maze", "train_lower_round", "RobotProfile.perturbed"} <= names
    assert {"BatchSimulator.run", "MazeLayout.__new__", "LowerRoundSettings.__new__"} <= names


def test_the_lint_stays_on() -> None:
    allowed = [
        f"{p.relative_to(REPO)}:{code_of(p.read_text()).count(chr(10), 0, m.start()) + 1}"
        for p in rust_sources()
        for m in re.finditer(r"too_many_arguments", code_of(p.read_text()))
    ]
    assert not allowed, "clippy::too_many_arguments switched off at " + ", ".join(allowed)
    threshold = re.search(
        r"^too-many-arguments-threshold\s*=\s*(\d+)", (REPO / "clippy.toml").read_text(), re.M
    )
    assert threshold is not None and int(threshold.group(1)) == LIMIT


@pytest.mark.parametrize(
    ("source", "expected"),
    [
        ("fn f() {}", 0),
        ("pub fn f(&self) {}", 1),
        ("fn f<'a, T: Into<u8>>(a: &'a T, b: Vec<(u8, u8)>,) -> u8 { 0 }", 2),
        (
            "fn f(x: impl Fn(u8, u8) -> u8, y: [u8; 2], z: Option<Box<dyn Fn(u8) -> (u8, u8)>>) {}",
            3,
        ),
        ("fn f(\n    // a, b, c\n    a: &str, /* d, e */ b: char,\n) {}", 2),
        ('fn f(a: u8) { let s = "fn g(a, b, c, d)"; let c = \',\'; let r = r#"("#; }', 1),
        ("fn f(#[pyo3(from_py_with = g)] a: u8, mut b: u8, (c, d): (u8, u8)) {}", 3),
        ("type T = fn(u8, u8, u8) -> u8; fn f(a: T) {}", 1),
        ("fn f<F>(a: F) where F: Fn(u8, u8) {}", 1),
    ],
)
def test_the_scanner_counts_parameters(tmp_path: Path, source: str, expected: int) -> None:
    path = tmp_path / "lib.rs"
    path.write_text(source)
    assert [s.parameters for s in signatures(path)][-1] == expected


def test_the_scanner_sees_every_function() -> None:
    # A count of the core's and the binding's functions that a broken scanner would miss.
    found = [s for p in rust_sources() for s in signatures(p)]
    names = {s.name for s in found}
    assert {"run", "step_task", "run_steps_of", "decide", "new"} <= names
    assert len(found) > 500
