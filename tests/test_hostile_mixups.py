"""Hostile inputs that mix things up (issue #15): a cache folder an environment variable places
where a file is. It is refused saying what it is and what to do, not by a later step that cannot
write."""

from __future__ import annotations

from pathlib import Path

import pytest

from mazesim.errors import MazesimIOError
from mazesim.webots.native_controller import cache_folder
from mazesim.webots.proto import cache_dir, fetch_url


def test_a_cache_variable_naming_a_file_is_refused_naming_the_variable(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    file = tmp_path / "cache"
    file.write_text("not a folder")
    monkeypatch.setenv("MAZESIM_OFFLINE", "1")
    monkeypatch.setenv("MAZESIM_PROTO_CACHE", str(file))
    with pytest.raises(MazesimIOError, match=r"\$MAZESIM_PROTO_CACHE names .* it is a file, not a"):
        fetch_url("https://example.invalid/Thing.proto")
    monkeypatch.setenv("MAZESIM_CACHE", str(file))
    with pytest.raises(MazesimIOError, match="but above it, .*cache, is a file, not a folder"):
        cache_folder()
    monkeypatch.setenv("MAZESIM_PROTO_CACHE", str(tmp_path / "new" / "protos"))
    assert cache_dir() == tmp_path / "new" / "protos"
