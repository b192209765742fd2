"""A private ROS master on a free loopback port, and the processes started against it.

:class:`LocalMaster` starts ``roscore -p PORT`` on a port the system picks, gives every process it
starts the matching ``ROS_MASTER_URI`` (plus ``ROS_IP=127.0.0.1`` and a private ``ROS_HOME`` for
logs) and, when closed, stops them all: nodes with SIGINT (then SIGTERM, then SIGKILL if they hang),
the master with SIGTERM by its PID. Every process carries a tag in its environment, so what is
left behind, children of children included, can be listed (:meth:`LocalMaster.leftovers`); closing
ends those too and reports them.

It needs the ``roscore`` command but does not import ``rospy``, so one process can hold a master
and still be (at most) one ROS node itself. The ``mazesim ros demo`` command, the ROS benchmark and
the tests use it.
"""

from __future__ import annotations

import os
import random
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import uuid
import xmlrpc.client
from collections.abc import Sequence
from typing import Any

from mazesim._closing import Closing
from mazesim.errors import InvalidArgumentError, MazesimError, MissingDependencyError, _shown

__all__ = ["LocalMaster", "free_loopback_port", "processes_with"]

#: The environment variable whose value tags every process a LocalMaster starts.
TAG_VARIABLE = "MAZESIM_ROS_GRAPH"
#: The caller id this module gives the master's XML-RPC API.
CALLER_ID = "/mazesim_local_master"


def _xmlrpc(uri: str, method: str, *args: object) -> Any:
    """Calls a ROS XML-RPC API method; returns ``[code, message, value]`` as the API defines."""
    with xmlrpc.client.ServerProxy(uri) as proxy:
        return getattr(proxy, method)(CALLER_ID, *args)


def processes_with(variable: str, value: str) -> list[tuple[int, str]]:
    """Running (not zombie) processes whose environment has ``variable=value``: ``(pid, command
    line)`` pairs. Reads ``/proc``; elsewhere it returns an empty list."""
    marker = f"{variable}={value}".encode()
    found: list[tuple[int, str]] = []
    if not os.path.isdir("/proc"):
        return found
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/environ", "rb") as environ:
                if marker not in environ.read().split(b"\0"):
                    continue
            with open(f"/proc/{entry}/stat", "rb") as stat:
                if stat.read().rsplit(b")", 1)[1].split()[0] == b"Z":
                    continue  # a zombie: exited, waiting to be reaped
            with open(f"/proc/{entry}/cmdline", "rb") as cmdline:
                command = cmdline.read().replace(b"\0", b" ").decode(errors="replace")
        except OSError:
            continue
        found.append((int(entry), command.strip()))
    return found


#: Where :func:`free_loopback_port` looks first: below Linux's ephemeral range (32768-60999 by
#: default), so that no outgoing connection is given the port between the pick and its use.
LISTEN_PORTS = (20000, 32768)
#: How long :meth:`LocalMaster.start` waits for roscore and rosout, and
#: :meth:`LocalMaster.wait_for_connections` for nodes to connect, before it gives up: a ceiling
#: that only bounds a hang (each wait ends as soon as what it waits for is there), generous
#: enough for Python nodes starting on a loaded machine.
START_TIMEOUT_S = 120.0
#: Times :meth:`LocalMaster.start` tries another port when roscore finds its own one taken.
PORT_ATTEMPTS = 4


def _ephemeral_start() -> int:
    """The first port of the system's ephemeral range (the ports outgoing connections get)."""
    try:
        with open("/proc/sys/net/ipv4/ip_local_port_range") as ranges:
            return int(ranges.read().split()[0])
    except (OSError, ValueError, IndexError):
        return LISTEN_PORTS[1]


