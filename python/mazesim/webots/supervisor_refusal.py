"""Webots' refusal of the supervisor functions to a robot whose ``supervisor`` field is FALSE.

A controller may make a ``Supervisor`` whatever its robot's node says; in Webots the supervisor
functions then do nothing but print Webots' two error lines, each naming the C function, and
answer as libController does without a supervisor: no node (``getFromDef`` and the other
look-ups give None; ``getRoot`` and ``getSelf`` a node that refers to nothing, whose positions and
orientations are NaN and whose fields are None), no effect (a reset, a quit, a label). Only a
robot node of the world file that Webots' own types make a plain robot (``Robot``, the E-puck
PROTOs, ``DifferentialWheels``) with its ``supervisor`` field left FALSE is refused
(:attr:`~mazesim.webots.scene.Scene.supervisor_refused`); a robot of a mazesim world, or of a
project's own robot PROTO, keeps the supervisor's powers its controller asks for.
"""

from __future__ import annotations

import math
from typing import Any, Callable

from mazesim.webots.devices import _print_error

#: How many NaNs a refused node's vector getters give (libController's ``invalid_vector``).
_NAN_SIZES = {
    "getPosition": 3,
    "getOrientation": 9,
    "getPose": 16,
    "getCenterOfMass": 3,
    "getVelocity": 6,
}
#: A refused node's getters of text: libController's empty string.
_TEXTS = ("getDef", "getTypeName", "getBaseTypeName", "exportString")
#: The supervisor's look-ups that give a node which refers to nothing (Webots' Python
#: ``Node()`` and ``Node(tag=0)``), not None.
_EMPTY_NODES = ("getRoot", "getSelf")


def _refused(c_name: str) -> None:
    """Prints Webots' two lines for a supervisor function a plain robot called."""
    _print_error(f"Error: ignoring illegal call to {c_name}() in a 'Robot' controller.")
    _print_error("Error: this function can only be used in a 'Supervisor' controller.")


def _c_names(target: str) -> dict[str, str]:
    """The C name of each Python method of ``target`` (``"supervisor"`` or ``"node"``), from
    the table the C controllers are served by."""
    from mazesim.webots.native_calls import FUNCTIONS

    return {f.method: name for name, f in FUNCTIONS.items() if f.target == target}


def _node_answer(method: str) -> Any:
    if method in _NAN_SIZES:
        return [math.nan] * _NAN_SIZES[method]
    if method in _TEXTS:
        return ""
    return None


class _EmptyNode:
    """A node that refers to nothing: each of its methods prints Webots' refusal and answers
    as libController does without a supervisor."""

    def __init__(self) -> None:
        self._c_names = _c_names("node")

    def __getattr__(self, method: str) -> Callable[..., Any]:
        if method.startswith("_"):
            raise AttributeError(method)
        c_name = self._c_names.get(method, f"wb_supervisor_node_{method}")

        def refused(*args: Any, **kwargs: Any) -> Any:
            _refused(c_name)
            return _node_answer(method)

        return refused


def _supervisor_answer(method: str) -> Any:
    if method in _EMPTY_NODES:
        return _EmptyNode()
    if method in ("worldSave", "movieIsReady", "movieFailed", "virtualRealityHeadsetIsUsed"):
        return False
    if method == "simulationGetMode":
        return 0
    return None


def _refuse_supervisor(robot: Any) -> None:
    """Makes each supervisor function of ``robot`` (a ``Supervisor``) print Webots' refusal and
    answer as libController does for a robot whose ``supervisor`` field is FALSE."""
    for method, c_name in _c_names("supervisor").items():

        def refused(*args: Any, _method: str = method, _c: str = c_name, **kwargs: Any) -> Any:
            _refused(_c)
            return _supervisor_answer(_method)

        setattr(robot, method, refused)


def _refusal_of(c_name: str) -> None:
    """Prints Webots' refusal of the C function ``c_name`` to a plain robot (for a compiled
    controller's call)."""
    _refused(c_name)
