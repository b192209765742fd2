"""A partial mirror: a local git repository that stands in for a repository too large to mirror
whole, holding only the files its manifest rows run, read one by one.

Usage: ``python tests/webots_corpus/partial_mirror.py --mirrors DIR --files CACHE --repo
OWNER/NAME``. ``CACHE/OWNER+NAME/`` holds files at their repository paths (each the stored
version of that file, read by hand; nothing of it is kept in this repository). For each row of
``manifest.toml`` from that repository, the files of ``CACHE`` under the folders the runner
exports for the row (its project's folder, its controllers' folders, its ``exports``) become one
local commit, and the git ``refs/replace/`` reference of the row's commit points at it: the
runner's ``git show COMMIT:PATH`` and ``git ls-tree COMMIT`` then read those files (rows at one
commit share that local commit, which holds all their files). A row whose commit a real mirror in
``DIR`` holds is left as it is.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
from pathlib import Path

if __package__ in (None, ""):  # run as a script: import the package from tests/
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from webots_corpus.manifest import Project, load_manifest
from webots_corpus.mirrors import find_mirror, has_commit

#: The author and committer of the local commits (their hash does not matter: the replace
#: reference names them).
_IDENTITY = {
    "GIT_AUTHOR_NAME": "partial mirror",
    "GIT_AUTHOR_EMAIL": "partial-mirror@localhost",
    "GIT_COMMITTER_NAME": "partial mirror",
    "GIT_COMMITTER_EMAIL": "partial-mirror@localhost",
    "GIT_AUTHOR_DATE": "2000-01-01T00:00:00Z",
    "GIT_COMMITTER_DATE": "2000-01-01T00:00:00Z",
}


def _git(git_dir: Path, *args: str, stdin: bytes = b"") -> str:
    done = subprocess.run(
        ["git", "--git-dir", str(git_dir), *args],
        input=stdin,
        capture_output=True,
        env=dict(os.environ, **_IDENTITY),
        check=True,
    )
    return done.stdout.decode().strip()


def row_files(project: Project, files: Path) -> list[str]:
    """The repository paths under ``files`` that the runner exports for the row."""
    folders = [project.root, *(str(Path(c).parent) for c in project.controllers)]
    folders += list(project.exports)
    wanted = {("" if f == "." else f.strip("/")) for f in folders}
    found = set()
    for path in files.rglob("*"):
        if path.is_file():
            name = path.relative_to(files).as_posix()
            if any(not f or name.startswith(f"{f}/") for f in wanted):
                found.add(name)
    return sorted(found)


def _tree(git_dir: Path, files: Path, names: list[str]) -> str:
    """Writes the files as blobs and trees; the root tree's hash."""
    children: dict[str, dict[str, str]] = {}
    blobs: dict[str, str] = {}
    for name in names:
        blobs[name] = _git(git_dir, "hash-object", "-w", str(files / name))
    entries: dict[str, list[str]] = {"": []}
    for name in names:
        parts = name.split("/")
        for depth in range(1, len(parts)):
            entries.setdefault("/".join(parts[:depth]), [])
    for folder in sorted(entries, key=lambda f: -f.count("/") - (1 if f else 0)):
        files_here = [n for n in names if _parent(n) == folder]
        lines = [f"100644 blob {blobs[n]}\t{n.rsplit('/', 1)[-1]}" for n in files_here]
        lines += [f"040000 tree {children[folder][c]}\t{c}" for c in children.get(folder, {})]
        tree = _git(git_dir, "mktree", stdin=("\n".join(lines) + "\n").encode())
        if folder:
            children.setdefault(_parent(folder), {})[folder.rsplit("/", 1)[-1]] = tree
        else:
            return tree
    raise AssertionError("the root tree is written last")


def _parent(name: str) -> str:
    return name.rsplit("/", 1)[0] if "/" in name else ""


def build(mirrors: Path, files: Path, repo: str, projects: list[Project]) -> list[str]:
    """Builds or completes the partial mirror of ``repo`` in ``mirrors`` for its rows.

    Returns:
        What was done, a line per row.
    """
    cache = files / repo.replace("/", "+")
    git_dir = find_mirror(mirrors, repo)
    if git_dir is None:
        git_dir = mirrors / repo.replace("/", "+") / "repo"
        git_dir.mkdir(parents=True)
        _git(git_dir, "init", "--quiet", "--bare")
    said = []
    rows = [p for p in projects if p.repo == repo]
    for project in rows:
        # Rows at one commit share its stand-in: it holds the files of all of them.
        sharing = [p for p in rows if p.commit == project.commit]
        names = sorted({name for p in sharing for name in row_files(p, cache)})
        replaced = _git(git_dir, "for-each-ref", f"refs/replace/{project.commit}")
        if has_commit(git_dir, project.commit) and not replaced:
            said.append(f"{project.name}: the mirror holds {project.commit[:12]} itself")
            continue
        if not names:
            said.append(f"{project.name}: no files under {cache}")
            continue
        tree = _tree(git_dir, cache, names)
        commit = _git(git_dir, "commit-tree", tree, "-m", f"{repo} files of {project.name}")
        _git(git_dir, "update-ref", f"refs/replace/{project.commit}", commit)
        said.append(f"{project.name}: {len(names)} files as {project.commit[:12]}")
    return said


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--mirrors", type=Path, required=True, help="folder of git mirrors")
    parser.add_argument("--files", type=Path, required=True, help="folder of files read")
    parser.add_argument("--repo", required=True, help="owner/name")
    args = parser.parse_args(argv)
    for line in build(args.mirrors, args.files, args.repo, load_manifest()):
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