def free_loopback_port() -> int:
    """A TCP port on 127.0.0.1 that no one uses now.

    A port the system picks (binding port 0) lies in its ephemeral range, which it also hands to
    outgoing connections: one of those could take the port before the server that is to listen
    on it binds it. So a free port below that range is preferred, drawn at random; the system's
    pick is the fallback.
    """
    low, high = LISTEN_PORTS[0], min(LISTEN_PORTS[1], _ephemeral_start())
    draw = random.Random(os.urandom(8))
    for _ in range(64 if high > low else 0):
        port = draw.randrange(low, high)
        with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
            try:
                probe.bind(("127.0.0.1", port))
            except OSError:
                continue
            return port
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


class LocalMaster(Closing):
    """``roscore`` on a free loopback port, with the processes started against it.

    Use it as a context manager::

        with LocalMaster() as master:
            bridge = master.spawn("bridge", ["mazesim", "ros", "bridge"])
            ...
        assert not master.leftovers()

    Attributes:
        port: The master's port on 127.0.0.1.
        uri: The master's URI, ``http://127.0.0.1:PORT``.
        home: The folder of the logs (``ROS_HOME``); each spawned process writes ``NAME.log`` here.
        env: The environment of every process started (``ROS_MASTER_URI``, ``ROS_IP``,
            ``ROS_HOME`` and the tag set; this Python's folder first on ``PATH``).
    """

    def __init__(self, home: str | None = None) -> None:
        """Prepares the master; :meth:`start` (or ``with``) starts it.

        Args:
            home: The folder for logs; by default a new temporary folder, kept for its logs.
        """
        self.port = free_loopback_port()
        self.uri = f"http://127.0.0.1:{self.port}"
        self.tag = uuid.uuid4().hex
        self.home = home if home is not None else tempfile.mkdtemp(prefix="mazesim-ros-")
        os.makedirs(self.home, exist_ok=True)
        env = dict(os.environ)
        env.pop("ROS_HOSTNAME", None)
        python_folder = os.path.dirname(sys.executable)
        env.update(
            {
                "ROS_MASTER_URI": self.uri,
                "ROS_IP": "127.0.0.1",
                "ROS_HOME": self.home,
                "ROS_LOG_DIR": os.path.join(self.home, "log"),
                "PATH": python_folder + os.pathsep + env.get("PATH", ""),
                "PYTHONUNBUFFERED": "1",
                TAG_VARIABLE: self.tag,
            }
        )
        self.env = env
        self.roscore: subprocess.Popen[bytes] | None = None
        self.processes: list[tuple[str, subprocess.Popen[bytes]]] = []

    def __enter__(self) -> LocalMaster:
        self.start()
        return self

    def log_path(self, name: str) -> str:
        """The file that receives the standard output and error of the process ``name``, in
        :attr:`home`.

        Raises:
            InvalidArgumentError: ``name`` is no plain file name (``../x`` made or emptied a
                log file outside the master's home).
        """
        plain = (
            isinstance(name, str)
            and 0 < len(name) <= 200
            and name not in (".", "..")
            and not any(c in name for c in "/\\\x00")
        )
        if not plain:
            raise InvalidArgumentError(
                "expected a process name that is a plain file name (no '/', '\\', '..' or "
                f"NUL, at most 200 characters), found {_shown(name)}"
            )
        return os.path.join(self.home, f"{name}.log")

    def start(self, timeout: float = START_TIMEOUT_S) -> None:
        """Starts ``roscore -p PORT`` and waits until the master answers.

        Raises:
            MissingDependencyError: There is no ``roscore`` command.
            MazesimError: The master (and its rosout node) did not start within ``timeout`` seconds.
        """
        if shutil.which("roscore", path=self.env["PATH"]) is None:
            raise MissingDependencyError(
                "no 'roscore' command: install ROS 1 (on Debian, 'make ros-deps' or "
                "'apt-get install python3-roslaunch rosout')"
            )
        for attempt in range(PORT_ATTEMPTS):
            if attempt:
                self._move_to(free_loopback_port())
            if self._start_roscore(timeout):
                return
        raise MazesimError(
            f"roscore found its port taken {PORT_ATTEMPTS} times (the last {self.port}); "
            f"see {self.log_path('roscore')}"
        )

    def _move_to(self, port: int) -> None:
        """Gives the master (not started yet) another port."""
        self.port = port
        self.uri = f"http://127.0.0.1:{port}"
        self.env["ROS_MASTER_URI"] = self.uri

    def _start_roscore(self, timeout: float) -> bool:
        """Starts roscore on :attr:`port`; False when it stopped because the port was taken."""
        with open(self.log_path("roscore"), "wb") as log:
            self.roscore = subprocess.Popen(
                ["roscore", "-p", str(self.port)],
                env=self.env,
                stdin=subprocess.DEVNULL,
                stdout=log,
                stderr=subprocess.STDOUT,
                start_new_session=True,
            )
        deadline = time.monotonic() + timeout
        # Ready once rosout, the last thing roscore starts, listens: a roscore stopped before
        # that waits 10 s for a master it has already stopped.
        while not (self.is_online() and self._rosout_listens()):
            if self.roscore.poll() is not None or time.monotonic() > deadline:
                self.close()
                if self._port_was_taken():
                    return False
                raise MazesimError(
                    f"roscore did not start on port {self.port} within {timeout:g} s; "
                    f"see {self.log_path('roscore')}"
                )
            time.sleep(0.05)
        return True

    def _port_was_taken(self) -> bool:
        try:
            with open(self.log_path("roscore"), "rb") as log:
                return b"Address already in use" in log.read()
        except OSError:
            return False

    def is_online(self) -> bool:
        """Whether the master answers on its port."""
        try:
            with socket.create_connection(("127.0.0.1", self.port), timeout=0.5):
                pass
            code, _, _ = _xmlrpc(self.uri, "getPid")
        except (OSError, xmlrpc.client.Error):
            return False
        return bool(code == 1)

    def _rosout_listens(self) -> bool:
        try:
            _, subscribers, _ = self.system_state()
        except (OSError, xmlrpc.client.Error, MazesimError):
            return False
        return any(topic == "/rosout" and nodes for topic, nodes in subscribers)

    def set_param(self, name: str, value: object) -> None:
        """Sets a parameter on the master (an absolute name such as ``/use_sim_time``)."""
        code, message, _ = _xmlrpc(self.uri, "setParam", name, value)
        if code != 1:
            raise MazesimError(f"the ROS master at {self.uri} refused to set {name}: {message}")

    def system_state(self) -> tuple[Any, Any, Any]:
        """The master's publishers, subscribers and services: ``[[topic, [node, ...]], ...]``."""
        code, message, state = _xmlrpc(self.uri, "getSystemState")
        if code != 1:
            raise MazesimError(f"the ROS master at {self.uri} refused getSystemState: {message}")
        publishers, subscribers, services = state
        return publishers, subscribers, services

    def connections(self, node: str) -> list[tuple[str, str, str]]:
        """A node's open connections as ``(topic, peer node, direction)``; direction ``"o"`` is
        outbound (the node publishes to the peer), ``"i"`` inbound. Empty if the node is unknown.
        """
        code, _, uri = _xmlrpc(self.uri, "lookupNode", node)
        if code != 1:
            return []
        try:
            code, _, info = _xmlrpc(uri, "getBusInfo")
        except (OSError, xmlrpc.client.Error):
            return []
        if code != 1:
            return []
        return [(str(row[4]), str(row[1]), str(row[2])) for row in info]

    def wait_for_connections(
        self,
        publisher: str,
        topics: Sequence[str],
        subscriber: str,
        timeout: float = START_TIMEOUT_S,
    ) -> None:
        """Waits until node ``publisher`` is connected to node ``subscriber`` on every topic."""
        deadline = time.monotonic() + timeout
        wanted = set(topics)
        while True:
            connected = {
                topic
                for topic, peer, direction in self.connections(publisher)
                if peer == subscriber and direction == "o"
            }
            if wanted <= connected:
                return
            if time.monotonic() > deadline:
                missing = ", ".join(sorted(wanted - connected))
                raise MazesimError(
                    f"{publisher} did not connect to {subscriber} on {missing} "
                    f"within {timeout:g} s; see the logs in {self.home}"
                )
            time.sleep(0.05)

    def spawn(
        self,
        name: str,
        argv: Sequence[str],
        env: dict[str, str] | None = None,
        niceness: int = 0,
    ) -> subprocess.Popen[bytes]:
        """Starts a process against this master; its output goes to :meth:`log_path`.

        Args:
            name: A short name for logs and errors (``"bridge"``).
            argv: The command and its arguments.
            env: Variables to add to :attr:`env` for this process.
            niceness: How much lower than this process's its CPU priority is (``nice -n``; it
                execs the command, so the process is still the command's).
        """
        command = list(argv)
        if niceness and shutil.which("nice") is not None:
            command = ["nice", "-n", str(int(niceness)), *command]
        with open(self.log_path(name), "wb") as log:
            process = subprocess.Popen(
                command,
                env={**self.env, **(env or {})},
                stdin=subprocess.DEVNULL,
                stdout=log,
                stderr=subprocess.STDOUT,
                start_new_session=True,
            )
        self.processes.append((name, process))
        return process

    @staticmethod
    def stop_process(
        process: subprocess.Popen[Any], grace: float = 10.0, interrupted: bool = False
    ) -> int:
        """Stops one process: SIGINT, then SIGTERM and SIGKILL if it does not exit in time.

        Args:
            process: The process.
            grace: Seconds it may take to exit after SIGINT.
            interrupted: It was sent SIGINT already; only wait, then escalate.

        Returns:
            Its exit code.
        """
        steps: list[tuple[signal.Signals | None, float]] = [
            (None if interrupted else signal.SIGINT, grace),
            (signal.SIGTERM, 3.0),
            (signal.SIGKILL, 3.0),
        ]
        for stop_signal, wait in steps:
            if process.poll() is not None:
                break
            if stop_signal is not None:
                process.send_signal(stop_signal)
            try:
                process.wait(timeout=wait)
            except subprocess.TimeoutExpired:
                continue
        return process.wait()

    def close(self) -> list[tuple[int, str]]:
        """Stops the spawned processes, then the master, then anything they left behind.

        Every process gets SIGINT at once (newest first), so they shut down in parallel; one that
        has not exited after its grace time gets SIGTERM, then SIGKILL. The master gets SIGTERM.

        Returns:
            The processes that were still running with this master's tag after that (children
            of children that their parents did not stop) and were then ended: ``(pid, command
            line)`` pairs; empty when everything stopped as it should.
        """
        running = [process for _, process in reversed(self.processes) if process.poll() is None]
        for process in running:
            process.send_signal(signal.SIGINT)
        for process in running:
            self.stop_process(process, interrupted=True)
        self.processes.clear()
        if self.roscore is not None:
            if self.roscore.poll() is None:
                self.roscore.terminate()
                try:
                    self.roscore.wait(timeout=15.0)
                except subprocess.TimeoutExpired:
                    self.roscore.kill()
                    self.roscore.wait()
            self.roscore = None
        left_behind = self.leftovers()
        for stop_signal in (signal.SIGTERM, signal.SIGKILL):
            for pid, _ in self.leftovers():
                try:
                    os.kill(pid, stop_signal)
                except ProcessLookupError:
                    pass
            deadline = time.monotonic() + 3.0
            while self.leftovers() and time.monotonic() < deadline:
                time.sleep(0.05)
        return left_behind

    def leftovers(self) -> list[tuple[int, str]]:
        """Processes still running with this master's tag: ``(pid, command line)`` pairs.

        Reads ``/proc``; elsewhere it returns an empty list.
        """
        return processes_with(TAG_VARIABLE, self.tag)
