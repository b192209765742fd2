"""Every argument of every function and method of ``mazesim._core``, given a value of the wrong
type, raises ``mazesim.WrongTypeError`` naming the argument (an ``InvalidArgumentError`` that is
also a ``TypeError``): never pyo3's bare ``TypeError``.

The arguments are found by introspection, so a new function or method is covered as soon as it
exists; a parameter name this file has no valid sample for fails the test (add its sample below).
"""

from __future__ import annotations

import inspect
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import mazesim
import mazesim._core as core

WEBOTS_WORLD = sorted((Path(__file__).parent / "data" / "webots-worlds").glob("*.wbt"))[0]
NUM_ENVS = 2

#: The arguments of a ``TaskFeatures`` of ``NUM_ENVS`` e-pucks observing ``"plan"``.
TASK_FEATURES = (
    NUM_ENVS,
    "plan",
    False,
    np.array([4095.0] * 8 + [1000.0] * 3),
    np.full(26, -2.0, np.float32),
    np.full(26, 2.0, np.float32),
)

#: Private entry points: kept for tests of the panic guard, and the atomic writer's bookkeeping
#: of its writes in progress (called by ``mazesim._atomic`` alone, with a file name it made).
PRIVATE = {"_panic_for_tests", "_temporary_writing"}


class WrongType:
    """A value of a type no argument takes."""

    def __repr__(self) -> str:
        return "WrongType()"


def callables() -> Iterator[tuple[str, str, Callable[..., Any]]]:
    """(class or "", name, callable) for every public callable of the extension."""
    for name in sorted(dir(core)):
        obj = getattr(core, name)
        if name in PRIVATE or name.startswith("__"):
            continue
        if inspect.isclass(obj):
            if issubclass(obj, BaseException):
                continue
            yield "", name, obj
            for member in sorted(dir(obj)):
                if not member.startswith("_") and callable(getattr(obj, member)):
                    yield name, member, getattr(obj, member)
        elif callable(obj):
            yield "", name, obj


