"""Docs name things that exist.

- Each ``:mod:`` reference of a docstring to mazesim is a file of the tree.
- Each Sphinx role of a docstring (``:func:``, ``:class:``, ``:data:``, ``:meth:``, ``:attr:``,
  ``:exc:``, ``:mod:``) names something its module, one of its classes or, for a package, one of
  its modules defines, or, written out from ``mazesim.``, something that module defines.
- Each backticked ``mazesim.x.y`` of the core's and the binding's doc comments, of the pages
  (``README.md``, ``docs/*.md``) and of the tests' helpers (``tests/*.py``) is such a thing, and
  each backticked path of the repository (``tests/...py``, ``docs/...md``, ``crates/...rs``,
  ``python/...``, ``examples/...``) a file or folder of it (the package's docstrings too); a
  path with a placeholder in capitals (``docs/NAME.md``) names a pattern, which must match one.
- Each backticked path of the core (``navigator::door``, ``mazesim_core::limits::MAX_ROBOTS``)
  in those, in the package's docstrings and in the tests is a module of the core and names it
  defines or re-exports.

The names a module defines are read from its source (no import): its top-level definitions,
assignments and imports, the members of its classes and what a method assigns to ``self``.
"""

from __future__ import annotations

import ast
import functools
import importlib.util
import re
from pathlib import Path

import mazesim

ROOT = Path(mazesim.__file__).parent
REPOSITORY = ROOT.parents[1]
MODULE_REFERENCE = re.compile(r":mod:`~?(mazesim(?:\.\w+)*)`")
#: A Sphinx role naming a Python object, with its target (a leading ``~`` or ``.`` dropped).
ROLE = re.compile(r":(?:mod|func|class|data|meth|attr|exc|obj):`[~.]?([A-Za-z_][\w.]*)`")
#: A dotted name of the package written in backticks (one or two), calls' ``()`` allowed.
DOTTED = re.compile(r"`+(mazesim(?:\.[A-Za-z_]\w*)+)(?:\(\))?`+")
#: A path of the core written in backticks: ``navigator::door``, ``mazesim_core::limits::X``.
CORE_PATH = re.compile(r"`+((?:mazesim_core|crate|[a-z_]+)(?:::[A-Za-z_]\w*)+)`+")
#: Paths of other projects' trees that the package's docstrings cite (Webots' documentation).
ELSEWHERE = {"docs/reference/javascript-procedural-proto.md"}
CORE = REPOSITORY / "crates" / "mazesim-core" / "src"
#: A path of the repository written in backticks.
REPOSITORY_PATH = re.compile(
    r"`+((?:tests|docs|crates|python|examples|benches|worlds|robots)/[\w./-]*\w)`+"
)
#: A placeholder of a path: a name in capitals (``WORLD``, ``NAME``) standing for any name.
PLACEHOLDER = re.compile(r"(?<![\w-])[A-Z][A-Z_]+(?![\w-])")
#: Built-in names roles may name.
OUTSIDE = {"DeprecationWarning"}


def module_exists(name: str, root: Path = ROOT) -> bool:
    """Whether the dotted ``name`` (``mazesim.x.y``) is a module or package under ``root``."""
    return module_file(name, root) is not None or name == "mazesim"


def module_file(name: str, root: Path = ROOT) -> Path | None:
    """The file of the dotted module ``name`` under ``root`` (a package's ``__init__.py``, the
    compiled core's stub), or None."""
    parts = name.split(".")[1:]
    base = root.joinpath(*parts)
    for candidate in (
        base.with_suffix(".py"),
        base.with_suffix(".pyi"),
        base / "__init__.py",
    ):
        if parts and candidate.is_file():
            return candidate
    return root / "__init__.py" if not parts and (root / "__init__.py").is_file() else None


