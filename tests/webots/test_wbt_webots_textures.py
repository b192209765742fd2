"""Floor textures named by ``webots://`` URLs (Webots' own sample worlds name theirs so) are
found as the PROTO engine finds a ``webots://`` PROTO: in ``$WEBOTS_HOME``, in the Webots tree
the world lies in, else in Webots' repository at the world's version, through the download
cache; one that cannot be had is named, with its https URL, as a run's missing feature."""

from __future__ import annotations

import urllib.error
import urllib.request
from pathlib import Path

import numpy as np
import pytest

from mazesim.webots.importer import import_wbt_text, undownloaded_textures
from mazesim.webots.proto.resolver import _cached_path

TEXTURE = "projects/samples/worlds/textures/band.png"
RAW = "https://raw.githubusercontent.com/cyberbotics/webots/R2022a/" + TEXTURE


@pytest.fixture(autouse=True)
def _private_cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A cache of the test's own, no Webots installation, and no network: a download fails."""
    monkeypatch.setenv("MAZESIM_PROTO_CACHE", str(tmp_path / "cache"))
    monkeypatch.delenv("WEBOTS_HOME", raising=False)
    monkeypatch.delenv("MAZESIM_OFFLINE", raising=False)

    def unreachable(url: object, timeout: float = 0.0) -> None:
        raise urllib.error.URLError("no network in this test")

    monkeypatch.setattr(urllib.request, "urlopen", unreachable)


def _band(path: Path) -> None:
    """A white image with a black band down its left third."""
    from PIL import Image

    path.parent.mkdir(parents=True, exist_ok=True)
    grey = np.full((30, 30), 255, dtype=np.uint8)
    grey[:, :10] = 0
    Image.fromarray(grey).save(path)


def _world(header: str = "R2022a") -> str:
    return (
        f"#VRML_SIM {header} utf8\nRectangleArena {{\n  floorSize 0.9 0.9\n"
        "  floorTileSize 0.9 0.9\n  floorAppearance PBRAppearance {\n"
        f'    baseColorMap ImageTexture {{ url [ "webots://{TEXTURE}" ] }}\n  }}\n}}\n'
    )


def _painted(world: object) -> bool:
    """Whether the floor holds the band: dark at the left, light at the right."""
    reflectance = world.floor_reflectance  # type: ignore[attr-defined]
    return bool(reflectance(-0.3, 0.0) <= 0.2 and reflectance(0.3, 0.0) > 0.8)


def test_a_webots_texture_is_read_from_the_webots_installation(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    _band(tmp_path / "webots" / TEXTURE)
    monkeypatch.setenv("WEBOTS_HOME", str(tmp_path / "webots"))
    world, report = import_wbt_text(_world(), str(tmp_path / "elsewhere" / "worlds" / "w.wbt"))
    assert _painted(world), report["warnings"]
    assert not [w for w in report["warnings"] if "texture" in w]


def test_a_webots_texture_is_read_from_the_tree_the_world_lies_in(tmp_path: Path) -> None:
    # A sample world of a checkout of Webots' repository names a texture of another project.
    _band(tmp_path / "checkout" / TEXTURE)
    source = tmp_path / "checkout" / "projects" / "robots" / "r" / "worlds" / "w.wbt"
    world, report = import_wbt_text(_world(), str(source))
    assert _painted(world), report["warnings"]


def test_a_webots_texture_comes_from_webots_repository_at_the_world_version(
    tmp_path: Path,
) -> None:
    _band(_cached_path(RAW))
    world, report = import_wbt_text(_world("R2022a"), str(tmp_path / "w.wbt"))
    assert _painted(world), report["warnings"]
    # Of another release, it is another file, which the cache does not hold.
    other, _ = import_wbt_text(_world("R2023b"), str(tmp_path / "w.wbt"))
    assert not _painted(other)


def test_a_webots_texture_that_cannot_be_had_is_a_missing_feature_naming_its_url(
    tmp_path: Path,
) -> None:
    world, report = import_wbt_text(_world(), str(tmp_path / "w.wbt"))
    assert not _painted(world)
    about = [w for w in report["warnings"] if "band.png" in w]
    assert len(about) == 1, report["warnings"]
    assert f"{RAW}: cannot be downloaded" in about[0]
    assert undownloaded_textures(report["warnings"]) == [
        f"the floor texture {RAW}, which cannot be downloaded here and is not in the download "
        "cache (no network): the floor's paint is left out"
    ]