def samples(tmp: Path) -> dict[str, Any]:
    """A valid value of every parameter name, and an instance of every class."""
    world = mazesim.World.builtin("seed-maze")
    batch = core.BatchSimulator(world, num_envs=NUM_ENVS)
    x, y, yaw = world.start
    saved = tmp / "world.toml"
    world.save(saved)
    simulator = core.Simulator(world)
    features = core.TaskFeatures(*TASK_FEATURES)
    navigator = core.Navigator(np.zeros((4, 3 * 4096, 12)), NUM_ENVS)
    return {
        "instances": {
            "World": world,
            "Simulator": simulator,
            "BatchSimulator": batch,
            "RobotProfile": core.RobotProfile.builtin("e-puck"),
            "TaskFeatures": features,
            "Navigator": navigator,
        },
        "name": {"World": "seed-maze", "RobotProfile": "e-puck"},
        "name_or_path": "e-puck",
        "path": {"load": saved, "save": tmp / "out.toml", "import_wbt": WEBOTS_WORLD},
        "worlds": world,
        "world": world,
        "num_envs": NUM_ENVS,
        "robot": "e-puck",
        "robot_index": 0,
        "kept_robots": [0],
        "robot_profiles": None,
        "overlap_robots": False,
        "commands": np.zeros((1, 2)),
        "seeds": None,
        "noise": True,
        "control_step_ms": None,
        "threads": 0,
        "observations": np.zeros((NUM_ENVS, batch.observation_width), np.float32),
        "poses": np.zeros((NUM_ENVS, 3), np.float32),
        "colliding": np.zeros(NUM_ENVS, bool),
        "crossings": np.zeros(NUM_ENVS, np.int32),
        "actions": np.zeros((NUM_ENVS, 2), np.float32),
        "mask": None,
        "starts": np.array([[x, y, yaw]] * NUM_ENVS),
        "goals": np.array([[x, y, 0.05]] * NUM_ENVS),
        "radius": 0.05,
        "index": 0,
        "walls": [],
        "bodies": [],
        "paint": [],
        "from_pose": (x, y, yaw),
        "to_pose": (x, y, yaw),
        "seed": 0,
        "reading": 100.0,
        "reflectance": 0.5,
        "x": x,
        "y": y,
        "yaw": yaw,
        "left": 0.0,
        "right": 0.0,
        "vx": 0.0,
        "vy": 0.0,
        "turn_rate": 0.0,
        "text": world.to_toml(),
        "source": "sample",
        "floor_images": None,
        "wall_colours": None,
        "codes": core.default_codes(),
        "volts": 1.0,
        "width": 5,
        "height": 5,
        "cell_size": 0.25,
        "wall_thickness": 0.01,
        "loops": 0.0,
        "checkpoints": True,
        "junction": True,
        "floor_reflectance": 0.36,
        "layout": core.MazeLayout(),
        "drive": core.DrivePerturbation(),
        "sensing": core.SensingPerturbation(),
        "envs": np.arange(NUM_ENVS, dtype=np.int64),
        "low": np.zeros(11, np.float32),
        "high": np.full(11, 5000.0, np.float32),
        "steps": 3,
        "controller": "braitenberg",
        "robot_line": None,
        "imported_from": None,
        "settings": core.RunSettings(),
        "limits": core.EpisodeLimits(),
        "max_steps": 0,
        "end_at_goal": False,
        "end_at_crossing": False,
        "autoreset": True,
        "trace": None,
        "table": np.zeros((4096, 12)),
        "allowed_actions": None,
        "table_index": None,
        "epsilon": 0.0,
        "threshold": 80.0,
        "max_speed": 6.28,
        "active": None,
        "hold_spins": False,
        "hold_heading": False,
        "wheel_speed_limit": None,
        "subtasks": None,
        "snapshot": {"restore": simulator.snapshot(), "restore_env": batch.snapshot_env(0)},
        "wheel_radius_scale": 1.05,
        "axle_length_scale": 0.95,
        "motor_gains": (1.0, 0.95),
        "noise_scale": 2.0,
        "ir_angle_error": 0.05,
        "ir_offset_error": 0.002,
        "wall_reflectance": 0.5,
        "ground_gain": 0.9,
        "slip_on_contact": 0.2,
        "observation": TASK_FEATURES[1],
        "include_pose": TASK_FEATURES[2],
        "sensor_scale": TASK_FEATURES[3],
        "feature_low": TASK_FEATURES[4],
        "feature_high": TASK_FEATURES[5],
        "env": 0,
        "place": np.array([0.1, 0.1, 1.0, 0.0, 0.0, 0.25, 0.0, 0.0]),
        "rows": 2,
        "cols": 2,
        "shape": (2, 2),
        "waypoints": np.zeros((4, 2)),
        "open_sides": np.ones((4, 4)),
        "goal_cell": 3,
        "mode": "maze",
        "goal": np.array([0.3, 0.3, 0.05]),
        "origin": np.zeros(2),
        "targets": np.zeros((4, 5)),
        "readings": np.zeros((NUM_ENVS, 11), np.float32),
        "previous": np.zeros((NUM_ENVS, 2), np.float32),
        "state": features.state(),
        "features": features,
        "observe": True,
        "bounds": core.StepBounds(np.zeros(11, np.float32), np.full(11, 5000.0, np.float32), 6.28),
        "elevation": 0.16,
        "lower_q": np.zeros((4, 3 * 4096, 12)),
        "distances_cm": np.full((NUM_ENVS, 6), 30.0),
        "odometry": np.zeros((NUM_ENVS, 3)),
        "chosen": np.full(NUM_ENVS, -1, np.int64),
        # Parameters whose name means something else for one callable.
        "overrides": {
            "observe_env": {"readings": np.zeros(11, np.float32), "pose": np.zeros(3, np.float32)},
            "run": {"controller": core.TabularSettings(np.zeros((4096, 12)))},
            "sharp_distances": {"readings": np.full(6, 1.0), "in_cm": False},
            "train_lower_round": lower_round_samples(world, x, y, yaw, batch),
            "LowerRoundSettings": lower_round_samples(world, x, y, yaw, batch),
            "set_subtask_arrays": {"subtasks": navigator.subtask_arrays()},
            "q_batch_update": {
                "q": np.zeros((4, 3)),
                "visits": np.zeros((4, 3), np.int64),
                "transitions": {
                    "states": np.array([0, 1], np.int64),
                    "actions": np.array([0, 2], np.int64),
                    "rewards": np.array([1.0, -1.0]),
                    "next_states": np.array([1, 2], np.int64),
                    "bootstrap": np.array([0.9, 0.0]),
                },
                "allowed": np.ones(3, bool),
                "rate": (0.5, 0.02, 0.5),
            },
        },
    }


