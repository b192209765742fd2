"""BotStudio automata (``.bsg``): the e-puck's graphical finite-state machines, run as Webots'
botstudio robot window runs one.

Webots' Robotics curriculum programs the e-puck of its beginner and novice worlds with BotStudio,
a robot window that draws an automaton of states and transitions and runs it on the robot: a
world's robot whose controller folder holds ``NAME.bsg`` has that automaton run from the start of
the run here, as the window runs it once its Run button is pressed (Webots starts nothing until
then). Facts read from Webots' sources (Apache-2.0; no code is kept),
projects/robots/gctronic/e-puck/plugins/robot_windows/botstudio at R2023b: core/Model.cpp,
Automaton.cpp, State.cpp, Transition.cpp, Tokenizer.cpp, e-puck/EPuckFacade.cpp,
EPuckSensorCondition.cpp and EPuckActuatorCommand.cpp.

- The file: the header ``#botstudio 4.0`` (files of the older 3.0 layout are read too: see
  :func:`_read_version_3`), the robot's line ``#e-puck``, then one state or transition a line,
  tokens ending at ``;``. A state: ``S;id;name;x;y;initial;`` then its commands, ten LEDs
  (``led0``..``led9``: 0 off, 1 on, 2 as they are) and the left and right speeds (whole
  numbers, each 0.0628 rad/s). A transition:
  ``T;id;name;x;y;from;to;`` then its conditions, a threshold and whether it is inverted for each
  of ``ps0``..``ps7`` and ``gs0``..``gs2``, the timer (tenths of a second, and an unused flag),
  and the camera's threshold and flag. A token that is no whole number reads 0, as Qt's
  ``toInt`` reads it; a line of too few tokens, or a transition naming a state not listed before
  it, makes the file unreadable, as in Webots.
- Running: the one initial state's commands are sent (with no initial state, or several, the
  automaton does not run and the robot stands still). After every basic step the sensors are
  read, a distance sensor as ``int(value) * 100 / 4096``, a ground sensor as
  ``int(value) * 100 / 1024`` (whole numbers), the camera as where a dark line (grey under 50)
  crosses its last row, from -100 (left) to 100 (right), 0 when it sees none; then the current
  state's transitions are tried in the file's order, and the first whose every condition holds
  makes its end state current, whose commands are sent. A condition of threshold 0 is none; a
  reading below its threshold fails it, or above it when inverted; a camera that sees no line
  fails a camera condition; a timer holds once its tenths of a second have passed since the
  state was entered.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Any

from mazesim._paths import MAX_TEXT_CHARACTERS, read_input
from mazesim.errors import InvalidArgumentError, _shown
from mazesim.webots.node_types import node_type

__all__ = ["Automaton", "State", "Transition", "read_automaton", "run_automaton"]

#: The version of the files read (Webots' ``Model::macroVersion`` and ``microVersion``), and
#: the older layout BotStudio still reads.
VERSION = (4, 0)
VERSION_3 = (3, 0)
#: LEDs a state commands, speeds it sets, and the value of an LED it leaves as it is.
LEDS = 10
UNCHANGED = 2
#: Radians a second of one unit of a state's speed (``EPuckFacade::setSpeeds``).
SPEED_UNIT = 0.0628
#: The distance and ground sensors a transition reads.
DISTANCE_SENSORS = 8
GROUND_SENSORS = 3
#: A grey level under this is dark (the line), above it light (``EPuckFacade``'s threshold).
DARK = 50
_WHOLE = re.compile(r"[+-]?[0-9]+")
_INT_RANGE = (-(2**31), 2**31 - 1)


@dataclass(frozen=True)
class Condition:
    """A threshold on a reading: none when 0; the reading fails it below the threshold, or
    above it when ``inverted``."""

    threshold: int = 0
    inverted: bool = False

    def holds(self, reading: int) -> bool:
        """Whether ``reading`` meets it (always, without a threshold)."""
        if not self.threshold:
            return True
        return reading <= self.threshold if self.inverted else reading >= self.threshold


@dataclass(frozen=True)
class State:
    """A state: the LED values (0, 1, or :data:`UNCHANGED`) and the speeds it commands."""

    id: int
    name: str
    initial: bool
    leds: tuple[int, ...]
    speeds: tuple[int, int]


@dataclass(frozen=True)
class Transition:
    """A transition from state ``start`` to state ``end`` (their ids) once its conditions hold."""

    id: int
    name: str
    start: int
    end: int
    distance: tuple[Condition, ...]
    ground: tuple[Condition, ...]
    tenths: int
    camera: Condition


@dataclass
class Automaton:
    """A BotStudio file's states and transitions, in the file's order."""

    states: list[State] = field(default_factory=list)
    transitions: list[Transition] = field(default_factory=list)

    def has_state(self, state_id: int) -> bool:
        """Whether a state of that id has been listed."""
        if len(self._ids) != len(self.states):
            self._ids = {state.id for state in self.states}
        return state_id in self._ids

    _ids: set[int] = field(default_factory=set, repr=False, compare=False)

    def initial(self) -> State | None:
        """The state the automaton starts in: its one initial state (None for none or several,
        when it does not run)."""
        initial = [state for state in self.states if state.initial]
        return initial[0] if len(initial) == 1 else None

    def state(self, state_id: int) -> State:
        """The first state of that id.

        Raises:
            InvalidArgumentError: No state has that id.
        """
        found = next((state for state in self.states if state.id == state_id), None)
        if found is None:
            ids = ", ".join(str(state.id) for state in self.states) or "none"
            raise InvalidArgumentError(
                f"expected the id of one of the automaton's states ({ids}), found "
                f"{_shown(state_id)}"
            )
        return found

    def leaving(self, state: State) -> list[Transition]:
        """The transitions from ``state``, in the file's order."""
        return [transition for transition in self.transitions if transition.start == state.id]


