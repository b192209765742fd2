"""A partial mirror stands in for a repository too large to mirror: the runner's mirror
functions read a row's files at the row's commit from it, and a real mirror is left alone."""

from __future__ import annotations

import subprocess
from dataclasses import replace
from pathlib import Path

from webots_corpus.manifest import Project
from webots_corpus.mirrors import export, find_mirror, has_commit, read_file
from webots_corpus.partial_mirror import build, row_files

COMMIT = "0123456789abcdef0123456789abcdef01234567"


def _project(commit: str = COMMIT) -> Project:
    return Project(
        name="someone/big-sample",
        repo="someone/big",
        commit=commit,
        world="samples/demo/worlds/demo.wbt",
        controllers=("samples/demo/controllers/demo/demo.c", "shared/helper/helper.c"),
        language="c",
        does="drives",
        seconds=1.0,
        expect=("exit 0",),
    )


def _files(tmp_path: Path) -> Path:
    """Files read one by one, at their repository paths, and one outside the row's folders."""
    files = tmp_path / "files"
    for name, text in {
        "samples/demo/worlds/demo.wbt": "#VRML_SIM R2023b utf8\n",
        "samples/demo/protos/Thing.proto": "PROTO Thing [] { Solid {} }\n",
        "samples/demo/controllers/demo/demo.c": "int main() { return 0; }\n",
        "shared/helper/helper.c": "int helper;\n",
        "other/unrelated.c": "int other;\n",
    }.items():
        path = files / "someone+big" / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    return files


def test_a_partial_mirror_answers_for_the_rows_commit(tmp_path: Path) -> None:
    files = _files(tmp_path)
    mirrors = tmp_path / "mirrors"
    project = _project()
    assert row_files(project, files / "someone+big") == [
        "samples/demo/controllers/demo/demo.c",
        "samples/demo/protos/Thing.proto",
        "samples/demo/worlds/demo.wbt",
        "shared/helper/helper.c",
    ]
    said = build(mirrors, files, "someone/big", [project])
    assert said == ["someone/big-sample: 4 files as 0123456789ab"]
    git_dir = find_mirror(mirrors, "someone/big")
    assert git_dir is not None and has_commit(git_dir, COMMIT)
    assert not has_commit(git_dir, "f" * 40)
    assert read_file(git_dir, COMMIT, "shared/helper/helper.c") == b"int helper;\n"
    into = tmp_path / "export"
    assert export(git_dir, COMMIT, ["samples/demo"], into) == 0
    assert sorted(p.relative_to(into).as_posix() for p in into.rglob("*") if p.is_file()) == [
        "samples/demo/controllers/demo/demo.c",
        "samples/demo/protos/Thing.proto",
        "samples/demo/worlds/demo.wbt",
    ]
    # A second row at the same commit, from another folder: the commit holds both rows' files.
    other = replace(
        project,
        name="someone/other-sample",
        world="other/worlds/other.wbt",
        controllers=("other/unrelated.c",),
    )
    (files / "someone+big" / "other/worlds").mkdir(parents=True)
    (files / "someone+big" / "other/worlds/other.wbt").write_text("#VRML_SIM R2023b utf8\n")
    build(mirrors, files, "someone/big", [project, other])
    assert read_file(git_dir, COMMIT, "other/unrelated.c") == b"int other;\n"
    assert read_file(git_dir, COMMIT, "shared/helper/helper.c") == b"int helper;\n"
    # Built again (more files read since), the row's commit names the new files.
    (files / "someone+big" / "samples/demo/controllers/demo/demo.c").write_text("int x;\n")
    build(mirrors, files, "someone/big", [project])
    assert read_file(git_dir, COMMIT, "samples/demo/controllers/demo/demo.c") == b"int x;\n"


def test_a_real_mirror_holding_the_commit_is_left_alone(tmp_path: Path) -> None:
    git_dir = tmp_path / "mirrors" / "someone+big" / "repo"
    subprocess.run(["git", "init", "-q", "--bare", str(git_dir)], check=True)
    env = ["-c", "user.name=t", "-c", "user.email=t@example.org"]
    tree = (
        subprocess.run(
            ["git", "--git-dir", str(git_dir), "mktree"], input=b"", capture_output=True, check=True
        )
        .stdout.decode()
        .strip()
    )
    real = (
        subprocess.run(
            ["git", *env, "--git-dir", str(git_dir), "commit-tree", tree, "-m", "real"],
            capture_output=True,
            check=True,
        )
        .stdout.decode()
        .strip()
    )
    said = build(tmp_path / "mirrors", _files(tmp_path), "someone/big", [_project(real)])
    assert said == [f"someone/big-sample: the mirror holds {real[:12]} itself"]
    listed = subprocess.run(
        ["git", "--git-dir", str(git_dir), "ls-tree", "-r", real], capture_output=True, check=True
    )
    assert listed.stdout == b""