def lower_round_samples(world: Any, x: float, y: float, yaw: float, batch: Any) -> dict[str, Any]:
    """A valid round of one step of ``train_lower_round`` for the ``NUM_ENVS`` robots of
    ``batch``, with the arguments of its ``LowerRoundSettings``."""
    rows = 3 * 4096
    samples: dict[str, Any] = {
        "crews": [
            {
                "simulator": batch,
                "observations": np.zeros((NUM_ENVS, batch.observation_width), np.float32),
                "poses": np.zeros((NUM_ENVS, 3), np.float32),
                "colliding": np.zeros(NUM_ENVS, bool),
                "crossings": np.zeros(NUM_ENVS, np.int32),
                "world_of_env": np.zeros(NUM_ENVS, np.int64),
                "wheel_speeds": np.zeros((12, 2), np.float32),
                "members": np.arange(NUM_ENVS, dtype=np.int64),
            }
        ],
        "worlds": [world],
        "role": np.arange(NUM_ENVS, dtype=np.int64) % 4,
        "starts": {
            "world": np.zeros((NUM_ENVS, 1), np.int64),
            "pose": np.array([[[x, y, yaw]]] * NUM_ENVS),
            "seed": np.zeros((NUM_ENVS, 1), np.uint64),
            "path": np.zeros((NUM_ENVS, 1, 9)),
        },
        "explore": np.zeros((1, NUM_ENVS)),
        "random_action": np.zeros((1, NUM_ENVS), np.int64),
        "q": np.zeros((4, rows, 12)),
        "visits": np.zeros((4, rows, 12), np.int64),
        "allowed": np.ones((4, 12), bool),
        "learning": {
            "gamma": 0.99,
            "epsilon": 0.0,
            "decision_steps": 10,
            "corridor_episode_steps": 350,
            "rate_initial": 0.5,
            "rate_floor": 0.02,
            "rate_power": 0.5,
            "progress_reward": 10.0,
            "collision_penalty": -2.0,
            "corridor_step_reward": -0.02,
            "door_step_reward": -0.03,
            "heading_reward": 2.0,
            "door_success_reward": 5.0,
            "door_failure_reward": -5.0,
            "door_path_exit": 0.25,
            "success_past_centre": 0.04,
            "success_across": 0.08,
        },
    }
    samples["settings"] = core.LowerRoundSettings(
        *(samples[k] for k in ("learning", "worlds", "role", "allowed"))
    )
    return samples


def sample(table: dict[str, Any], param: str, owner: str, name: str) -> Any:
    own = table["overrides"].get(name, {})
    if param in own:
        return own[param]
    value = table[param]
    if param in ("name", "path", "snapshot"):
        return value[owner or name] if param == "name" else value[name]
    if param == "text" and name == "import_wbt_text":
        return WEBOTS_WORLD.read_text(encoding="utf-8")
    if param == "text" and owner == "RobotProfile":
        return core.RobotProfile.builtin("seed").to_toml()
    return value


def cases(tmp: Path) -> Iterator[tuple[str, Callable[..., Any], dict[str, Any], str]]:
    """(label, callable, valid keyword arguments, the parameter to give a wrong type)."""
    table = samples(tmp)
    for owner, name, target in callables():
        bound = getattr(table["instances"][owner], name) if owner else target
        try:
            params = [p for p in inspect.signature(bound).parameters.values() if p.name != "self"]
        except (TypeError, ValueError):
            continue
        own = table["overrides"].get(name, {})
        missing = [p.name for p in params if p.name not in table and p.name not in own]
        assert not missing, f"{owner}.{name}: no valid sample for {missing}; add one"
        valid = {p.name: sample(table, p.name, owner, name) for p in params}
        for p in params:
            yield f"{owner + '.' if owner else ''}{name}({p.name}=)", bound, valid, p.name


