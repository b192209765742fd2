"""What each topic of the bridge carries, as plain Python (this module does not need ROS).

Published by the bridge (``std_msgs/Float64MultiArray`` unless said otherwise; names are relative
to the bridge's namespace, except ``/clock``):

- ``sensors``: every distance sensor, then every ground sensor, in the robot profile's order and in
  the sensors' own units (the report's Listing 3.1). For the e-puck that is 11 values, ``ps0`` ..
  ``ps7`` (raw counts, 0-4095) then ``gs0`` .. ``gs2`` (raw, about 300 on black and 856 on white);
  for the ``seed`` robot 7 values, the six Sharp sensors in volts (front, back, left, right,
  left-front, right-front) then the centre ground sensor ``gs``. The layout's single dimension is
  labelled with the sensor names.
- ``sensor_data`` (robots with Sharp sensors, such as ``seed`` and ``alphabot2``; not advertised
  for the e-puck): the six Sharp distances in cm (volts converted with
  :func:`mazesim.sharp_volts_to_cm`, 3-40 cm) then the current checkpoint: the signed id of the
  barcode crossed in the last control step (positive on arrival, negative on departure), 0 if none
  (the report's Alg. 6).
- ``pose``: ``[x, y, yaw, time]``: metres, radians and simulated seconds after the step.
- ``/clock`` (``rosgraph_msgs/Clock``): the simulated time.

Subscribed by the bridge:

- ``motor`` (``std_msgs/Float64MultiArray``): ``[left, right]`` wheel speeds in rad/s (the report's
  Listing 3.2), clamped to the motor limit.
- ``action`` (``std_msgs/String``): one of the report's primitive action codes (``00`` forward,
  ``11``-``44`` turn right, ``55``-``88`` turn left, ``aa``/``bb`` spin right/left, ``99`` back),
  turned into wheel speeds by :func:`mazesim.actions.wheel_speeds` with the robot's motor limit
  (on the e-puck, ``00`` is 3.14 rad/s on both wheels).

A command that is not exactly two finite numbers, or an unknown action code, is rejected with a
:class:`~mazesim.errors.InvalidActionError`; both bridges (ROS 1 and ROS 2) then log it and take
it as a command keeping the wheel speeds of the last one accepted (:class:`HeldCommand`).

Set by the bridge on the parameter server, relative to its namespace like its topics:

- ``control_step_ms``: the length of one control step in milliseconds (32 for the e-puck and the
  ``seed`` robot), set before the bridge subscribes ``motor`` and ``action``.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Sequence
from typing import Any

from mazesim._core import RobotProfile, Simulator, sharp_volts_to_cm
from mazesim.errors import InvalidActionError, InvalidArgumentError, MazesimError, _shown

__all__ = [
    "ACTION_TOPIC",
    "CLOCK_TOPIC",
    "CONTROL_STEP_PARAM",
    "HeldCommand",
    "MOTOR_TOPIC",
    "POSE_TOPIC",
    "SENSORS_TOPIC",
    "SENSOR_DATA_TOPIC",
    "current_checkpoint",
    "has_sharp_sensors",
    "motor_command",
    "demo_robot",
    "pose_values",
    "sensor_data_values",
    "sensor_names",
    "sensors_values",
]

SENSORS_TOPIC = "sensors"
SENSOR_DATA_TOPIC = "sensor_data"
POSE_TOPIC = "pose"
CLOCK_TOPIC = "/clock"
MOTOR_TOPIC = "motor"
ACTION_TOPIC = "action"
#: The parameter holding the bridge's control step in ms.
CONTROL_STEP_PARAM = "control_step_ms"


def sensor_names(simulator: Simulator) -> list[str]:
    """Names of the values on ``sensors``: the distance sensors, then the ground sensors."""
    robot = simulator.robot
    return [*robot.distance_sensor_names, *robot.ground_sensor_names]


def sensors_values(simulator: Simulator) -> list[float]:
    """The ``sensors`` values: distance sensors then ground sensors, in their own units."""
    return [*simulator.distance_sensors().tolist(), *simulator.ground_sensors().tolist()]


def has_sharp_sensors(simulator: Simulator) -> bool:
    """Whether the robot reads Sharp distance sensors in volts, so ``sensor_data`` is published."""
    return simulator.robot.distance_sensor_unit == "volts"


def current_checkpoint(simulator: Simulator) -> int:
    """The signed id of the barcode crossed in the last control step, 0 if none.

    Reads ``Simulator.last_crossing`` where the core provides it, else 0.
    """
    return int(getattr(simulator, "last_crossing", 0) or 0)


def sensor_data_values(simulator: Simulator) -> list[float]:
    """The ``sensor_data`` values: the Sharp distances in cm, then the current checkpoint."""
    distances = [sharp_volts_to_cm(volts) for volts in simulator.distance_sensors().tolist()]
    return [*distances, float(current_checkpoint(simulator))]


def pose_values(simulator: Simulator) -> list[float]:
    """The ``pose`` values: ``[x, y, yaw, time]``."""
    x, y, yaw = simulator.pose
    return [x, y, yaw, simulator.time]


def motor_command(values: Sequence[Any]) -> tuple[float, float]:
    """Checks a ``motor`` message's data and returns the (left, right) wheel speeds in rad/s.

    Args:
        values: The message's ``data`` field.

    Returns:
        The left and right wheel speeds.

    Raises:
        InvalidActionError: The data is not exactly two finite numbers.
    """
    if len(values) != 2:
        raise InvalidActionError(
            f"expected motor data [left, right] in rad/s (2 values); found {len(values)} values"
        )
    left, right = (float(value) for value in values)
    for side, value in (("left", left), ("right", right)):
        if not math.isfinite(value):
            raise InvalidActionError(
                f"expected a finite {side} wheel speed in rad/s on motor; found {value}"
            )
    return left, right


class HeldCommand:
    """The wheel speeds one robot's commands give, under the rule both bridges share.

    A command the bridge refuses (a speed that is not finite, an unknown action code, data that
    does not decode) is still a command: it keeps the wheel speeds of the last one accepted (at
    first none, the robot standing still), as ROS's diff drive controllers ignore a NaN twist
    while the simulation goes on. In lockstep it therefore takes its step, and a node answering
    each state with one command gets the next state.
    """

    def __init__(self) -> None:
        #: The wheel speeds of the last command accepted (what a refused one keeps).
        self.latest = (0.0, 0.0)
        #: How many commands were refused.
        self.refused = 0

    def take(self, read: Callable[[], tuple[float, float]]) -> tuple[tuple[float, float], str]:
        """Reads one command: returns its wheel speeds and, for a refused one, why ("" if not).

        Args:
            read: Decodes the message and returns its (left, right) wheel speeds in rad/s,
                raising :class:`~mazesim.errors.MazesimError`, ``ValueError`` or ``KeyError``
                when it cannot.
        """
        try:
            self.latest = read()
        except (MazesimError, ValueError, KeyError) as error:
            self.refused += 1
            return self.latest, str(error)
        return self.latest, ""


def demo_robot(controller: str, robot: str | None) -> str:
    """The robot a demo's bridge runs (``mazesim ros demo``, ``mazesim ros2 demo``): ``robot``
    (a built-in profile's name or a profile file's path, as ``--robot`` takes everywhere), else
    ``seed`` for ``hrl`` and ``e-puck`` for ``avoid-collision``; a file's path made absolute, as
    the nodes run in other folders.

    Raises:
        InvalidArgumentError: The profile lacks the sensors the controller node reads: the
            perform-learning node reads six Sharp distances (``sensor_data``), the
            avoid-collision node the e-puck's ps0-ps7 as the first 8 values of ``sensors``.
        MazesimError: No such profile, or a profile file that does not read.
    """
    if robot is None:
        return "seed" if controller == "hrl" else "e-puck"
    profile = RobotProfile.load(robot)
    names = list(profile.distance_sensor_names)
    if controller == "hrl":
        fits = profile.distance_sensor_unit == "volts" and len(names) == 6
        needs = "the six Sharp distance sensors of the seed robot (in volts), read on sensor_data"
    else:
        fits = profile.distance_sensor_unit == "raw" and names[:8] == [f"ps{i}" for i in range(8)]
        needs = "the e-puck's 8 raw proximity sensors ps0-ps7, first on sensors"
    if not fits:
        raise InvalidArgumentError(
            f"the {controller} node needs {needs}; robot {_shown(robot)} ({profile.name}) has "
            f"{', '.join(names)} in {_shown(profile.distance_sensor_unit)}: give such a "
            "profile, or "
            f"leave --robot out ({'seed' if controller == 'hrl' else 'e-puck'})"
        )
    return os.path.abspath(robot) if os.path.exists(robot) else robot