@functools.cache
def defined_names(path: Path, root: Path = ROOT) -> frozenset[str]:
    """The names ``path`` defines: its top-level definitions, assignments and imports, the
    members of its classes (methods, class attributes, dataclass fields, enum members) and what
    its functions assign to ``self``."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    names: set[str] = set(imported_names(path, root))
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            names.add(node.id)
        elif isinstance(node, ast.Attribute) and isinstance(node.ctx, ast.Store):
            names.add(node.attr)
    return frozenset(names)


@functools.cache
def imported_names(path: Path, root: Path = ROOT) -> dict[str, str]:
    """The names ``path`` imports, each with the dotted module it comes from (``mazesim.x`` for
    the package's own, relative imports resolved; the module itself for ``import x``)."""
    package = ".".join(("mazesim", *path.relative_to(root).parent.parts))
    found: dict[str, str] = {}
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            base = package.split(".")
            if node.level:
                base = base[: len(base) - node.level + 1]
                source = ".".join([*base, node.module] if node.module else base)
            else:
                source = node.module or ""
            for alias in node.names:
                found[alias.asname or alias.name] = source
        elif isinstance(node, ast.Import):
            for alias in node.names:
                found[(alias.asname or alias.name).split(".")[0]] = alias.name
    return found


def resolves(name: str, root: Path = ROOT) -> bool:
    """Whether the dotted ``name`` (``mazesim.x.y.z``) is a module under ``root`` or a name the
    longest module it starts with defines (every part after the module, loosely: each a name the
    module defines, or the module it imports the first from defines)."""
    parts = name.split(".")
    for end in range(len(parts), 0, -1):
        path = module_file(".".join(parts[:end]), root)
        if path is not None:
            return names_in(path, parts[end:], root)
    return False


def names_in(path: Path, parts: list[str], root: Path = ROOT) -> bool:
    """Whether ``parts`` (a name and its attributes) name something in the module at ``path``."""
    if not parts:
        return True
    source = imported_names(path, root).get(parts[0])
    if source is not None:
        if not source.startswith("mazesim"):
            return True  # the standard library's, numpy's, ...: not checked here
        if resolves(f"{source}.{'.'.join(parts)}", root):
            return True
    sibling = module_file(f"{module_name(path, root).rsplit('.', 1)[0]}.{parts[0]}", root)
    if sibling is not None and sibling != path:
        return names_in(sibling, parts[1:], root)
    return all(part in defined_names(path, root) for part in parts)


def module_name(path: Path, root: Path = ROOT) -> str:
    """The dotted name of the module at ``path`` (a package's: the package's, as ``x.__init``'s
    siblings are its modules)."""
    return ".".join(("mazesim", *path.relative_to(root).with_suffix("").parts))


def resolves_in(path: Path, target: str, root: Path = ROOT) -> bool:
    """Whether a role's ``target`` written in the module at ``path`` names something: written out
    from ``mazesim.``, or a name of the module (a package's: also of its modules)."""
    if target.startswith("mazesim.") or target == "mazesim":
        return resolves(target, root)
    parts = target.split(".")
    if parts[0] in OUTSIDE or names_in(path, parts, root) or importable_elsewhere(parts[0]):
        return True
    if path.name == "__init__.py":
        return any(names_in(module, parts, root) for module in path.parent.glob("*.py"))
    return False


def importable_elsewhere(name: str) -> bool:
    """Whether ``name`` is a module outside the package (``functools``, ``numpy``)."""
    return name != "mazesim" and importlib.util.find_spec(name) is not None


def missing_modules(root: Path = ROOT) -> list[str]:
    """The references of the tree's files to modules that do not exist, as ``file: name``."""
    return [
        f"{path.relative_to(root)}: {name}"
        for path in sorted(root.rglob("*.py"))
        for name in MODULE_REFERENCE.findall(path.read_text(encoding="utf-8"))
        if not module_exists(name, root)
    ]


def unresolved_roles(root: Path = ROOT) -> list[str]:
    """The roles of the tree's docstrings whose targets name nothing, as ``file: target``."""
    return [
        f"{path.relative_to(root)}: {target}"
        for path in sorted(root.rglob("*.py"))
        for target in sorted(set(ROLE.findall(path.read_text(encoding="utf-8"))))
        if not resolves_in(path, target, root)
    ]


ITEM = re.compile(
    r"\b(?:fn|struct|enum|const|static|type|trait|mod)\s+([A-Za-z_]\w*)|^\s+([A-Z]\w*)[,({]",
    re.M,
)
#: A ``pub use`` of the core, whose names it re-exports.
REEXPORT = re.compile(r"^\s*pub use ([^;]*);", re.M)


@functools.cache
def items_of(scope: Path) -> frozenset[str]:
    """The names a module of the core (its file, or its folder) defines or re-exports: functions,
    types, constants, modules and, loosely, enum variants (identifiers that start a line)."""
    files = sorted(scope.rglob("*.rs")) if scope.is_dir() else [scope]
    texts = [path.read_text(encoding="utf-8") for path in files]
    defined = {name for text in texts for found in ITEM.findall(text) for name in found if name}
    exported = {
        name
        for text in texts
        for statement in REEXPORT.findall(text)
        for name in re.findall(r"\w+", statement.rsplit("::", 1)[-1])
    }
    return frozenset(defined | exported)


def core_path_exists(path: str) -> bool | None:
    """Whether ``path`` (``navigator::door::wrap``) is a module of the core followed by names
    that module defines; None when it does not start with a module of the core (``std::f64``,
    ``Batch::step``)."""
    parts = path.split("::")
    if parts[0] in ("mazesim_core", "crate"):
        parts = parts[1:]
    elif not ((CORE / parts[0]).is_dir() or (CORE / f"{parts[0]}.rs").is_file()):
        return None
    scope = CORE / "lib.rs"
    folder = CORE
    while parts and ((folder / parts[0]).is_dir() or (folder / f"{parts[0]}.rs").is_file()):
        folder, parts = folder / parts[0], parts[1:]
        scope = folder if folder.is_dir() else folder.with_suffix(".rs")
    return all(part in items_of(scope) for part in parts[:1]) and all(
        part in items_of(CORE) for part in parts[1:]
    )


def repository_path_exists(name: str, bases: list[Path]) -> bool:
    """Whether ``name`` (``docs/design.md``) is a file or folder under one of ``bases``; a name
    with placeholders in capitals (``docs/NAME.md``, ``worlds/WORLD.toml``) is a pattern, which
    must match one (a file whose name is in capitals, ``README.md``, is itself first)."""
    if any((base / name).exists() for base in bases):
        return True
    pattern = PLACEHOLDER.sub("*", name)
    return pattern != name and any(any(base.glob(pattern)) for base in bases)


def documents() -> list[Path]:
    """The pages, the Rust sources and the tests' helpers whose backticked names and paths are
    checked."""
    return [
        REPOSITORY / "README.md",
        *sorted((REPOSITORY / "docs").glob("*.md")),
        *sorted((REPOSITORY / "crates").rglob("*.rs")),
        ROOT / "_core.pyi",
        *python_sources(),
        *sorted(p for p in (REPOSITORY / "tests").glob("*.py") if not p.name.startswith("test_")),
    ]


def python_sources() -> list[Path]:
    """The package's modules, whose docstrings may name the core's modules too."""
    return sorted(ROOT.rglob("*.py"))


def test_docstrings_name_only_modules_that_exist() -> None:
    assert not missing_modules(), "docstrings name modules that do not exist:\n" + "\n".join(
        missing_modules()
    )


def test_the_reader_finds_a_missing_module(tmp_path: Path) -> None:
    (tmp_path / "distributed").mkdir()
    (tmp_path / "distributed" / "__init__.py").write_text(
        '"""Trainers: :mod:`mazesim.distributed.flat_q`, :mod:`mazesim.distributed`."""\n'
    )
    (tmp_path / "distributed" / "episodes.py").write_text(
        '"""See :mod:`~mazesim.distributed.episodes`."""\n'
    )
    assert missing_modules(tmp_path) == ["distributed/__init__.py: mazesim.distributed.flat_q"]


def test_docstrings_name_only_things_that_exist() -> None:
    found = unresolved_roles()
    assert not found, "docstrings name things that do not exist:\n" + "\n".join(found)


def test_the_reader_finds_a_role_that_names_nothing(tmp_path: Path) -> None:
    (tmp_path / "__init__.py").write_text("")
    (tmp_path / "learn").mkdir()
    (tmp_path / "learn" / "__init__.py").write_text(
        '"""See :func:`train` and :class:`mazesim.learn.lower.Trainer`."""\n'
    )
    (tmp_path / "learn" / "lower.py").write_text(
        '"""Uses :attr:`LowerTrainer.tables`, :meth:`LowerTrainer.run_round` and :func:`gone`."""\n'
        "class LowerTrainer:\n"
        "    def __init__(self):\n"
        "        self.tables = None\n"
        "    def run_round(self):\n"
        "        pass\n"
        "def train():\n"
        "    pass\n"
    )
    assert unresolved_roles(tmp_path) == [
        "learn/__init__.py: mazesim.learn.lower.Trainer",
        "learn/lower.py: gone",
    ]


def test_pages_and_doc_comments_name_only_things_that_exist() -> None:
    found = []
    for path in documents():
        text = path.read_text(encoding="utf-8")
        where = path.relative_to(REPOSITORY)
        names = sorted(set(DOTTED.findall(text)))
        found += [f"{where}: {name}" for name in names if not resolves(name)]
        found += [
            f"{where}: {name}"
            for name in sorted(set(CORE_PATH.findall(text)))
            if core_path_exists(name) is False
        ]
        # A crate's own tests name their data from the crate's folder.
        bases = [REPOSITORY, *[parent for parent in path.parents if parent.parent.name == "crates"]]
        found += [
            f"{where}: {name}"
            for name in sorted(set(REPOSITORY_PATH.findall(text)))
            if not any(mark in name for mark in ("*", ".."))
            and name not in ELSEWHERE
            and not repository_path_exists(name, bases)
        ]
    assert not found, "pages and doc comments name things that do not exist:\n" + "\n".join(found)


def test_a_path_with_a_placeholder_must_match_a_file(tmp_path: Path) -> None:
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "arena.toml").write_text("")
    (tmp_path / "README.md").write_text("")
    assert repository_path_exists("README.md", [tmp_path])
    assert repository_path_exists("worlds/WORLD.toml", [tmp_path])
    assert repository_path_exists("worlds/NAME", [tmp_path])
    # The repository's worlds are no .wbt files: a user project's worlds/WORLD.wbt is not here.
    assert not repository_path_exists("worlds/WORLD.wbt", [tmp_path])
    assert not repository_path_exists("docs/NAME.md", [tmp_path])
    assert not repository_path_exists("worlds/arena-2.toml", [tmp_path])
    assert not repository_path_exists("READMEE.txt", [tmp_path])


def test_the_tests_name_only_core_modules_that_exist() -> None:
    here = Path(__file__).resolve()
    found = [
        f"{path.relative_to(REPOSITORY)}: {name}"
        for path in sorted((REPOSITORY / "tests").rglob("*.py"))
        if path != here and "data" not in path.relative_to(REPOSITORY / "tests").parts
        for name in sorted(set(CORE_PATH.findall(path.read_text(encoding="utf-8"))))
        if core_path_exists(name) is False
    ]
    assert not found, "tests name core modules that do not exist:\n" + "\n".join(found)


def test_the_core_path_reader_finds_what_is_gone() -> None:
    assert core_path_exists("navigator::door::wrap")
    assert core_path_exists("mazesim_core::limits::MAX_ROBOTS")
    assert core_path_exists("crate::Batch::run_steps")
    assert core_path_exists("mazesim_core::qlearning") is False
    assert core_path_exists("control::door") is False
    assert core_path_exists("std::f64::consts") is None
