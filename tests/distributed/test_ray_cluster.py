"""The cluster recipe of docs/ray.md, end to end on loopback: a head started with ``ray start
--head`` and token authentication, then ``mazesim eval`` and ``mazesim sweep`` with ``--address``.

The head runs with ``--block`` in its own session with a tag in its environment, and is stopped
by its process id (``ray stop``, as in the recipe, would stop every Ray instance of the machine's
user). Its token lives in a temporary ``HOME``, so the user's ``~/.ray`` is never touched.
"""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import uuid
from collections.abc import Iterator
from pathlib import Path

import pytest

from mazesim.distributed.cluster import connection_advice
from mazesim.errors import ClusterConnectionError
from mazesim.ros.local_master import free_loopback_port
from mazesim_process import mazesim_command
from ros_support import processes_with

pytest.importorskip("ray", reason="Ray is optional: pip install 'mazesim[ray]'")

REPO = Path(__file__).resolve().parents[2]
BIN = Path(sys.executable).parent
TAG_VARIABLE = "MAZESIM_TEST_RAY_HEAD"
#: A sweep small enough to check a cluster: two runs of a few hundred env-steps.
TINY_SWEEP = """\
[sweep]
name = "cluster-check"

[grid]
seed = [0, 1]
trainer = "flat-q"
world = "seed-maze"
envs = 4
steps = 50
episode_steps = 50
eval_episodes = 2
"""


def test_connection_advice_names_what_to_set(monkeypatch: pytest.MonkeyPatch) -> None:
    failure = ConnectionError("Failed to connect to Ray cluster at 10.0.0.5:6379")
    monkeypatch.delenv("RAY_AUTH_MODE", raising=False)
    advice = connection_advice("10.0.0.5:6379", failure)
    assert "at 10.0.0.5:6379 (Failed to connect to Ray cluster at 10.0.0.5:6379)" in advice
    assert "set RAY_AUTH_MODE=token here too (it is unset)" in advice
    assert "RAY_AUTH_TOKEN" in advice and "~/.ray/auth_token" in advice
    assert "ray get-auth-token" in advice
    monkeypatch.setenv("RAY_AUTH_MODE", "token")
    advice = connection_advice("10.0.0.5:6379", failure)
    assert "RAY_AUTH_MODE=token is set: check that this machine has the cluster's token" in advice
    assert issubclass(ClusterConnectionError, ConnectionError)


def _gone(tag: str, ceiling_s: float) -> bool:
    """Waits until no process carries the tag (True), or ``ceiling_s`` has passed (False)."""
    deadline = time.monotonic() + ceiling_s
    while processes_with(TAG_VARIABLE, tag):
        if time.monotonic() > deadline:
            return False
        time.sleep(0.2)
    return True


def _stop(head: subprocess.Popen[bytes], tag: str) -> None:
    """Stops the head (SIGTERM: ``--block`` then stops its node's processes), then whatever
    carries the tag, by process id, and waits until they are gone (the waits are ceilings for a
    hang: each ends as soon as the processes have)."""
    if head.poll() is None:
        head.send_signal(signal.SIGTERM)
        try:
            head.wait(timeout=120)
        except subprocess.TimeoutExpired:
            head.kill()
            head.wait()
    if _gone(tag, 120.0):
        return
    for pid in processes_with(TAG_VARIABLE, tag):
        try:
            os.kill(pid, signal.SIGKILL)
        except ProcessLookupError:
            pass  # it ended meanwhile
    _gone(tag, 120.0)