def _whole(token: str) -> int:
    """A token as Qt's ``toInt`` reads it: the whole number it writes, else 0."""
    text = token.strip()
    # Beyond 10 digits it is outside Qt's int whatever they are (and Python's int() refuses
    # more than 4300).
    if not _WHOLE.fullmatch(text) or len(text.lstrip("+-").lstrip("0")) > 10:
        return 0
    value = int(text)
    return value if _INT_RANGE[0] <= value <= _INT_RANGE[1] else 0


def _tokens(line: str, count: int, what: str, where: str) -> list[str]:
    """The first ``count`` tokens of ``line``, each ending at a ``;`` or the line's end."""
    parts = line.split(";")
    if line.endswith(";"):
        parts.pop()
    if len(parts) < count:
        raise InvalidArgumentError(
            f"{where}: expected a {what} of {count} fields, found {len(parts)}: {_shown(line)}"
        )
    return parts[:count]


def read_automaton(text: str, where: str = "the BotStudio file") -> Automaton:
    """The automaton of a BotStudio file's ``text``.

    Raises:
        InvalidArgumentError: The text is not a BotStudio 4.0 or 3.0 file, or a line of it is
            corrupted (too few fields, a transition naming a state not listed before it, a 3.0
            condition not written ``command:value``).
    """
    first, newline, rest = text.partition("\n")
    header = [word for word in re.split(r"[#. ]", first.strip()) if word]
    if not newline or len(header) != 3 or header[0] != "botstudio":
        raise InvalidArgumentError(
            f"{where}: expected a BotStudio file, starting with the line '#botstudio 4.0', "
            f"found {_shown(first)}"
        )
    version = (_whole(header[1]), _whole(header[2]))
    if version == VERSION_3:
        return _read_version_3(rest, where)
    if version != VERSION:
        raise InvalidArgumentError(
            f"{where}: expected a BotStudio file of version 4.0 or 3.0, found version "
            f"{_shown(header[1] + '.' + header[2])}, which BotStudio does not read either"
        )
    automaton = Automaton()
    for number, line in enumerate(rest.split("\n"), start=2):
        line = line.rstrip("\r")
        at = f"{where}, line {number}"
        if line.startswith("S"):
            tokens = _tokens(line, 6 + LEDS + 2, "state", at)
            values = [_whole(token) for token in tokens]
            automaton.states.append(
                State(
                    id=values[1],
                    name=tokens[2],
                    initial=bool(values[5]),
                    leds=tuple(values[6 : 6 + LEDS]),
                    speeds=(values[6 + LEDS], values[7 + LEDS]),
                )
            )
        elif line.startswith("T"):
            size = 7 + 2 * (DISTANCE_SENSORS + GROUND_SENSORS + 2)
            tokens = _tokens(line, size, "transition", at)
            values = [_whole(token) for token in tokens]
            if not (automaton.has_state(values[5]) and automaton.has_state(values[6])):
                raise InvalidArgumentError(
                    f"{at}: expected a transition between states listed before it, found one "
                    f"from state {values[5]} to state {values[6]}"
                )
            pairs = [Condition(values[k], bool(values[k + 1])) for k in range(7, size, 2)]
            automaton.transitions.append(
                Transition(
                    id=values[1],
                    name=tokens[2],
                    start=values[5],
                    end=values[6],
                    distance=tuple(pairs[:DISTANCE_SENSORS]),
                    ground=tuple(pairs[DISTANCE_SENSORS : DISTANCE_SENSORS + GROUND_SENSORS]),
                    tenths=pairs[DISTANCE_SENSORS + GROUND_SENSORS].threshold,
                    camera=pairs[-1],
                )
            )
    return automaton


