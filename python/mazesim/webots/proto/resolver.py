"""Where a PROTO's file is, found as Webots finds it: the ``EXTERNPROTO`` declaration of the file
that uses it (a path relative to that file, ``webots://`` or an http(s) URL), the project's
``protos/`` folder, the Webots installation named by ``WEBOTS_HOME``, or for a ``webots://`` URL
(or its https form in Webots' repository, which Webots writes into the worlds it saves) the
Webots tree the world itself lies in (Webots' own sample worlds). URLs are downloaded once
into a cache (``MAZESIM_PROTO_CACHE``, by default ``~/.cache/mazesim/protos``) and read from it
afterwards; ``MAZESIM_OFFLINE=1`` forbids downloads. ``webots://`` is Webots' own repository at
the world's version when no installation has the file."""

from __future__ import annotations

import hashlib
import http.client
import os
import re
import urllib.error
import urllib.parse
import urllib.request
from dataclasses import dataclass
from pathlib import Path

from mazesim._atomic import atomic_file
from mazesim._paths import cache_folder, read_input
from mazesim.errors import MazesimIOError

__all__ = ["ProtoSource", "ProtoUnavailableError", "Resolver", "cache_dir", "fetch_url"]

#: Largest PROTO file or texture read or downloaded, bytes.
MAX_DOWNLOAD_BYTES = 16 * 1024 * 1024
#: Seconds a download may take.
DOWNLOAD_TIMEOUT_S = 20.0
_WEBOTS_RAW = "https://raw.githubusercontent.com/cyberbotics/webots/{version}/"
#: Webots' repository at a release tag (or a branch or commit), and the path in it.
_WEBOTS_REPOSITORY = re.compile(
    r"https://raw\.githubusercontent\.com/cyberbotics/webots/[^/]+/(.+)"
)


class ProtoUnavailableError(MazesimIOError):
    """A PROTO or texture URL that cannot be downloaded and is not in the cache."""


def cache_dir() -> Path:
    """The download cache: ``$MAZESIM_PROTO_CACHE`` or ``~/.cache/mazesim/protos``.

    Raises:
        MazesimIOError: It, or a folder above it, is a file (the message names the variable
            that set it).
    """
    return cache_folder("MAZESIM_PROTO_CACHE", "protos")


def _cached_path(url: str) -> Path:
    digest = hashlib.sha256(url.encode("utf-8", "surrogatepass")).hexdigest()[:20]
    name = urllib.parse.urlsplit(url).path.rsplit("/", 1)[-1] or "file"
    return cache_dir() / digest / name


def fetch_url(url: str) -> Path:
    """The local copy of a URL: from the cache, else downloaded into it.

    Raises:
        ProtoUnavailableError: Not in the cache and cannot be downloaded (offline, unreachable,
            not found); the message names the URL and where to put the file instead.
    """
    target = _cached_path(url)
    if target.is_file():
        return target
    advice = (
        f"download it into the project's protos/ folder (or to {target}), set WEBOTS_HOME to a "
        "Webots installation, or run once with a network"
    )
    if os.environ.get("MAZESIM_OFFLINE", "") not in ("", "0"):
        raise ProtoUnavailableError(f"{url}: not in the cache and MAZESIM_OFFLINE is set: {advice}")
    try:
        with urllib.request.urlopen(url, timeout=DOWNLOAD_TIMEOUT_S) as response:  # noqa: S310
            data = response.read(MAX_DOWNLOAD_BYTES + 1)
    except (urllib.error.URLError, http.client.HTTPException, OSError, ValueError) as error:
        reason = getattr(error, "reason", error)
        raise ProtoUnavailableError(f"{url}: cannot be downloaded ({reason}): {advice}") from None
    if len(data) > MAX_DOWNLOAD_BYTES:
        raise ProtoUnavailableError(f"{url}: larger than {MAX_DOWNLOAD_BYTES} bytes: {advice}")
    target.parent.mkdir(parents=True, exist_ok=True)
    with atomic_file(target) as handle:
        handle.write(data)
    return target


@dataclass(frozen=True)
class ProtoSource:
    """A PROTO file found: its text and where it came from (a path or URL; the base for its own
    relative ``EXTERNPROTO``)."""

    text: str
    origin: str


def as_webots_url(url: str) -> str | None:
    """A PROTO URL of Webots' own library as ``webots://PATH``: a ``webots://`` URL itself, or
    its https form in Webots' repository at a release
    (``https://raw.githubusercontent.com/cyberbotics/webots/R2025a/PATH``, what Webots writes
    into the worlds it saves); None for any other URL or path. Webots reads either from its
    installation; so does the import (:meth:`Resolver.webots_file`) before downloading."""
    if url.startswith("webots://"):
        return url
    found = _WEBOTS_REPOSITORY.fullmatch(url)
    return None if found is None else "webots://" + found.group(1)


def is_url(location: str) -> bool:
    """Whether a location is an http(s) URL (else a path)."""
    return location.startswith(("http://", "https://"))