@pytest.fixture
def cluster(tmp_path: Path) -> Iterator[tuple[str, dict[str, str]]]:
    """A Ray head with token authentication on 127.0.0.1: its address and the driver's
    environment (with ``RAY_AUTH_MODE=token``)."""
    home = tmp_path / "home"
    home.mkdir()
    tag = uuid.uuid4().hex
    env = dict(os.environ, HOME=str(home), RAY_AUTH_MODE="token", **{TAG_VARIABLE: tag})
    env["PATH"] = f"{BIN}{os.pathsep}{env.get('PATH', '')}"
    generate = subprocess.run(
        ["ray", "get-auth-token", "--generate"],
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert generate.returncode == 0, generate.stderr
    assert (home / ".ray" / "auth_token").is_file()
    port = free_loopback_port()
    # Ray's session folder holds Unix sockets, whose paths may not exceed 107 bytes.
    session_root = tempfile.mkdtemp(prefix="mazesim-ray-", dir="/tmp")
    with open(tmp_path / "ray-head.log", "wb") as log:
        head = subprocess.Popen(
            [
                *("ray", "start", "--head", "--node-ip-address", "127.0.0.1"),
                *("--port", str(port), "--num-cpus", "2", "--include-dashboard=false"),
                *("--disable-usage-stats", "--temp-dir", session_root, "--block"),
            ],
            env=env,
            stdout=log,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
    try:
        deadline = time.monotonic() + 120.0
        while b"Ray runtime started" not in (tmp_path / "ray-head.log").read_bytes():
            assert head.poll() is None, (tmp_path / "ray-head.log").read_text()
            assert time.monotonic() < deadline, "the Ray head did not start in 120 s"
            time.sleep(0.2)
        yield f"127.0.0.1:{port}", env
    finally:
        _stop(head, tag)
        shutil.rmtree(session_root, ignore_errors=True)
    assert processes_with(TAG_VARIABLE, tag) == []


def test_documented_cluster_recipe_on_loopback(
    cluster: tuple[str, dict[str, str]], tmp_path: Path
) -> None:
    address, env = cluster
    # Without RAY_AUTH_MODE=token the driver sends no token: mazesim says what to set.
    # (Ray's connection window shortened from about 20 s to 2.)
    no_token = {key: value for key, value in env.items() if key != "RAY_AUTH_MODE"}
    no_token["RAY_gcs_server_port_wait_time_s"] = "2"
    refused = mazesim_command(
        "eval", "--episodes", "2", "--address", address, cwd=tmp_path, env=no_token
    )
    assert refused.returncode == 2
    error = refused.stderr.strip().splitlines()[-1]
    assert error.startswith(f"mazesim: error: could not join the Ray cluster at {address}")
    assert "set RAY_AUTH_MODE=token here too (it is unset)" in error

    # With it, as the recipe says, eval and sweep run on the cluster.
    evaluation = mazesim_command(
        "eval",
        "--episodes",
        "4",
        "--max-steps",
        "50",
        "--json",
        "--address",
        address,
        cwd=tmp_path,
        env=env,
    )
    assert evaluation.returncode == 0, evaluation.stderr
    assert '"episodes": 4' in evaluation.stdout
    alone = mazesim_command(
        "eval", "--episodes", "4", "--max-steps", "50", "--json", cwd=tmp_path, env=env
    )
    assert alone.returncode == 0, alone.stderr
    assert evaluation.stdout == alone.stdout  # the same episodes wherever they run

    (tmp_path / "tiny.toml").write_text(TINY_SWEEP)
    sweep = mazesim_command(
        "sweep", "tiny.toml", "--address", address, "--out", "sw", cwd=tmp_path, env=env
    )
    assert sweep.returncode == 0, sweep.stderr
    assert f"2 runs on Ray ({address})" in sweep.stdout
    assert (tmp_path / "sw" / "results.json").is_file()
    assert len(list((tmp_path / "sw" / "runs").iterdir())) == 2


def test_recipe_is_the_one_documented() -> None:
    text = (REPO / "docs" / "ray.md").read_text()
    for line in (
        "export RAY_AUTH_MODE=token",
        "ray get-auth-token --generate",
        "ray start --head --node-ip-address 127.0.0.1 --port 6390",
        "mazesim eval --episodes 20 --address 127.0.0.1:6390",
        "mazesim sweep examples/sweep.toml --address 127.0.0.1:6390",
        "ray stop",
    ):
        assert line in text, line