def test_every_argument_of_a_wrong_type_is_a_wrong_type_error(tmp_path: Path) -> None:
    checked = 0
    failures = []
    for label, target, valid, wrong in cases(tmp_path):
        try:
            target(**{**valid, wrong: WrongType()})
        except mazesim.WrongTypeError as error:
            if wrong not in str(error):
                failures.append(f"{label}: the message does not name {wrong!r}: {error}")
        except BaseException as error:  # noqa: BLE001 - any other exception is the failure
            failures.append(f"{label}: {type(error).__name__}: {error}")
        else:
            failures.append(f"{label}: accepted a WrongType()")
        checked += 1
    assert not failures, "\n".join(failures)
    assert checked >= 60


#: Methods whose valid call needs a movable body, which the sample world lacks
#: (tests/core/test_bodies.py calls them on a world with one).
NEEDS_A_BODY = {"Simulator.set_body_velocity"}


def test_the_valid_samples_are_accepted(tmp_path: Path) -> None:
    """The other half of the check above: with every argument valid, nothing is refused, so the
    errors above are the wrong-typed argument's doing."""
    seen = set()
    for label, target, valid, _ in cases(tmp_path):
        if label.split("(")[0] in seen:
            continue
        seen.add(label.split("(")[0])
        if label.split("(")[0] in NEEDS_A_BODY:
            # The sample world has no movable body: the valid call is refused for that alone.
            with pytest.raises(mazesim.InvalidArgumentError, match="world's 0 bodies"):
                target(**valid)
            continue
        target(**valid)
    assert len(seen) >= 20


@pytest.mark.parametrize("robot", [None, 3, b"e-puck"])
def test_simulator_robot_of_a_wrong_type(robot: Any) -> None:
    world = mazesim.World.builtin("seed-maze")
    with pytest.raises(
        mazesim.InvalidArgumentError, match=r"expected robot to be .*found (an? |None)"
    ):
        mazesim.Simulator(world, robot=robot)


def wrong_counts(
    target: Callable[..., Any], valid: dict[str, Any]
) -> Iterator[tuple[str, tuple[Any, ...], dict[str, Any]]]:
    """Calls of ``target`` with the wrong number of arguments: each required one left out, one
    positional value too many, and a keyword it does not know."""
    params = [p for p in inspect.signature(target).parameters.values() if p.name != "self"]
    for p in params:
        if p.default is p.empty:
            yield f"without {p.name}", (), {k: v for k, v in valid.items() if k != p.name}
    yield "with one value too many", (*(valid[p.name] for p in params), 0), {}
    yield "with an unknown keyword", (), {**valid, "not_a_parameter": 0}


def test_every_wrong_number_of_arguments_is_an_invalid_argument_error(tmp_path: Path) -> None:
    """pyo3 and CPython refuse a call with too many, too few or unknown arguments before the
    entry point runs; the refusal is ``InvalidArgumentError`` (a ``MazesimError``) with their
    message, never a bare ``TypeError``: for every constructor, function, method, static and
    class method of the extension, those without parameters included."""
    failures = []
    seen = set()
    for label, target, valid, _ in cases(tmp_path):
        entry = label.split("(")[0]
        if entry in seen:
            continue
        seen.add(entry)
        for how, args, kwargs in wrong_counts(target, valid):
            try:
                target(*args, **kwargs)
            except mazesim.InvalidArgumentError as error:
                if type(error).__name__ != "InvalidArgumentError" or not str(error):
                    failures.append(f"{entry} {how}: {type(error).__name__}: {error}")
            except BaseException as error:  # noqa: BLE001 - any other exception is the failure
                failures.append(f"{entry} {how}: {type(error).__name__}: {error}")
            else:
                failures.append(f"{entry} {how}: accepted")
    assert not failures, "\n".join(failures)
    assert len(seen) >= 20


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda w: mazesim.Simulator(w, 1, 2, 3, 4, 5), "takes from 1 to 5 positional"),
        (lambda w: mazesim.Simulator(), "missing 1 required positional argument: 'world'"),
        (lambda w: mazesim.Simulator(w, bogus=1), "unexpected keyword argument 'bogus'"),
        (lambda w: mazesim.Simulator(w).step(1.0), "missing 1 required positional argument"),
        (lambda w: mazesim.Simulator(w).snapshot(1), r"snapshot\(\) takes no arguments"),
        (lambda w: mazesim.builtin_world_names(w), r"builtin_world_names\(\) takes no arguments"),
        (lambda w: mazesim.World.builtin(), "missing 1 required positional argument: 'name'"),
        (lambda w: mazesim.Simulator.__new__(int), "expected the class Simulator"),
    ],
)
def test_a_wrong_number_of_arguments_names_what_was_expected(
    call: Callable[[Any], Any], message: str
) -> None:
    with pytest.raises(mazesim.InvalidArgumentError, match=message):
        call(mazesim.World.builtin("arena"))


