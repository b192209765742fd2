"""Local git mirrors of the corpus's repositories, and a project's files exported from one.

A mirror of ``owner/name`` is a git directory (bare, or a clone's ``.git``) in the mirrors
folder, under any of the names :func:`candidates` lists. Nothing is fetched from a network.
"""

from __future__ import annotations

import io
import subprocess
from pathlib import Path

GIT_TIMEOUT_S = 60


class MirrorError(RuntimeError):
    """A mirror is missing, lacks the commit, or cannot be read."""


def candidates(mirrors: Path, repo: str) -> list[Path]:
    """Where a mirror of ``owner/name`` may be: ``owner+name/repo`` (bare or with ``.git``),
    ``owner+name(.git)``, ``owner/name(.git)``."""
    owner, name = repo.split("/", 1)
    joined = mirrors / f"{owner}+{name}"
    return [
        joined / "repo" / ".git",
        joined / "repo",
        joined / ".git",
        joined,
        mirrors / f"{owner}+{name}.git",
        mirrors / owner / f"{name}.git",
        mirrors / owner / name / ".git",
        mirrors / owner / name,
    ]


def _git(git_dir: Path, *args: str) -> subprocess.CompletedProcess[bytes]:
    return subprocess.run(
        ["git", "--git-dir", str(git_dir), *args],
        capture_output=True,
        timeout=GIT_TIMEOUT_S,
        check=False,
    )


def find_mirror(mirrors: Path, repo: str) -> Path | None:
    """The git directory of the repository's mirror, or None."""
    for path in candidates(mirrors, repo):
        if (path / "HEAD").is_file() and (path / "objects").is_dir():
            return path
    return None


def has_commit(git_dir: Path, commit: str) -> bool:
    """Whether the mirror holds the commit, or a commit standing in for it (a ``refs/replace/``
    reference, as a partial mirror has: :mod:`webots_corpus.partial_mirror`)."""
    found = _git(git_dir, "rev-parse", "--verify", "--quiet", f"{commit}^{{commit}}")
    return found.returncode == 0


def read_file(git_dir: Path, commit: str, path: str) -> bytes:
    """A file's bytes at a commit.

    Raises:
        MirrorError: The commit has no such file.
    """
    shown = _git(git_dir, "show", f"{commit}:{path}")
    if shown.returncode != 0:
        raise MirrorError(f"{path} is not in commit {commit[:12]}")
    return shown.stdout


def export(git_dir: Path, commit: str, paths: list[str], into: Path) -> int:
    """Writes the files under ``paths`` (folders or files; ``""`` for all) at ``commit`` into
    ``into``, keeping their paths. Files the mirror lacks (a snapshot may leave out large
    files) are left out.

    Returns:
        The number of files left out.

    Raises:
        MirrorError: git cannot list the commit's files.
    """
    wanted = sorted({p.strip("/") for p in paths})
    pathspecs = [] if "" in wanted else wanted
    listed = _git(git_dir, "ls-tree", "-r", "-z", commit, "--", *pathspecs)
    if listed.returncode != 0:
        message = listed.stderr.decode("utf-8", "replace").strip()
        raise MirrorError(f"cannot list {pathspecs or 'the commit'}: {message}")
    blobs: list[tuple[str, str]] = []
    for entry in listed.stdout.decode("utf-8", "surrogateescape").split("\0"):
        meta, _, name = entry.partition("\t")
        fields = meta.split()
        if len(fields) == 3 and fields[1] == "blob" and _safe(name):
            blobs.append((fields[2], name))
    batch = subprocess.run(
        ["git", "--git-dir", str(git_dir), "cat-file", "--batch"],
        input="".join(f"{sha}\n" for sha, _ in blobs).encode(),
        capture_output=True,
        timeout=GIT_TIMEOUT_S,
        check=False,
    )
    stream = io.BytesIO(batch.stdout)
    left_out = 0
    for _, name in blobs:
        header = stream.readline().split()
        if len(header) != 3:  # "<sha> missing"
            left_out += 1
            continue
        content = stream.read(int(header[2]))
        stream.read(1)  # the newline after each object
        target = into / name
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(content)
    return left_out


def _safe(name: str) -> bool:
    """A member name that stays inside the folder it is extracted into."""
    parts = Path(name).parts
    return not Path(name).is_absolute() and ".." not in parts
