"""Whether the compiled core a corpus run would use was built from the checkout's sources.

``make build`` installs mazesim in editable mode: the Python package is read from the checkout's
``python/`` as it stands, but the Rust core (``mazesim/_core*.so``) is whatever was compiled
last. A checkout that took in Rust changes (a merge, a pull, a switch of branch) and was not
built again runs today's Python over yesterday's core, and the corpus page would credit the
checkout's commit with the old core's results: a floor texture painted by the code before the
merge, for one. :func:`newer_sources` finds the build inputs changed after the core was
written: every file under ``crates/`` that Cargo reads (``*.rs``, ``Cargo.toml``), the
workspace's ``Cargo.toml`` and ``Cargo.lock``, and each file a crate's source embeds with
``include_str!`` or ``include_bytes!`` (the built-in robot profiles and worlds).
"""

from __future__ import annotations

import importlib.util
import re
from pathlib import Path

__all__ = ["build_inputs", "core_file", "newer_sources", "stale_core_message"]

#: ``include_str!("path")`` or ``include_bytes!("path")`` in a Rust source, the path relative to
#: that source's folder.
_EMBEDDED = re.compile(r"include_(?:str|bytes)!\(\s*\"([^\"]+)\"\s*\)")


def core_file() -> Path | None:
    """The compiled core ``mazesim._core`` that this interpreter imports, or None when it
    has none."""
    spec = importlib.util.find_spec("mazesim._core")
    if spec is None or spec.origin is None:
        return None
    return Path(spec.origin)


def build_inputs(root: Path) -> list[Path]:
    """The files of checkout ``root`` that the core is compiled from (see the module notes),
    those that exist, sorted."""
    crates = root / "crates"
    found = {root / "Cargo.toml", root / "Cargo.lock"}
    found.update(crates.rglob("Cargo.toml"))
    for source in crates.rglob("*.rs"):
        found.add(source)
        text = source.read_text(encoding="utf-8", errors="replace")
        for embedded in _EMBEDDED.findall(text):
            found.add((source.parent / embedded).resolve())
    return sorted(path for path in found if path.is_file())


def newer_sources(core: Path, root: Path) -> list[Path]:
    """The build inputs of checkout ``root`` modified after ``core`` was written, newest
    first."""
    built = core.stat().st_mtime
    newer = [path for path in build_inputs(root) if path.stat().st_mtime > built]
    return sorted(newer, key=lambda path: path.stat().st_mtime, reverse=True)


def stale_core_message(core: Path, root: Path) -> str | None:
    """Why a run of checkout ``root`` must not use ``core``, or None when the core is at least
    as new as every one of its sources."""
    newer = newer_sources(core, root)
    if not newer:
        return None
    shown = ", ".join(str(path.relative_to(root)) for path in newer[:3])
    more = f" and {len(newer) - 3} more" if len(newer) > 3 else ""
    return (
        f"the compiled core {core} is older than {len(newer)} of its sources ({shown}{more}): "
        f"its results would not be the checkout's; run 'make build' first"
    )
