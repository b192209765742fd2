"""BotStudio automata (``.bsg``, Webots' Robotics curriculum), read and run as Webots' botstudio
robot window runs them once its Run button is pressed (#32)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import mazesim
from mazesim.errors import InvalidArgumentError
from mazesim.webots import run_controller
from mazesim.webots.botstudio import line_position, read_automaton
from mazesim.webots.lockstep import controller_of, run_world

HEADER = "#botstudio 4.0\n#e-puck\n\n"
#: Ten LEDs left as they are and the speeds, a state's commands.
KEEP = "2;" * 10


def state(number: int, name: str, initial: bool, left: int, right: int, leds: str = KEEP) -> str:
    return f"S;{number};{name};0;0;{int(initial)};{leds}{left};{right};\n"


def transition(number: int, start: int, end: int, **conditions: int) -> str:
    """A transition whose conditions are all none but those given by index (``c0=7``: ps0's
    threshold 7; ``c22``: the timer; ``c24``: the camera)."""
    values = [conditions.get(f"c{i}", 0) for i in range(26)]
    return f"T;{number};t;0;0;{start};{end};" + "".join(f"{v};" for v in values) + "\n"


def test_states_and_transitions_are_read_as_botstudio_writes_them() -> None:
    text = (
        HEADER
        + state(0, "forward", True, 50, 50, "1;0;2;2;2;2;2;2;2;2;")
        + state(1, "turn", False, 20, -20)
        + transition(2, 0, 1, c0=7, c1=1, c16=57, c22=10, c24=-50, c25=1)
        + "X;anything else is left out\n"
    )
    automaton = read_automaton(text)
    forward, turn = automaton.states
    assert (forward.initial, forward.speeds, forward.leds[:3]) == (True, (50, 50), (1, 0, 2))
    assert automaton.initial() is forward and automaton.leaving(turn) == []
    (step,) = automaton.leaving(forward)
    assert (step.start, step.end, step.tenths) == (0, 1, 10)
    assert (step.distance[0].threshold, step.distance[0].inverted) == (7, True)
    assert (step.ground[0].threshold, step.ground[0].inverted) == (57, False)
    assert (step.camera.threshold, step.camera.inverted) == (-50, True)
    # A condition of threshold 0 is none; a reading below a threshold fails it, above an
    # inverted one.
    assert step.distance[1].holds(-1000)
    assert step.ground[0].holds(57) and not step.ground[0].holds(56)
    assert step.distance[0].holds(7) and not step.distance[0].holds(8)
    # Tokens that are no whole number read 0, as Qt's toInt reads them.
    odd = read_automaton(HEADER + "S;0;s;0;0;yes;" + KEEP + "12.5;1e3;\n")
    assert (odd.states[0].initial, odd.states[0].speeds) == (False, (0, 0))
    assert odd.initial() is None, "no initial state: the automaton does not run"


@pytest.mark.parametrize(
    ("text", "said"),
    [
        ("", "starting with the line '#botstudio 4.0'"),
        ("#botstudio 4.0", "starting with the line"),
        ("#botstudio 2.0\nS\n", "version 4.0 or 3.0, found version '2.0'"),
        ("#botstudio 3.0\na;0;0;1;2;3;4;5;6;7;8\n\nt;0;0;x;y;20\n", "command:value, found '20'"),
        ("#botstudio 3.0\na;0;0;1;2;3;4;5;6;7;8\n\nt;0;4;x;y;\n", "from state 0 to state 4"),
        ("#botstudio 3.0\na;0;0;1;2;3;4\n", "line 2: expected a state of 11 fields, found 7"),
        (HEADER + "S;0;s;0;0;1;2;2;\n", "line 4: expected a state of 18 fields, found 8"),
        (HEADER + state(0, "a", True, 1, 1) + transition(1, 0, 5), "from state 0 to state 5"),
        (HEADER + transition(1, 0, 0) + state(0, "a", True, 1, 1), "states listed before it"),
    ],
)
def test_a_file_botstudio_cannot_read_is_refused_with_what_it_holds(text: str, said: str) -> None:
    with pytest.raises(InvalidArgumentError, match="expected") as raised:
        read_automaton(text, "a.bsg")
    assert said in str(raised.value) and str(raised.value).startswith("a.bsg")


def test_a_file_of_the_older_3_0_layout_is_read_as_botstudio_reads_it() -> None:
    """BotStudio 3.0 (``fromStringVersion3``): states until an empty line (``name;x;y;`` then
    eight commands: speeds fourth and fifth, LEDs turned on and off as bits sixth and seventh),
    ids in order, the first initial; then transitions ``name;from;to;`` with two tokens left
    out and ``command:value`` conditions (4-11 ps, 12-14 gs, 20 timer in halves of tenths, 21
    camera in tenths, negative inverted)."""
    text = (
        "#botstudio 3.0\n"
        "go;10;20;0;0;0;40;40;5;1;0;\n"
        "turn;30;40;0;0;0;-20;20;0;0;0;\n"
        "\n"
        "wait;0;1;0;0;20:20;\n"
        "near;0;1;0;0;4:-30;13:57;21:-5;\n"
    )
    automaton = read_automaton(text)
    go, turn = automaton.states
    assert (go.id, go.initial, go.speeds) == (0, True, (40, 40))
    assert (turn.id, turn.initial, turn.speeds) == (1, False, (-20, 20))
    # On: bits 0 and 2 (5); off: bit 0 (1), which wins: led0 off, led2 on, the rest as they are.
    assert go.leds[:4] == (0, 2, 1, 2) and turn.leds == (2,) * 10
    wait, near = automaton.leaving(go)
    assert (wait.tenths, wait.end) == (10, 1)
    assert (near.distance[0].threshold, near.distance[0].inverted) == (30, True)
    assert (near.ground[1].threshold, near.ground[1].inverted) == (57, False)
    assert (near.camera.threshold, near.camera.inverted) == (50, True)


def test_the_camera_reads_where_a_dark_line_crosses_its_row() -> None:
    light, dark = 200, 10
    assert line_position([light] * 10) == 0 and line_position([dark] * 10) == 0
    assert line_position([dark] + [light] * 9) == -100
    assert line_position([light] * 9 + [dark]) == 100
    # Dark pixels 6 and 7 of 10: (6 + 7) * 100 / 10 - 100.
    assert line_position([light] * 6 + [dark] * 2 + [light] * 2) == 30
    assert line_position([light] * 2 + [dark] + [light] * 7) == -60
    # Grey 50 is neither dark nor light: (4 + 4) * 100 / 6 - 100, in whole numbers.
    assert line_position([50] * 4 + [dark] + [light]) == 33


def write_automaton(folder: Path, name: str, text: str) -> Path:
    path = folder / "controllers" / name / f"{name}.bsg"
    path.parent.mkdir(parents=True)
    path.write_text(text)
    return path


def test_an_automaton_drives_the_e_puck_through_its_states(tmp_path: Path) -> None:
    """Forward at 50 (3.14 rad/s, 0.0628 m/s) until its 1 s timer, then a turn in place at 20
    (1.256 rad/s each wheel, the other way round) until the run ends: 1 s forward, then the
    heading turns by 1.256 * 0.02 * 2 / 0.05685 rad a second."""
    path = write_automaton(
        tmp_path,
        "two_states",
        HEADER
        + state(0, "forward", True, 50, 50)
        + state(1, "turn", False, 20, -20)
        # Back to forward only once ps0 reads over 90 % (never, in the open arena).
        + transition(2, 0, 1, c22=10)
        + transition(3, 1, 0, c0=90),
    )
    world = mazesim.load_world("arena")
    run = run_controller(path, world, seconds=2.0, noise=False)
    assert (run.exit_status, run.error) == (0, "")
    x, y, yaw = run.final_pose
    start_x, start_y, start_yaw = world.start
    assert math.hypot(x - start_x, y - start_y) == pytest.approx(0.0628, abs=0.004)
    assert run.distance_m == pytest.approx(0.0628, abs=0.004), "turning in place adds none"
    # About 1 s of turning clockwise (the left wheel forward).
    rate = 1.256 * 0.02 * 2 / 0.05685
    assert math.remainder(start_yaw - yaw, 2 * math.pi) == pytest.approx(rate, rel=0.08)


def test_a_world_s_robot_runs_the_automaton_of_its_controller_folder(tmp_path: Path) -> None:
    """A curriculum world: the E-puck's controller ``forward`` is ``controllers/forward/
    forward.bsg`` (one initial state, speed 100): found, run, and the e-puck drives 6.28 rad/s
    of its wheels, 0.126 m a second; an automaton without an initial state does not run."""
    (tmp_path / "worlds").mkdir()
    world = tmp_path / "worlds" / "fsm.wbt"
    world.write_text(
        "#VRML_SIM R2023b utf8\nRectangleArena { floorSize 2 2 }\n"
        'E-puck { controller "forward" window "botstudio" }\n'
        'E-puck { translation 0 0.3 0 name "idle" controller "idle" }\n'
    )
    path = write_automaton(tmp_path, "forward", HEADER + state(0, "forward", True, 100, 100))
    write_automaton(tmp_path, "idle", HEADER + state(0, "still", False, 100, 100))
    assert controller_of({"name": "e-puck", "controller": "forward"}, str(world), {}) == (
        str(path),
        "",
    )
    run = run_world(str(world), seconds=1.0)
    driver, idle = run.robots
    assert (driver.exit_status, driver.missing) == (0, ())
    assert driver.distance_m == pytest.approx(0.126, abs=0.01)
    assert idle.distance_m == 0.0


def test_a_proximity_condition_stops_the_e_puck_before_the_wall(tmp_path: Path) -> None:
    """Forward at 100 until ps0 or ps7 (the two front sensors) read 25 % of 4096 (a transition
    each, tried in the file's order), then a state of speed 0: the e-puck stops a few
    millimetres from the arena's wall ahead, untouched, and stands there."""
    path = write_automaton(
        tmp_path,
        "brake",
        HEADER
        + state(0, "forward", True, 100, 100)
        + state(1, "stop", False, 0, 0)
        + transition(2, 0, 1, c0=25)
        + transition(3, 0, 1, c14=25),
    )
    world = mazesim.load_world("arena")
    run = run_controller(path, world, seconds=12.0, noise=False)
    assert (run.exit_status, run.error, run.collisions) == (0, "", 0)
    # The wall's face is at x 0.495; the body (radius 0.037) stops 3.8 mm short of it, where
    # ps0 and ps7 first read 1024 (25 * 4096 / 100).
    gap = 0.495 - run.final_pose[0] - 0.037
    assert 0.002 < gap < 0.006, "stopped short of the wall ahead, body clear"
    assert run.longest_stop_s > 8.0, "and stands there until the run's end"


def test_a_mutated_file_is_read_or_refused_with_the_package_s_error() -> None:
    """Bytes of a 4.0 and a 3.0 automaton changed, deleted or inserted at random (fixed seed,
    600 files): each reads as an automaton or is refused with InvalidArgumentError, never
    another exception."""
    import random

    texts = [
        HEADER
        + state(0, "forward", True, 50, 50, "1;0;2;2;2;2;2;2;2;2;")
        + state(1, "turn", False, 20, -20)
        + transition(2, 0, 1, c0=7, c1=1, c16=57, c22=10, c24=-50, c25=1)
        + transition(3, 1, 0, c22=5),
        "#botstudio 3.0\ngo;10;20;0;0;0;40;40;5;1;0;\nturn;3;4;0;0;0;-2;2;0;0;0;\n\n"
        "wait;0;1;0;0;20:20;\nnear;1;0;0;0;4:-30;13:57;21:-5;\n",
    ]
    pieces = [";", ":", "\n", "\r", "-", "9" * 12, "", "S", "T", "\x00", "é", "#botstudio 3.0\n"]
    chance = random.Random(20261204)
    outcomes = {"read": 0, "refused": 0}
    for number in range(600):
        text = list(texts[number % 2])
        for _ in range(chance.randint(1, 4)):
            at = chance.randrange(len(text) + 1)
            kind = chance.randrange(3)
            if kind == 0 and at < len(text):
                del text[at : at + chance.randint(1, 6)]
            else:
                text[at:at] = chance.choice(pieces)
        try:
            read_automaton("".join(text), "m.bsg")
            outcomes["read"] += 1
        except InvalidArgumentError:
            outcomes["refused"] += 1
    assert min(outcomes.values()) > 50, outcomes


def test_a_file_it_cannot_read_ends_the_controller_with_one_line_saying_why(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    path = write_automaton(tmp_path, "bad", HEADER + "S;1;2\n")
    run = run_controller(path, mazesim.load_world("arena"), seconds=0.5, noise=False)
    err = capfd.readouterr().err
    assert run.exit_status == 1
    assert "BotStudio: " in err and "expected a state of 18 fields, found 3" in err
    assert "Traceback" not in err


def test_run_automaton_called_as_a_function_raises_what_it_cannot_read(tmp_path: Path) -> None:
    # Only the controller program ends the process; the function raises as every other does
    # (it once raised SystemExit(1), which ends a caller's process).
    from mazesim.webots.botstudio import run_automaton

    with pytest.raises(mazesim.MazesimError, match="expected a state of 18 fields, found 3"):
        run_automaton(str(write_automaton(tmp_path, "bad", HEADER + "S;1;2\n")))
    with pytest.raises(mazesim.MazesimError):
        run_automaton(str(tmp_path / "missing.bsg"))


def test_a_number_of_thousands_of_digits_reads_as_qt_reads_one_out_of_range() -> None:
    # Qt's toInt gives 0 beyond an int's range; Python's int() refuses over 4300 digits.
    text = HEADER + f"S;0;go;0;0;1;{KEEP}{'9' * 5000};50;\n"
    automaton = read_automaton(text, "big.bsg")
    assert automaton.states[0].speeds == (0, 50)