def _read(path: Path) -> str:
    data = read_input(path, MAX_DOWNLOAD_BYTES, "the PROTO file")
    if len(data) > MAX_DOWNLOAD_BYTES:
        raise MazesimIOError(f"{path}: a PROTO file larger than {MAX_DOWNLOAD_BYTES} bytes")
    return data.decode("utf-8", errors="replace")


class Resolver:
    """Finds PROTO files for one world.

    Args:
        world: The world file's path.
        version: The world's Webots version tag (``R2023b``), for ``webots://`` URLs.
    """

    def __init__(self, world: str, version: str) -> None:
        self.world = os.path.abspath(world)
        self.version = version
        worlds_dir = os.path.dirname(self.world)
        self.project = os.path.dirname(worlds_dir)
        self._project_protos: dict[str, str] | None = None
        self._webots_protos: dict[str, str] | None = None
        #: URLs read from the cache (not downloaded) by this resolver.
        self.cache_hits: list[str] = []
        #: URLs downloaded by this resolver.
        self.downloads: list[str] = []

    def webots_url(self, url: str) -> str:
        """``webots://path`` as Webots' repository URL at the world's version."""
        return _WEBOTS_RAW.format(version=self.version) + url[len("webots://") :]

    def declared(self, url: str, base: str) -> ProtoSource | None:
        """The file of an ``EXTERNPROTO`` URL written in a file at ``base``.

        Returns None for a relative path that does not exist (one that is no regular file, a
        device or a folder, is read and refused as such: it exists).

        Raises:
            ProtoUnavailableError: A URL cannot be downloaded.
        """
        webots = as_webots_url(url)
        if webots is not None:
            local = self.webots_file(webots)
            if local is not None:
                return ProtoSource(_read(local), str(local))
            return self.url(url if is_url(url) else self.webots_url(url))
        if is_url(url):
            return self.url(url)
        if is_url(base):
            return self.url(urllib.parse.urljoin(base, url))
        path = Path(os.path.dirname(base)) / url
        if path.exists():
            return ProtoSource(_read(path), str(path.resolve()))
        return None

    def webots_file(self, url: str) -> Path | None:
        """The local file of a ``webots://`` URL (a PROTO or a texture): in the Webots
        installation named by ``WEBOTS_HOME``, else in the Webots tree the world lies in; None
        when neither holds it (it is then Webots' repository at :meth:`webots_url`)."""
        path = url[len("webots://") :]
        home = os.environ.get("WEBOTS_HOME")
        if home:
            local = Path(home) / path
            if local.is_file():
                return local
        return self.in_world_tree(path)

    def webots_texture(self, url: str) -> Path:
        """The local copy of a ``webots://`` texture URL: :meth:`webots_file`, else downloaded
        from Webots' repository at the world's version through the cache.

        Raises:
            ProtoUnavailableError: Neither installed, in the world's tree nor in the cache, and
                it cannot be downloaded (the message names the https URL).
        """
        local = self.webots_file(url)
        return local if local is not None else fetch_url(self.webots_url(url))

    def in_world_tree(self, path: str) -> Path | None:
        """The file at ``path`` of the Webots tree the world lies in, or None: a world of Webots'
        own (a sample world of a checkout of its repository, or a copy of one of its projects
        kept at its place in the tree) names its project's PROTOs by ``webots://`` URLs, which
        Webots reads from the installation the world lies in; the nearest folder above the
        world that holds ``path`` is that tree's root."""
        for root in Path(self.world).parents:
            candidate = root / path
            if candidate.is_file():
                return candidate
        return None

    def url(self, url: str) -> ProtoSource:
        """A PROTO file at a URL, through the cache."""
        was_cached = _cached_path(url).is_file()
        path = fetch_url(url)
        (self.cache_hits if was_cached else self.downloads).append(url)
        return ProtoSource(_read(path), url)

    def project_proto(self, name: str) -> ProtoSource | None:
        """The PROTO of that name in the project's ``protos/`` folder, or None."""
        if self._project_protos is None:
            self._project_protos = _index(Path(self.project) / "protos")
        found = self._project_protos.get(name)
        return None if found is None else ProtoSource(_read(Path(found)), found)

    def undeclared(self, name: str) -> ProtoSource | None:
        """A PROTO no ``EXTERNPROTO`` names: the project's ``protos/`` folder, then
        ``$WEBOTS_HOME/projects``."""
        own = self.project_proto(name)
        if own is not None:
            return own
        home = os.environ.get("WEBOTS_HOME")
        if home and self._webots_protos is None:
            self._webots_protos = _index(Path(home) / "projects")
        found = (self._webots_protos or {}).get(name)
        if found is None:
            return None
        return ProtoSource(_read(Path(found)), found)


def _index(root: Path, limit: int = 20_000) -> dict[str, str]:
    """Every ``Name.proto`` under a folder, by name (the first found, in sorted order)."""
    found: dict[str, str] = {}
    if not root.is_dir():
        return found
    seen = 0
    for folder, directories, files in os.walk(root):
        directories.sort()
        for file in sorted(files):
            seen += 1
            if file.endswith(".proto"):
                found.setdefault(file[: -len(".proto")], os.path.join(folder, file))
        if seen > limit:
            break
    return found
