"""The compatibility corpus's manifest: public e-puck Webots projects, each named by repository,
commit and paths, with the behaviour expected of it written as checkable facts.

The manifest (``manifest.toml`` beside this file) holds no third-party code, only where to find
it. Each ``[[project]]`` table has these fields:

- ``name``: unique, ``owner/short-name``;
- ``repo``: ``owner/name`` of the public repository; ``commit``: 40 hex digits;
- ``world``: the ``.wbt`` file's path in the repository;
- ``controllers``: the controller files' paths (the first is the one run: the robot's own);
- ``language``: ``python``, ``c``, ``cpp`` or ``botstudio`` (what the first controller is
  written in: a BotStudio automaton for the last), or a language Webots runs controllers in that
  mazesim names as one it does not run (``java``, ``matlab``: :data:`NOT_RUN`), whose row is
  then not run, its cause what the run says of it;
- ``does``: what the project does, in a sentence;
- ``seconds``: the simulated time a run lasts; the run may take 30 s of wall-clock time more
  (``runner.GRACE_S``), so a controller whose own ``time.sleep`` calls cost wall-clock time (in
  Webots too: the simulation waits for its next step) is given a simulated time it reaches;
- ``expect``: the facts a run in Webots shows (see :mod:`webots_corpus.facts`);
- ``broken``: empty when the project works in Webots as published, else why it does not;
- optional ``known``: what is known of why a run here does not show the expected facts, with
  its figures (a row that does not pass ends its cause with it);
- optional ``alone``: why the corpus runs the project's first controller alone though its
  world starts several (the row's cause begins with it); without it such a world runs whole;
- optional ``exports``: repository paths the run needs besides the project's folder and its
  controllers' (``""``: the whole repository), such as the library a controller's own
  ``CMakeLists.txt`` builds from the repository's root;
- optional ``packages``: third-party Python packages its controller imports (for the reader: the
  run itself says at its start which of them are missing); ``keys``: a keyboard script
  (``time_s key [duration_s]`` lines, ``mazesim webots run --keys``).
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - the venv is 3.11; tomli is tomllib's backport
    import tomli as tomllib

from mazesim.webots.runner import OTHER_LANGUAGES
from webots_corpus.facts import parse_fact

MANIFEST = Path(__file__).with_name("manifest.toml")
#: The languages of the controllers mazesim runs (``botstudio``: a BotStudio automaton).
RUN = ("python", "c", "cpp", "botstudio")
#: The other languages of Webots' controllers, which mazesim's runner names as not run.
NOT_RUN = tuple(sorted({language.lower() for language in OTHER_LANGUAGES.values()}))
LANGUAGES = RUN + NOT_RUN
REQUIRED = ("name", "repo", "commit", "world", "controllers", "language", "does", "seconds")
REQUIRED_LISTS = ("expect",)
_HEX40 = re.compile(r"[0-9a-f]{40}")
_REPO = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.-]*/[A-Za-z0-9][A-Za-z0-9_.-]*")


class ManifestError(ValueError):
    """The manifest does not have the shape this module documents."""


@dataclass(frozen=True)
class Project:
    """One project of the corpus: a world and its controllers at one commit."""

    name: str
    repo: str
    commit: str
    world: str
    controllers: tuple[str, ...]
    language: str
    does: str
    seconds: float
    expect: tuple[str, ...]
    broken: str = ""
    known: str = ""
    alone: str = ""
    packages: tuple[str, ...] = ()
    keys: tuple[str, ...] = field(default=())
    exports: tuple[str, ...] = ()

    @property
    def root(self) -> str:
        """The project's folder in the repository: the parent of the world's ``worlds/``
        folder (where Webots looks for ``controllers/`` and ``protos/``), else the world's
        own folder."""
        parts = self.world.split("/")
        if len(parts) >= 2 and parts[-2] == "worlds":
            return "/".join(parts[:-2])
        return "/".join(parts[:-1])


def _check(index: int, table: dict[str, Any]) -> Project:
    where = f"project {index + 1} ({table.get('name', '?')})"
    for key in REQUIRED:
        if key not in table:
            raise ManifestError(f"{where}: expected the field {key!r}, found none")
    for key in ("name", "repo", "commit", "world", "language", "does"):
        if not isinstance(table[key], str) or not table[key].strip():
            raise ManifestError(f"{where}: expected {key} a non-empty string, found {table[key]!r}")
    if not _HEX40.fullmatch(table["commit"]):
        raise ManifestError(f"{where}: expected commit 40 hex digits, found {table['commit']!r}")
    if not _REPO.fullmatch(table["repo"]):
        raise ManifestError(f"{where}: expected repo owner/name, found {table['repo']!r}")
    if not table["world"].endswith(".wbt"):
        raise ManifestError(f"{where}: expected world a .wbt path, found {table['world']!r}")
    if table["language"] not in LANGUAGES:
        raise ManifestError(
            f"{where}: expected language in {LANGUAGES}, found {table['language']!r}"
        )
    seconds = table["seconds"]
    if isinstance(seconds, bool) or not isinstance(seconds, (int, float)) or not 0 < seconds <= 120:
        raise ManifestError(f"{where}: expected seconds in (0, 120], found {seconds!r}")
    controllers = table["controllers"]
    if not isinstance(controllers, list) or not controllers:
        raise ManifestError(
            f"{where}: expected controllers a non-empty list, found {controllers!r}"
        )
    for key in ("controllers", "expect", "packages", "keys"):
        values = table.get(key, [])
        if not isinstance(values, list) or not all(isinstance(v, str) and v for v in values):
            raise ManifestError(f"{where}: expected {key} a list of strings, found {values!r}")
    exports = table.get("exports", [])
    if not isinstance(exports, list) or not all(isinstance(v, str) for v in exports):
        raise ManifestError(f"{where}: expected exports a list of paths, found {exports!r}")
    broken = table.get("broken", "")
    if not isinstance(broken, str):
        raise ManifestError(f"{where}: expected broken a string, found {broken!r}")
    known = table.get("known", "")
    alone = table.get("alone", "")
    for key, text in (("known", known), ("alone", alone)):
        if not isinstance(text, str):
            raise ManifestError(f"{where}: expected {key} a string, found {text!r}")
    if "broken" not in table:
        raise ManifestError(f"{where}: expected the field 'broken' ('' when it works in Webots)")
    if not table.get("expect") and not broken:
        raise ManifestError(f"{where}: a project that is not broken needs facts in 'expect'")
    for fact in table.get("expect", []):
        try:
            parse_fact(fact)
        except ValueError as error:
            raise ManifestError(f"{where}: {error}") from None
    return Project(
        name=table["name"],
        repo=table["repo"],
        commit=table["commit"],
        world=table["world"],
        controllers=tuple(controllers),
        language=table["language"],
        does=table["does"],
        seconds=float(seconds),
        expect=tuple(table.get("expect", [])),
        broken=broken,
        known=known,
        alone=alone,
        packages=tuple(table.get("packages", [])),
        keys=tuple(table.get("keys", [])),
        exports=tuple(exports),
    )


def parse_manifest(text: str) -> list[Project]:
    """The projects of a manifest's text, checked.

    Raises:
        ManifestError: A field is missing or of the wrong kind, a fact does not parse, or two
            projects share a name.
    """
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ManifestError(f"the manifest is not TOML: {error}") from None
    tables = data.get("project")
    if not isinstance(tables, list) or not tables:
        raise ManifestError("expected [[project]] tables, found none")
    projects = [_check(i, t) for i, t in enumerate(tables)]
    names = [p.name for p in projects]
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        raise ManifestError(f"expected unique project names, found twice: {twice}")
    return projects


def load_manifest(path: Path = MANIFEST) -> list[Project]:
    """The projects of the manifest file (by default the corpus's own)."""
    return parse_manifest(path.read_text(encoding="utf-8"))