def _read_version_3(rest: str, where: str) -> Automaton:
    """The automaton of a BotStudio 3.0 file after its header (``Automaton::
    fromStringVersion3``): states, one a line, until an empty line, then transitions. A state
    is ``name;x;y;`` and eight commands, of which the fourth and fifth are the speeds and the
    sixth and seventh the LEDs turned on and off (bit ``i`` for ``led<i>``); its id is its place
    among the states, the first one initial. A transition is ``name;from;to;``, two tokens
    left out, then conditions ``command:value``: 4-11 ``ps0``..``ps7`` and 12-14 ``gs0``..``gs2``
    of threshold ``|value|``, 20 the timer of ``|value| / 2`` tenths of a second, 21 the camera
    of ``10 |value|``, each inverted when the value is negative."""
    automaton = Automaton()
    reading_states = True
    for number, line in enumerate(rest.split("\n"), start=2):
        line = line.rstrip("\r")
        at = f"{where}, line {number}"
        if not line:
            reading_states = False
        elif reading_states:
            tokens = _tokens(line, 3 + 8, "state", at)
            values = [_whole(token) for token in tokens]
            on, off = values[3 + 5], values[3 + 6]
            leds = [0 if off & (1 << i) else 1 if on & (1 << i) else UNCHANGED for i in range(LEDS)]
            count = len(automaton.states)
            automaton.states.append(
                State(count, tokens[0], count == 0, tuple(leds), (values[6], values[7]))
            )
        else:
            automaton.transitions.append(_transition_version_3(line, automaton, at))
    return automaton


def _transition_version_3(line: str, automaton: Automaton, at: str) -> Transition:
    tokens = _tokens(line, 3 + 2, "transition", at)
    start, end = _whole(tokens[1]), _whole(tokens[2])
    if not (automaton.has_state(start) and automaton.has_state(end)):
        raise InvalidArgumentError(
            f"{at}: expected a transition between states listed before it, found one from "
            f"state {start} to state {end}"
        )
    distance = [Condition()] * DISTANCE_SENSORS
    ground = [Condition()] * GROUND_SENSORS
    tenths, camera = 0, Condition()
    parts = line.split(";")
    for condition in parts[5 : len(parts) - line.endswith(";")]:
        pair = condition.split(":")
        if len(pair) != 2:
            raise InvalidArgumentError(
                f"{at}: expected conditions written command:value, found {_shown(condition)}"
            )
        command, value = _whole(pair[0]), _whole(pair[1])
        made = Condition(abs(value), value < 0)
        if command == 20:
            tenths = abs(value) // 2
        elif command == 21:
            camera = Condition(10 * abs(value), value < 0)
        elif 4 <= command <= 11:
            distance[command - 4] = made
        elif 12 <= command <= 14:
            ground[command - 12] = made
    count = len(automaton.states) + len(automaton.transitions)
    return Transition(count, tokens[0], start, end, tuple(distance), tuple(ground), tenths, camera)


def line_position(greys: list[int]) -> int:
    """Where a dark line crosses a row of grey levels: -100 when its leftmost pixel is dark,
    100 when its rightmost is, else the middle of the dark pixels from -100 to 100; 0 when no
    pixel is dark or none is light (``EPuckFacade``'s line detection)."""
    size = len(greys)
    dark = [i for i, grey in enumerate(greys) if grey < DARK]
    if not dark or not any(grey > DARK for grey in greys):
        return 0
    if dark[0] == 0:
        return -100
    if dark[-1] == size - 1:
        return 100
    return (dark[0] + dark[-1]) * 100 // size - 100


def _scaled(value: float, full: int) -> int:
    """A reading in BotStudio's units: ``int(value) * 100 / full`` in whole numbers, truncated
    towards 0 as C truncates."""
    if not math.isfinite(value):
        return 0
    whole = int(value) * 100
    return whole // full if whole >= 0 else -((-whole) // full)


