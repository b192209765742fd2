"""A corpus run refuses a compiled core older than its Rust sources: a checkout written here
(crates, an embedded profile, a core file) with its files' times set one by one."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from webots_corpus import run_corpus
from webots_corpus.core_build import build_inputs, newer_sources, stale_core_message

#: Modification times (s since the epoch) of the checkout written here.
BUILT = 2_000_000_000
BEFORE = BUILT - 3600
AFTER = BUILT + 60


def _checkout(root: Path) -> Path:
    """A checkout whose core was built after every source was written; returns the core."""
    files = {
        "Cargo.toml": "[workspace]\n",
        "Cargo.lock": "",
        "crates/core/Cargo.toml": "[package]\n",
        "crates/core/src/lib.rs": 'const P: &str = include_str!("../../../robots/bot.toml");\n',
        "robots/bot.toml": 'name = "bot"\n',
        "robots/unused.toml": 'name = "unused"\n',
        "docs/notes.md": "notes\n",
    }
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
        os.utime(path, (BEFORE, BEFORE))
    core = root / "python" / "pkg" / "_core.so"
    core.parent.mkdir(parents=True)
    core.write_bytes(b"\x7fELF")
    os.utime(core, (BUILT, BUILT))
    return core


def test_the_build_inputs_are_the_crates_the_workspace_and_the_embedded_files(
    tmp_path: Path,
) -> None:
    _checkout(tmp_path)
    names = {str(p.relative_to(tmp_path)) for p in build_inputs(tmp_path)}
    assert names == {
        "Cargo.toml",
        "Cargo.lock",
        "crates/core/Cargo.toml",
        "crates/core/src/lib.rs",
        "robots/bot.toml",
    }


def test_a_core_built_after_its_sources_is_current(tmp_path: Path) -> None:
    core = _checkout(tmp_path)
    assert newer_sources(core, tmp_path) == []
    assert stale_core_message(core, tmp_path) is None
    # Files the core is not built from may change.
    for name in ("robots/unused.toml", "docs/notes.md"):
        os.utime(tmp_path / name, (AFTER, AFTER))
    assert stale_core_message(core, tmp_path) is None


@pytest.mark.parametrize("changed", ["crates/core/src/lib.rs", "robots/bot.toml", "Cargo.lock"])
def test_a_source_changed_after_the_build_makes_the_core_stale(
    tmp_path: Path, changed: str
) -> None:
    core = _checkout(tmp_path)
    os.utime(tmp_path / changed, (AFTER, AFTER))
    assert newer_sources(core, tmp_path) == [tmp_path / changed]
    message = stale_core_message(core, tmp_path)
    assert message is not None
    assert changed in message and "make build" in message


def test_the_corpus_refuses_to_run_on_a_stale_core(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """Before any project runs or any page is written: the checkout's own sources are all newer
    than a core file dated 1970."""
    core = tmp_path / "_core.so"
    core.write_bytes(b"\x7fELF")
    os.utime(core, (0, 0))
    monkeypatch.setattr(run_corpus, "core_file", lambda: core)
    out = tmp_path / "page.md"
    arguments = ["--mirrors", str(tmp_path), "--out", str(out), "--only", "no/such"]
    assert run_corpus.main(arguments) == 2
    assert not out.exists()
    assert "older than" in capsys.readouterr().err