def test_a_bound_method_and_a_valid_call_are_served_as_before() -> None:
    """The guard changes only a refused call: a method taken as a value refuses extra arguments
    the same way, and valid calls of every kind return as before."""
    world = mazesim.World.builtin("arena")
    simulator = mazesim.Simulator(world, seed=3)
    step, snapshot = simulator.step, simulator.snapshot
    with pytest.raises(mazesim.InvalidArgumentError, match="unexpected keyword"):
        step(1.0, 1.0, x=2)
    with pytest.raises(mazesim.InvalidArgumentError, match="takes no arguments"):
        snapshot(x=2)
    step(1.0, 1.0)
    other = mazesim.Simulator(world, seed=3)
    other.restore(core.Simulator.snapshot(simulator))
    assert other.pose == simulator.pose
    assert mazesim.World.builtin(name="arena").to_toml() == world.to_toml()


def test_a_typed_dict_parameter_is_checked_as_a_mapping() -> None:
    """``isinstance`` refuses a TypedDict; the check reads one as a mapping, so a wrong or a
    missing settings argument is the check's refusal, not a TypeError of typing's."""
    from mazesim._checks import checked
    from mazesim.webots.recognition import RecognitionSettings

    def takes(settings: RecognitionSettings, other: int = 0) -> int:
        return int(settings["robot_line"]) + other

    takes.__module__ = "mazesim.webots.recognition"
    check = checked(takes)
    with pytest.raises(mazesim.WrongTypeError, match="settings refused: expected a mapping"):
        check(1.5)
    with pytest.raises(mazesim.InvalidArgumentError, match="expected the argument 'settings'"):
        check(other=1)
    assert check({"robot_line": 2}, 1) == 3


def test_a_container_for_a_plain_value_is_refused_before_the_call() -> None:
    # numpy's SeedSequence recurses into a list given for a seed in C, without bound: a list
    # nested deep enough crashed the process (found by the fuzzed registry); any container
    # given where an int, a float, a bool or a text is annotated is refused before the call.
    from mazesim.benchmark.workloads import RandomWorkload

    deep: list[Any] = []
    for _ in range(100_000):
        deep = [deep]
    for given in (deep, [1, 2], (3,), {"seed": 1}, {1}):
        with pytest.raises(mazesim.WrongTypeError, match="seed refused: expected int"):
            RandomWorkload(4, seed=given)  # type: ignore[arg-type]
    assert RandomWorkload(4, seed=3).rng.random() == RandomWorkload(4, seed=3).rng.random()


def test_a_missing_argument_annotated_with_a_protocol_is_named() -> None:
    # The check looks among the given values for the missing one's class; a protocol that is
    # not runtime-checkable cannot be tested so (isinstance raised TypeError out of the check).
    from mazesim.webots.termination import Watchdog

    with pytest.raises(mazesim.InvalidArgumentError, match="expected the argument 'run'"):
        Watchdog(stop=KeyboardInterrupt, stall_seconds=1.0)  # type: ignore[call-arg]
