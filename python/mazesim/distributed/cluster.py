"""Connecting to Ray: an existing cluster by its address, or a local instance started for one run.

Ray is optional (``pip install "mazesim[ray]"``); it is imported only here, when a sweep or an
evaluation asks for it, so ``import mazesim`` and ``mazesim --help`` never need it.

Without an address (or with ``"local"``), :func:`ray_session` starts a local Ray instance with one
CPU per core of this machine, no dashboard, listening on 127.0.0.1 only, and its session files in a
fresh temporary folder that is removed when the session ends. With an address (``"auto"``,
``"HOST:6379"`` or ``"ray://HOST:10001"``) it joins that cluster, whose machines must have the same
mazesim installed. When Ray is already initialised in this process (a notebook, a test), the
session uses it and leaves it running.
"""

from __future__ import annotations

import contextlib
import logging
import os
import shutil
import socket
import tempfile
from collections.abc import Iterator
from types import ModuleType

from mazesim.errors import (
    ClusterConnectionError,
    InvalidArgumentError,
    MissingDependencyError,
    _shown,
)

__all__ = ["LOCAL", "connection_advice", "import_ray", "local_cpus", "ray_session"]

#: The address that asks for a local Ray instance, as no address does.
LOCAL = "local"
#: Ray's switch for token authentication: ``token`` turns it on for this process.
AUTH_MODE_VARIABLE = "RAY_AUTH_MODE"
#: Where Ray looks for the token, in this order: the token itself, a file, the default file.
TOKEN_VARIABLE = "RAY_AUTH_TOKEN"
TOKEN_PATH_VARIABLE = "RAY_AUTH_TOKEN_PATH"
DEFAULT_TOKEN_FILE = "~/.ray/auth_token"


def import_ray() -> ModuleType:
    """Imports Ray.

    Raises:
        MissingDependencyError: Ray is not installed.
    """
    try:
        import ray
    except ImportError:
        raise MissingDependencyError(
            "running on Ray needs the 'ray' package: pip install 'mazesim[ray]'"
        ) from None
    return ray


def local_cpus() -> int:
    """The cores this process may run on."""
    if hasattr(os, "sched_getaffinity"):
        return max(1, len(os.sched_getaffinity(0)))
    return max(1, os.cpu_count() or 1)


@contextlib.contextmanager
def _on_loopback(ray: ModuleType) -> Iterator[None]:
    """Makes a local instance started in the block listen on 127.0.0.1 only.

    Ray gives a node the address other machines would reach it by, even for an instance that
    only this machine uses; its own switch for single-machine platforms keeps it on the loopback
    interface. Where a Ray version lacks the switch, Ray's default address is used.
    """
    constants = getattr(getattr(ray, "_private", None), "ray_constants", None)
    if constants is None or not hasattr(constants, "ENABLE_RAY_CLUSTER"):
        yield
        return
    saved = constants.ENABLE_RAY_CLUSTER
    constants.ENABLE_RAY_CLUSTER = False
    try:
        yield
    finally:
        constants.ENABLE_RAY_CLUSTER = saved


def connection_advice(address: str, error: BaseException) -> str:
    """What to check or set after joining the Ray cluster at ``address`` failed with ``error``.

    Ray 2.5x turns on token authentication for a cluster that ``ray start --head`` starts when
    ``RAY_AUTH_MODE=token`` is set or a token already exists (``~/.ray/auth_token``, left by any
    earlier local instance); a driver that joins by address sends its token only when
    ``RAY_AUTH_MODE=token`` is set, and otherwise gets a bare "Failed to connect".
    """
    mode = os.environ.get(AUTH_MODE_VARIABLE)
    token_sources = (
        f"{TOKEN_VARIABLE}, the file named by {TOKEN_PATH_VARIABLE}, or {DEFAULT_TOKEN_FILE} "
        f"(print it with 'ray get-auth-token' on the head node)"
    )
    if mode is None or mode.lower() != "token":
        found = "unset" if mode is None else repr(mode)
        auth = (
            f"if the cluster uses token authentication (Ray's default for 'ray start --head' "
            f"when a token exists), set {AUTH_MODE_VARIABLE}=token here too (it is {found}) and "
            f"give the cluster's token in {token_sources}"
        )
    else:
        auth = (
            f"{AUTH_MODE_VARIABLE}=token is set: check that this machine has the cluster's token "
            f"in {token_sources}"
        )
    first_line = str(error).strip().splitlines()[0] if str(error).strip() else type(error).__name__
    return (
        f"could not join the Ray cluster at {address} ({first_line}); expected a cluster started "
        f"with 'ray start --head' listening there, with the same Ray version; {auth}"
    )