class _Robot:
    """The e-puck's devices as BotStudio reads and drives them (``EPuckFacade``)."""

    def __init__(self, robot: Any) -> None:
        self.robot = robot
        step = int(robot.getBasicTimeStep())
        self.step_ms = max(1, step)
        self.leds = [robot.getDevice(f"led{i}") for i in range(LEDS)]
        self.distance = [robot.getDevice(f"ps{i}") for i in range(DISTANCE_SENSORS)]
        self.ground = _ground_sensors(robot)
        self.camera = robot.getDevice("camera")
        self.motors = [robot.getDevice(f"{side} wheel motor") for side in ("left", "right")]
        for sensor in [*self.distance, *self.ground, self.camera]:
            if sensor is not None:
                sensor.enable(self.step_ms)
        self.time = 0.0

    def send(self, state: State) -> None:
        """The state's commands: its LEDs, then its speeds in velocity control."""
        for led, value in zip(self.leds, state.leds):
            if led is not None and value != UNCHANGED:
                led.set(int(bool(value)))
        for motor, speed in zip(self.motors, state.speeds):
            if motor is not None:
                motor.setPosition(math.inf)
                motor.setVelocity(speed * SPEED_UNIT)

    def reading(self, sensors: list[Any], full: int) -> list[int]:
        return [0 if s is None else _scaled(float(s.getValue()), full) for s in sensors]

    def line(self) -> int:
        camera = self.camera
        image = None if camera is None else camera.getImage()
        if not image:
            return 0
        width, height = camera.getWidth(), camera.getHeight()
        row = height - 1
        return line_position([camera.imageGetGray(image, width, x, row) for x in range(width)])


def _ground_sensors(robot: Any) -> list[Any]:
    """The robot's ``gs0``..``gs2``, found among its devices as BotStudio finds them (None for
    one it does not have: an E-puck without its ground sensors module, whose readings are 0)."""
    found: list[Any] = [None] * GROUND_SENSORS
    for index in range(robot.getNumberOfDevices()):
        device = robot.getDeviceByIndex(index)
        match = re.fullmatch(r"gs([0-9]+)", device.getName())
        if match and device.getNodeType() == node_type("DISTANCE_SENSOR"):
            number = int(match.group(1))
            if number < GROUND_SENSORS and found[number] is None:
                found[number] = device
    return found


def _fired(transition: Transition, robot: _Robot, entered: float) -> bool:
    """Whether every condition of ``transition`` holds now, the state entered at ``entered``."""
    distance = robot.reading(robot.distance, 4096)
    ground = robot.reading(robot.ground, 1024)
    if not all(c.holds(v) for c, v in zip(transition.distance, distance)):
        return False
    if not all(c.holds(v) for c, v in zip(transition.ground, ground)):
        return False
    if transition.camera.threshold:
        seen = robot.line()
        if not seen or not transition.camera.holds(seen):
            return False
    return not transition.tenths or robot.time - entered >= 0.1 * transition.tenths


def run_automaton(path: str) -> None:
    """Runs the BotStudio file ``path`` on the run's robot until the run ends (the controller of
    a world's robot whose controller is ``NAME.bsg``).

    Raises:
        MazesimError: The file cannot be read, or is not an automaton BotStudio reads (see
            :func:`read_automaton`); read before the robot is made. The controller program a
            world's ``.bsg`` controller runs (``mazesim.webots.runner.BOTSTUDIO_PROGRAM``) ends
            then with exit status 1 and one line on stderr saying why (``BotStudio: ...``), not
            a traceback of mazesim's.
    """
    from mazesim.webots.controller import Robot

    data = read_input(path, MAX_TEXT_CHARACTERS, "the BotStudio automaton")
    automaton = read_automaton(data.decode("utf-8", errors="replace"), path)
    robot = _Robot(Robot())
    current = automaton.initial()
    if current is None:
        count = sum(state.initial for state in automaton.states)
        print(f"BotStudio: the automaton has {count} initial states, not one: it does not run")
    else:
        robot.send(current)
    first: dict[int, State] = {}
    for state in automaton.states:
        first.setdefault(state.id, state)
    leaving: dict[int, list[Transition]] = {}
    for transition in automaton.transitions:
        leaving.setdefault(transition.start, []).append(transition)
    entered = 0.0
    while robot.robot.step(robot.step_ms) != -1:
        robot.time = float(robot.robot.getTime())
        if current is None:
            continue
        for transition in leaving.get(current.id, []):
            if _fired(transition, robot, entered):
                current = first[transition.end]
                robot.send(current)
                entered = robot.time
                break
