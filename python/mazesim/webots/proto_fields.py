"""The fields the PROTOs mazesim builds in declare, with their default values: what a Webots
supervisor reads from an instance's field that the world file leaves out.

Webots gives every field a PROTO declares to its instances; a world file writes only those it
changes. mazesim builds these PROTOs in rather than expanding their files (which it may not
have: their ``EXTERNPROTO`` URLs need a download), so their declared fields are written here.

Sources (cyberbotics/webots): ``projects/objects/floors/protos/RectangleArena.proto`` (the
same fields and defaults from R2019b on), ``projects/robots/gctronic/e-puck/protos/
E-puck.proto`` (R2022b on: the default controller is ``e-puck_avoid_obstacles``, the radio
channels 1, the camera 52 x 39 pixels with a 0.84 rad field of view; the E-puck.proto of Webots
V8.5 declares the same default controller and radio channels, so worlds of every version share
them).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from mazesim._core import EPUCK_DEFAULT_CONTROLLER
from mazesim.webots.camera import DEFAULT_FOV, DEFAULT_HEIGHT, DEFAULT_WIDTH
from mazesim.webots.radio_devices import E_PUCK_CHANNEL

__all__ = ["DeclaredFields", "declared_fields"]


@dataclass(frozen=True)
class DeclaredFields:
    """A PROTO's declared fields with their defaults, by kind: numbers (an ``SFFloat``,
    ``SFInt32``, ``SFVec2f``...), strings and flags (``SFBool``)."""

    numbers: dict[str, list[float]] = field(default_factory=dict)
    strings: dict[str, str] = field(default_factory=dict)
    flags: dict[str, bool] = field(default_factory=dict)


_RECTANGLE_ARENA = DeclaredFields(
    numbers={
        "floorSize": [1.0, 1.0],
        "floorTileSize": [0.5, 0.5],
        "wallThickness": [0.01],
        "wallHeight": [0.1],
    },
    strings={"name": "rectangle arena", "contactMaterial": "default"},
)

_E_PUCK = DeclaredFields(
    numbers={
        "emitter_channel": [float(E_PUCK_CHANNEL)],
        "receiver_channel": [float(E_PUCK_CHANNEL)],
        "camera_width": [float(DEFAULT_WIDTH)],
        "camera_height": [float(DEFAULT_HEIGHT)],
        "camera_fieldOfView": [DEFAULT_FOV],
        "distance_sensor_numberOfRays": [1.0],
    },
    strings={
        "name": "e-puck",
        "controller": EPUCK_DEFAULT_CONTROLLER,
        "window": "e-puck",
        "customData": "",
        "version": "1",
    },
    flags={"supervisor": False, "synchronization": True, "kinematic": False},
)

_DECLARED = {"RectangleArena": _RECTANGLE_ARENA, "E-puck": _E_PUCK}


def declared_fields(type_name: str) -> DeclaredFields:
    """The declared fields of a PROTO mazesim builds in (none for another type)."""
    return _DECLARED.get(type_name, DeclaredFields())