#: How long a cluster's address is given to accept a connection before Ray is asked to join it
#: (Ray itself retries a silent address for over a minute, printing its own log lines).
ANSWER_SECONDS = 5.0


def _answering(address: str) -> None:
    """Refuses, before Ray is asked to join it, an address that is no HOST:PORT (with
    ``ray://`` or not; ``auto`` is Ray's to find) or where nothing accepts a connection within
    :data:`ANSWER_SECONDS`.

    Raises:
        InvalidArgumentError: No host and port 1 to 65535.
        ClusterConnectionError: Nothing answers there.
    """
    if address == "auto":
        return
    where = address.removeprefix("ray://")
    host, _, port_text = where.rpartition(":")
    port = int(port_text) if port_text.isdigit() else 0
    if not host or not 1 <= port <= 65535:
        raise InvalidArgumentError(
            f"expected a Ray address ('local', 'auto', HOST:6379 or ray://HOST:10001, a port "
            f"from 1 to 65535), found {_shown(address)}"
        )
    try:
        with socket.create_connection((host.strip("[]"), port), timeout=ANSWER_SECONDS):
            pass
    except OSError as error:
        reason = error.strerror or type(error).__name__
        raise ClusterConnectionError(
            f"could not join the Ray cluster at {address}: nothing answers there within "
            f"{ANSWER_SECONDS:g} s ({reason}); expected a cluster started with 'ray start "
            "--head' listening there"
        ) from None


@contextlib.contextmanager
def ray_session(address: str | None = None, cpus: int | None = None) -> Iterator[ModuleType]:
    """Connects to Ray for the duration of a ``with`` block.

    Args:
        address: The cluster to join; ``None`` or ``"local"`` starts a local instance on this
            machine.
        cpus: CPUs of a local instance (by default :func:`local_cpus`); ignored with an address.

    Yields:
        The ``ray`` module, initialised.

    Raises:
        MissingDependencyError: Ray is not installed.
        InvalidArgumentError: ``address`` is not a Ray address.
        ClusterConnectionError: The cluster at ``address`` cannot be joined; the message says what
            to check and set (:func:`connection_advice`).
    """
    ray = import_ray()
    if ray.is_initialized():
        yield ray
        return
    temporary = None
    if address is None or address == LOCAL:
        temporary = tempfile.mkdtemp(prefix="mazesim-ray-")
        with _on_loopback(ray):
            ray.init(
                num_cpus=cpus or local_cpus(),
                include_dashboard=False,
                _temp_dir=temporary,
                # Ray's notices about the instance it starts (its token, its ports) are no news.
                logging_level=logging.ERROR,
                log_to_driver=False,
            )
    else:
        _answering(address)
        try:
            ray.init(address=address, logging_level=logging.WARNING, log_to_driver=False)
        except ValueError as error:
            raise InvalidArgumentError(
                f"expected a Ray address ('local', 'auto', HOST:6379 or ray://HOST:10001), "
                f"found {_shown(address)}: {error}"
            ) from None
        except (ConnectionError, RuntimeError, ray.exceptions.RayError) as error:
            # A missing or wrong token raises Ray's AuthenticationError, a RayError.
            raise ClusterConnectionError(connection_advice(address, error)) from error
    try:
        yield ray
    finally:
        ray.shutdown()
        if temporary is not None:
            shutil.rmtree(temporary, ignore_errors=True)
