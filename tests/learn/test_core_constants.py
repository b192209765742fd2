"""The navigator's constants that the core and the package both write hold the same values.

The core's ``navigator`` module acts by its own constants (Table 4.1's edges, the sub-tasks'
angles, distances and step limit, the primitive actions' wheel speeds, the rewards its tests and
benches use); the package writes them too (:mod:`mazesim.learn.discretise`,
:mod:`mazesim.learn.subtasks`, :mod:`mazesim.actions`), for its files' descriptions, the rewards
it hands the core's training round and the numpy references of the tests. ``docs/design.md``
tells a contributor who changes a sub-task rule to change both; this test fails until they agree.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from mazesim.actions import WHEEL_SPEED_FRACTIONS
from mazesim.learn import discretise, subtasks

NAVIGATOR = Path(__file__).resolve().parents[2] / "crates" / "mazesim-core" / "src" / "navigator"


def rust_constant(file: str, name: str) -> str:
    """The value the core's ``navigator/<file>`` gives the constant ``name``, as written."""
    text = (NAVIGATOR / file).read_text(encoding="utf-8")
    found = re.search(rf"pub const {name}: [^=]+= (.*?);", text, flags=re.S)
    assert found, f"navigator/{file} defines no constant {name}"
    return found[1]


def numbers(text: str) -> list[float]:
    """The numbers written in ``text``, with ``PI / 2.0`` read as pi over 2."""
    text = re.sub(r"(-?)PI / 2\.0", lambda m: f"{m[1]}{math.pi / 2.0!r}", text)
    return [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?(?:e-?\d+)?", text)]


def rust_degrees(file: str, function: str) -> list[float]:
    """The degrees a function of ``navigator/<file>`` turns into radians (``30.0_f64``)."""
    text = (NAVIGATOR / file).read_text(encoding="utf-8")
    body = text.split(f"fn {function}()", 1)[1].split("\n}", 1)[0]
    return [float(v) for v in re.findall(r"(-?\d+(?:\.\d+)?)_f64\.to_radians", body)]


@pytest.mark.parametrize(
    ("name", "python"),
    [
        ("NUM_PHASES", subtasks.NUM_PHASES),
        ("MAX_DOOR_STEPS", (subtasks.MAX_DOOR_STEPS,)),
        ("TURN_EXIT_DISTANCE", (subtasks.TURN_EXIT_DISTANCE,)),
        ("FORWARD_DISTANCE", (subtasks.FORWARD_DISTANCE,)),
        ("DISTANCE_EDGES", subtasks.DISTANCE_EDGES),
        ("TARGET_TURN", subtasks.TARGET_TURN),
    ],
)
def test_the_sub_tasks_constants_agree(name: str, python: tuple[float, ...]) -> None:
    assert numbers(rust_constant("door.rs", name)) == list(python)


@pytest.mark.parametrize(
    ("function", "radians"),
    [
        ("turn_phase_angles", subtasks.TURN_PHASE_ANGLES),
        ("forward_phase_angle", (subtasks.FORWARD_PHASE_ANGLE,)),
        ("heading_tolerance", (subtasks.HEADING_TOLERANCE,)),
        ("give_up_angle", (subtasks.GIVE_UP_ANGLE,)),
    ],
)
def test_the_sub_tasks_angles_agree(function: str, radians: tuple[float, ...]) -> None:
    assert [math.radians(d) for d in rust_degrees("door.rs", function)] == list(radians)


def test_table_4_1_agrees() -> None:
    assert numbers(rust_constant("discretiser.rs", "LEVEL_EDGES_CM")) == list(
        discretise.LEVEL_EDGES_CM
    )
    assert numbers(rust_constant("discretiser.rs", "NUM_STATES")) == [discretise.NUM_STATES]


def test_the_wheel_speeds_agree() -> None:
    rust = numbers(rust_constant("tabular.rs", "WHEEL_SPEED_FRACTIONS"))
    assert rust == WHEEL_SPEED_FRACTIONS.ravel().tolist()


def test_the_rewards_of_the_cores_tests_are_the_navigators() -> None:
    text = rust_constant("training.rs", "NAVIGATOR")
    rust = {key: float(value) for key, value in re.findall(r"(\w+): (-?[\d.]+)", text)}
    assert rust == {
        "progress": subtasks.PROGRESS_REWARD,
        "collision": subtasks.COLLISION_PENALTY,
        "corridor_step": subtasks.CORRIDOR_STEP_REWARD,
        "door_step": subtasks.DOOR_STEP_REWARD,
        "heading": subtasks.HEADING_REWARD,
        "door_success": subtasks.DOOR_SUCCESS_REWARD,
        "door_failure": subtasks.DOOR_FAILURE_REWARD,
    }


def test_the_reader_reads_what_the_core_writes() -> None:
    assert numbers("[0.0, -PI / 2.0, PI / 2.0, 0.0]") == [0.0, -math.pi / 2, math.pi / 2, 0.0]
    assert numbers("[[0.5, 0.375],\n [-0.25, 0.25]]") == [0.5, 0.375, -0.25, 0.25]
    assert rust_degrees("door.rs", "turn_phase_angles") == [30.0, 60.0]
