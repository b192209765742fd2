"""Every corpus world's import written down, to see which rows a change of the import touches.

Usage: ``python tests/webots_corpus/import_snapshot.py take --mirrors DIR --out FILE.jsonl``
imports the world of each row of ``manifest.toml`` whose mirror DIR holds, with the mazesim
that ``import mazesim`` finds, and writes a JSON line a row: the mazesim world it became (its
TOML) and the import's warnings, or the import's error. Take one snapshot with a build from
before the change (``PYTHONPATH=OLD/python``, OLD a worktree of the commit before it with its
extension built) and one after; ``python tests/webots_corpus/import_snapshot.py compare BEFORE
AFTER`` names each row whose import changed and how (the world's tables whose counts changed,
the warnings gained and lost; paths in warnings are said from the row's folder, so two
snapshots differ only where the imports do). The 396 worlds of the corpus whose mirrors were at
hand imported in 158 s, their exports from the mirrors included (2026-12-07, 2-core machine),
where running their rows takes hours: the rows a change touched are the ones to run again
(``run_corpus.py --only``).
"""

from __future__ import annotations

import argparse
import json
import re
import shutil
import sys
import tempfile
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

if __package__ in (None, ""):  # run as a script: import the package from tests/
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from webots_corpus.manifest import Project, load_manifest
from webots_corpus.mirrors import export, find_mirror, has_commit

#: A TOML table header of a mazesim world (``[[walls]]``, ``[[paint]]``...).
_TABLE = re.compile(r"^\[\[(\w+)\]\]$", re.MULTILINE)


def import_row(project: Project, mirrors: Path, work: Path) -> dict[str, Any] | None:
    """The import of a row's world (``None`` without a mirror holding its commit)."""
    from mazesim.webots import import_wbt

    git_dir = find_mirror(mirrors, project.repo)
    if git_dir is None or not has_commit(git_dir, project.commit):
        return None
    root = work / project.name.replace("/", "+")
    folders = [project.root, *(str(Path(c).parent) for c in project.controllers)]
    folders += list(project.exports)
    try:
        export(git_dir, project.commit, ["" if f == "." else f for f in folders], root)
        controller = Path(project.controllers[0]).stem
        world, report = import_wbt(root / project.world, controller=controller)
    except Exception as error:  # noqa: BLE001 - any failure (MirrorError too) is the row's import
        message = str(error).replace(f"{root}/", "")
        return {"name": project.name, "error": f"{type(error).__name__}: {message}"}
    finally:
        shutil.rmtree(root, ignore_errors=True)  # the exported files, read once
    # Paths name the export's temporary folder, another at each snapshot: said from the row's.
    warnings = [w.replace(f"{root}/", "") for w in report["warnings"]]
    return {"name": project.name, "world": world.to_toml(), "warnings": warnings}


def take(projects: list[Project], mirrors: Path, out: Path) -> int:
    """Writes the import of every row whose mirror is at hand to ``out`` (whole or not at all:
    written beside it, then moved in); how many."""
    taken = 0
    part = out.with_name(out.name + ".part")
    with tempfile.TemporaryDirectory(prefix="mazesim-imports-") as work, part.open("w") as lines:
        for project in projects:
            row = import_row(project, mirrors, Path(work))
            if row is not None:
                lines.write(json.dumps(row) + "\n")
                taken += 1
    part.replace(out)
    return taken


@dataclass
class Change:
    """How a row's import differs between two snapshots."""

    name: str
    tables: dict[str, tuple[int, int]] = field(default_factory=dict)
    world: bool = False
    gained: list[str] = field(default_factory=list)
    lost: list[str] = field(default_factory=list)
    error: tuple[str, str] | None = None

    def __str__(self) -> str:
        said = [f"{table} {a} -> {b}" for table, (a, b) in sorted(self.tables.items())]
        if self.world and not self.tables:
            said.append("the same tables, other values or order")
        if self.gained or self.lost:
            said.append(f"warnings +{len(self.gained)} -{len(self.lost)}")
        if self.error is not None:
            said.append(f"error {self.error[0]!r} -> {self.error[1]!r}")
        return f"{self.name}: " + "; ".join(said)


def _tables(world: str) -> Counter[str]:
    return Counter(_TABLE.findall(world))


def compare(before: dict[str, dict[str, Any]], after: dict[str, dict[str, Any]]) -> list[Change]:
    """The rows of both snapshots whose import changed, in ``before``'s order."""
    changes = []
    for name, old in before.items():
        new = after.get(name)
        if new is None or new == old:
            continue
        change = Change(name)
        if old.get("error") != new.get("error"):
            change.error = (old.get("error", ""), new.get("error", ""))
        a, b = _tables(old.get("world", "")), _tables(new.get("world", ""))
        change.tables = {t: (a[t], b[t]) for t in a | b if a[t] != b[t]}
        change.world = old.get("world") != new.get("world")
        old_warnings, new_warnings = old.get("warnings", []), new.get("warnings", [])
        change.gained = [w for w in new_warnings if w not in old_warnings]
        change.lost = [w for w in old_warnings if w not in new_warnings]
        changes.append(change)
    return changes


def read(path: Path) -> dict[str, dict[str, Any]]:
    """A snapshot: its rows by name."""
    rows = (json.loads(line) for line in path.read_text(encoding="utf-8").splitlines() if line)
    return {row["name"]: row for row in rows}


def main(argv: list[str] | None = None) -> int:
    """``take`` or ``compare``; 0 when done."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    verbs = parser.add_subparsers(dest="verb", required=True)
    taking = verbs.add_parser("take", help="import every row's world and write a snapshot")
    taking.add_argument("--mirrors", type=Path, required=True, help="folder of git mirrors")
    taking.add_argument("--out", type=Path, required=True, help="the snapshot (.jsonl) to write")
    taking.add_argument("--only", nargs="*", default=None, help="project names to import")
    comparing = verbs.add_parser("compare", help="the rows whose import changed")
    comparing.add_argument("before", type=Path)
    comparing.add_argument("after", type=Path)
    args = parser.parse_args(argv)
    if args.verb == "take":
        projects = load_manifest()
        if args.only:
            projects = [p for p in projects if p.name in set(args.only)]
        taken = take(projects, args.mirrors, args.out)
        print(f"wrote {args.out} ({taken} of {len(projects)} rows' worlds imported)")
        return 0
    before, after = read(args.before), read(args.after)
    changes = compare(before, after)
    for change in changes:
        print(change)
    print(f"{len(changes)} of {len(before)} imports changed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
