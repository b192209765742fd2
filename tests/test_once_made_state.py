"""The compiled binding's once-made state is made by the import, each kind of it.

pyo3 and numpy fill some cells on first use with the GIL released; a process forked while a
thread was filling one would find it half-made and wait for ever. The binding's import fills
every kind its calls reach (``crates/mazesim-py/src/once_made.rs``, ``KINDS``): these tests grep
the binding's source for the calls of each kind, so that a call of a new kind, or a once-made
cell of the binding's own outside that module, fails here until the import makes it.
"""

from __future__ import annotations

import re
from pathlib import Path

BINDING = Path(__file__).resolve().parent.parent / "crates" / "mazesim-py" / "src"
ONCE_MADE = BINDING / "once_made.rs"

#: The calls of the binding that reach each kind of pyo3's or numpy's once-made state.
CALLS_OF_KIND = {
    "numpy arrays": r"\bPyArray\w*|numpy::",
    "buffer checks": r"\bbuffers::(?:readable|writable|copied)\b",
    "type names": r"\.(?:name|qualname|module|fully_qualified_name|mro|bases)\(\)",
    "sequences": r"\bVec<|\bPySequence\b|\bPyList\b",
    "mappings": r"\b(?:PyMapping|HashMap|BTreeMap)\b",
    "paths": r"\b(?:PathBuf|Path)\b",
    "argument notes": r"#\[(?:pyfunction|pymethods)\]",
}

#: A once-made cell written in the binding itself: it lives in once_made.rs, made by the import.
OWN_CELLS = re.compile(
    r"\bintern!|\bPyOnceLock\b|\bGILOnceCell\b|\bOnceLock\b|\bOnceCell\b|\bLazyLock\b"
    r"|\blazy_static!|\bcreate_exception!|\bimport_exception!|\bLazy<"
)

#: What of pyo3 or numpy the binding may not call at all: its once-made state has no kind here.
UNKNOWN_KINDS = re.compile(r"\b(?:PyDateTime|PyDate|PyTime|PyTzInfo|BigInt|chrono|PyDecimal)\b")


def _code(path: Path) -> str:
    """The file's text without its comments."""
    return "\n".join(line.split("//", 1)[0] for line in path.read_text().splitlines())


def _readied_kinds() -> list[str]:
    text = ONCE_MADE.read_text()
    table = text[text.index("pub const KINDS") : text.index("];", text.index("pub const KINDS"))]
    return re.findall(r'\("([^"]+)",', table)


def test_every_kind_of_once_made_state_the_binding_reaches_is_made_by_the_import() -> None:
    found: dict[str, list[str]] = {}
    for path in sorted(BINDING.glob("*.rs")):
        for kind, calls in CALLS_OF_KIND.items():
            if re.search(calls, _code(path)):
                found.setdefault(kind, []).append(path.name)
    readied = _readied_kinds()
    missing = {kind: files for kind, files in found.items() if kind not in readied}
    assert not missing, f"kinds of once-made state the import does not make: {missing}"
    assert set(readied) <= set(CALLS_OF_KIND), "a kind the source scan does not know"


def test_the_binding_has_no_once_made_cell_of_its_own_outside_the_import_s_module() -> None:
    cells = [
        f"{path.name}:{number}: {line.strip()}"
        for path in sorted(BINDING.glob("*.rs"))
        if path != ONCE_MADE
        for number, line in enumerate(_code(path).splitlines(), 1)
        if OWN_CELLS.search(line) or UNKNOWN_KINDS.search(line)
    ]
    assert not cells, cells


def test_every_class_of_the_binding_has_its_type_object_made_by_the_import() -> None:
    # A class's type object is made lazily, on first use: each is added at the import.
    classes = {
        name
        for path in BINDING.glob("*.rs")
        for name in re.findall(
            r"#\[pyclass[^\]]*\]\s*(?:#\[[^\]]*\]\s*)*pub struct (\w+)", path.read_text()
        )
    }
    added = set(re.findall(r"add_class::<\w+::(\w+)>", (BINDING / "lib.rs").read_text()))
    assert classes and classes <= added, sorted(classes - added)


def test_the_scan_finds_a_call_of_each_kind_it_knows() -> None:
    # The scan's patterns match what they are meant to: a change of the binding's style that
    # hid a kind from them would show here.
    samples = {
        "numpy arrays": "let a = numpy::PyArray1::<f32>::zeros(py, 1, false);",
        "buffer checks": "buffers::readable::<f32>(obj, name, dtype, shape)",
        "type names": "obj.get_type().qualname()",
        "sequences": "let v: Vec<i64> = obj.extract()?;",
        "mappings": "let m: HashMap<String, f64> = obj.extract()?;",
        "paths": "fn load(path: PathBuf)",
        "argument notes": "#[pyfunction]",
    }
    assert {kind for kind, line in samples.items() if re.search(CALLS_OF_KIND[kind], line)} == set(
        CALLS_OF_KIND
    )
    assert OWN_CELLS.search('let name = intern!(py, "x");')
