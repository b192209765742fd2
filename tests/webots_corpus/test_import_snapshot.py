"""An import snapshot holds each row's world as mazesim imports it, and comparing two names the
rows whose import changed and how."""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

from webots_corpus.import_snapshot import compare, main, read, take
from webots_corpus.manifest import Project
from webots_corpus.partial_mirror import build

COMMIT = "89abcdef0123456789abcdef0123456789abcdef"
WORLD = """#VRML_SIM R2023b utf8
E-puck { translation 0 0 0 controller "drive" }
Solid { translation 0.3 0 0.05 children [ DEF W Shape { geometry Box { size 0.02 0.4 0.1 } } ]
  boundingObject USE W }
Solid { translation 0 0.3 0.2 boundingObject Box { size 0.1 0.1 0.1 } }
Solid { translation 0 -0.3 0.05 children [ Shape { appearance PBRAppearance {
  baseColorMap ImageTexture { url [ "textures/absent.png" ] } }
  geometry Box { size 0.1 0.1 0.1 } } ] boundingObject Box { size 0.1 0.1 0.1 } }
"""


def _project(name: str = "someone/walls") -> Project:
    return Project(
        name=name,
        repo="someone/maze",
        commit=COMMIT,
        world="walls/worlds/walls.wbt",
        controllers=("walls/controllers/drive/drive.py",),
        language="python",
        does="drives",
        seconds=1.0,
        expect=("exit 0",),
    )


def test_a_snapshot_holds_each_rows_import_and_a_comparison_names_what_changed(
    tmp_path: Path,
) -> None:
    files = tmp_path / "files" / "someone+maze"
    for path, text in {
        "walls/worlds/walls.wbt": WORLD,
        "walls/controllers/drive/drive.py": "from controller import Robot\n",
    }.items():
        (files / path).parent.mkdir(parents=True, exist_ok=True)
        (files / path).write_text(text, encoding="utf-8")
    mirrors = tmp_path / "mirrors"
    build(mirrors, tmp_path / "files", "someone/maze", [_project()])
    elsewhere = replace(_project("someone/elsewhere"), repo="someone/absent")
    before = tmp_path / "before.jsonl"
    assert take([_project(), elsewhere], mirrors, before) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["before.jsonl", "files", "mirrors"]
    (row,) = read(before).values()
    assert row["name"] == "someone/walls"
    assert row["world"].count("[[walls]]") == 2, row["world"]  # none of the box above the robot
    assert any("passes over the robot" in w for w in row["warnings"]), row["warnings"]
    assert any("walls/worlds/textures/absent.png" in w for w in row["warnings"]), row["warnings"]
    assert not any(str(tmp_path) in w or "/tmp" in w for w in row["warnings"]), row["warnings"]
    again = tmp_path / "again.jsonl"  # another temporary folder for the export: the same rows
    take([_project()], mirrors, again)
    assert compare(read(before), read(again)) == []

    # The same row as another build might import it: one more paint, a warning traded.
    changed = dict(row)
    changed["world"] = row["world"] + '\n[[paint]]\nshape = "circle"\n'
    changed["warnings"] = [*row["warnings"][1:], "a new warning"]
    after = tmp_path / "after.jsonl"
    after.write_text(json.dumps(changed) + "\n", encoding="utf-8")
    (change,) = compare(read(before), read(after))
    assert change.tables == {"paint": (0, 1)}
    assert change.gained == ["a new warning"] and change.lost == row["warnings"][:1]
    assert str(change).startswith("someone/walls: paint 0 -> 1; warnings +1 -1")


def test_compare_on_the_command_line_counts_the_changed_imports(
    tmp_path: Path, capsys: object
) -> None:
    rows = [{"name": "a/one", "world": "[[walls]]\n", "warnings": []}]
    before, after = tmp_path / "before.jsonl", tmp_path / "after.jsonl"
    before.write_text("".join(json.dumps(r) + "\n" for r in rows), encoding="utf-8")
    rows[0]["error"] = "WorldFormatError: bad"
    after.write_text("".join(json.dumps(r) + "\n" for r in rows), encoding="utf-8")
    assert main(["compare", str(before), str(after)]) == 0
    out = capsys.readouterr().out  # type: ignore[attr-defined]
    assert "a/one: error '' -> 'WorldFormatError: bad'" in out
    assert out.rstrip().endswith("1 of 1 imports changed")
