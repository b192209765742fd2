"""ROS 2's ``--ros-args`` section of a node's command line, as a launch file passes it.

A launch file starts every node with its namespace, name, remappings and parameters after
``--ros-args`` (``launch_ros``'s ``Node(namespace='robot', remappings=[('scan', 'base_scan')],
parameters=[{'use_sim_time': True}])`` appends ``--ros-args -r __ns:=/robot --params-file FILE
-r scan:=base_scan``), and so does ``ros2 run``. The rules are ROS 2's (the "Remapping Names"
design article and ``rcl``'s argument parser): ``-r``/``--remap FROM:=TO`` renames a topic, a
relative name resolved against the node's namespace, ``NODE:FROM:=TO`` for the node ``NODE``
only; ``__ns:=`` and ``__node:=`` (or ``__name:=``) set the namespace and the node's name;
``-p``/``--param NAME:=VALUE`` and ``--params-file FILE`` set parameters; ``--log-level`` and the
``--enable-*``/``--disable-*`` logging flags; the section ends at ``--`` or the end.

mazesim's nodes take no ROS parameters (their settings are their options; the bridge shows its
own read-only, :mod:`mazesim.ros2.parameters`), except ``use_sim_time``, which every node takes
and which changes nothing here: the bridge is the clock. Any other parameter is refused, saying
which option to use, rather than dropped.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from pathlib import Path
from typing import NamedTuple

from mazesim.errors import InvalidArgumentError, RegisteredName, _known_name, _shown

__all__ = ["RosArguments", "split_ros_arguments"]

#: The parameters mazesim's nodes take: every ROS 2 node has ``use_sim_time``.
ACCEPTED_PARAMETERS = ("use_sim_time",)
_LOGGING_FLAG = re.compile(r"--(enable|disable)-(rosout|stdout|external-lib)-logs")
_NAME = re.compile(r"~?/?[A-Za-z_][A-Za-z0-9_]*(/[A-Za-z_][A-Za-z0-9_]*)*")


class RosArguments(NamedTuple):
    """What a ``--ros-args`` section says (empty when there is none)."""

    #: The node's namespace (``/robot``), ``""`` when not given.
    namespace: str = ""
    #: The node's name, ``""`` when not given.
    node_name: str = ""
    #: Remapping rules in order: (node the rule is for or ``""``, from, to), names as written.
    remappings: tuple[tuple[str, str, str], ...] = ()

    def remap(self, topic: str, node_name: str, namespace: str) -> str:
        """The name of ``topic`` (absolute, as the node makes it) after the first rule that
        matches it, ROS 2's way: a rule's relative names resolve against ``namespace``."""
        for node, source, target in self.remappings:
            if node and node != node_name:
                continue
            if _resolve(source, namespace, node_name) == topic:
                return _resolve(target, namespace, node_name)
        return topic


def _resolve(name: str, namespace: str, node_name: str) -> str:
    if name.startswith("/"):
        return name
    base = namespace.rstrip("/")
    if name.startswith("~"):
        return f"{base}/{node_name}{name[1:]}"
    return f"{base}/{name}"


def _rule(text: str, flag: str) -> tuple[str, str, str]:
    source, sep, target = text.partition(":=")
    node, colon, source_name = source.rpartition(":")
    if not sep or not source_name or not target:
        raise InvalidArgumentError(
            f"expected a remapping FROM:=TO (or NODE:FROM:=TO) after {flag} in --ros-args; "
            f"found {_shown(text)}"
        )
    return (node if colon else "", source_name, target)


def _parameters_in_file(path: str) -> list[str]:
    """The parameter names under ``ros__parameters:`` of a ROS 2 parameters file."""
    try:
        lines = Path(path).read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError) as e:
        raise InvalidArgumentError(
            f"expected a readable ROS 2 parameters file after --params-file; found {_shown(path)} "
            f"({e.__class__.__name__})"
        ) from None
    names: list[str] = []
    indent: int | None = None
    for line in lines:
        stripped = line.split("#", 1)[0].rstrip()
        if not stripped.strip():
            continue
        depth = len(stripped) - len(stripped.lstrip())
        if stripped.strip() == "ros__parameters:":
            indent = depth
        elif indent is not None and depth > indent and ":" in stripped:
            names.append(stripped.strip().split(":", 1)[0].strip())
        elif indent is not None and depth <= indent:
            indent = None
    return names


def _check_parameter(name: RegisteredName, where: str) -> None:
    option = "--" + str(name).replace("_", "-")
    _known_name(
        name,
        f"a ROS parameter ({where})",
        tuple(ACCEPTED_PARAMETERS),
        ": mazesim's ROS 2 nodes have no other, their settings are their options "
        f"(perhaps {option})",
    )


def split_ros_arguments(arguments: Sequence[str]) -> tuple[list[str], RosArguments]:
    """``arguments`` without their ``--ros-args`` sections, and what those sections say.

    Raises:
        InvalidArgumentError: a section holds something that is not a ROS argument, a
            malformed remapping, or a parameter mazesim's nodes do not have.
    """
    rest: list[str] = []
    namespace = node_name = ""
    rules: list[tuple[str, str, str]] = []
    items = list(arguments)
    i = 0
    inside = False
    while i < len(items):
        item = items[i]
        if not inside:
            if item == "--ros-args":
                inside = True
            else:
                rest.append(item)
            i += 1
            continue
        if item == "--":
            inside = False
            i += 1
            continue
        if item == "--ros-args":
            i += 1
            continue
        if _LOGGING_FLAG.fullmatch(item):
            i += 1
            continue
        if item in ("-r", "--remap", "-p", "--param", "--params-file", "--log-level", "-e",
                    "--enclave"):  # fmt: skip
            if i + 1 >= len(items):
                raise InvalidArgumentError(
                    f"expected a value after {item} in --ros-args; found the end of the line"
                )
            value = items[i + 1]
            if item in ("-r", "--remap"):
                node, source, target = _rule(value, item)
                if source in ("__ns", "__node", "__name"):
                    if source == "__ns":
                        namespace = "/" + target.strip("/")
                    else:
                        node_name = target
                elif not (_NAME.fullmatch(source) and _NAME.fullmatch(target)):
                    raise InvalidArgumentError(
                        f"expected ROS topic names in the remapping after {item}; found "
                        f"{_shown(value)}"
                    )
                else:
                    rules.append((node, source, target))
            elif item in ("-p", "--param"):
                name, sep, _ = value.partition(":=")
                if not sep:
                    raise InvalidArgumentError(
                        f"expected NAME:=VALUE after {item} in --ros-args; found {_shown(value)}"
                    )
                _check_parameter(name.rpartition(":")[2], f"{item} {value}")
            elif item == "--params-file":
                for name in _parameters_in_file(value):
                    _check_parameter(name, f"in {value}")
            i += 2
            continue
        raise InvalidArgumentError(
            "expected ROS 2 arguments after --ros-args (-r FROM:=TO, -r __ns:=/NAMESPACE, "
            "-r __node:=NAME, -p use_sim_time:=true, --params-file FILE, --log-level LEVEL, "
            f"ending at --); found {_shown(item)}"
        )
    return rest, RosArguments(namespace, node_name, tuple(rules))
