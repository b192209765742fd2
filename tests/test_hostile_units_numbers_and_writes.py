"""Hostile inputs of kinds the other hostile tests do not try: world sizes in the wrong unit
(centimetres or millimetres read as metres), duplicate keys and tables, tabs and carriage returns
in a map, negative zero, subnormals and huge integers in world fields, NaN and infinities in
every numeric field of every settings object, numpy scalars, 0-d arrays and booleans where
counts and seeds are expected, output buffers that are read-only, strided, of another dtype or
byte-swapped, snapshots truncated or corrupted, a full disk and Ctrl-C in the middle of a save,
and two threads sharing one simulator. Each ends in a result or a MazesimError that says what was
expected and what was found; a failed save leaves the old file whole and no temporary behind.
They run in this process (each takes milliseconds)."""

from __future__ import annotations

import errno
import inspect
import math
import os
import threading
from pathlib import Path
from typing import Any, Callable

import numpy as np
import pytest

import mazesim
import mazesim._sizes
import mazesim.learn
import mazesim.odometry
from mazesim import _atomic, _core
from mazesim.batch import RobotBatch
from mazesim.episodes import EpisodeBatch
from mazesim.learn.higher import HigherLearner, HigherLevel
from mazesim.learn.qlearning import LearningRate, batch_update, epsilon_greedy, greedy
from mazesim.maze import breadth_first_distances

WORLD = mazesim.load_world("seed-maze")
TOML = WORLD.to_toml()


def _grid(old: str, new: str) -> Callable[[], Any]:
    """Reads the seed maze's TOML with one line of it replaced."""
    assert old in TOML, old
    return lambda: mazesim.World.from_toml(TOML.replace(old, new, 1))


#: Worlds whose text is wrong: each must be refused with a WorldFormatError (or another
#: MazesimError) naming what was expected and what was found.
WORLD_TEXTS: dict[str, Callable[[], Any]] = {
    "cell_size_in_centimetres": _grid("cell_size = 0.25", "cell_size = 25"),
    "cell_size_in_millimetres": _grid("cell_size = 0.25", "cell_size = 250"),
    "cell_size_integer_centimetres_float": _grid("cell_size = 0.25", "cell_size = 25.0"),
    "wall_thickness_in_millimetres": _grid("wall_thickness = 0.01", "wall_thickness = 10"),
    "cell_size_negative_zero": _grid("cell_size = 0.25", "cell_size = -0.0"),
    "cell_size_subnormal": _grid("cell_size = 0.25", "cell_size = 5e-324"),
    "cell_size_nan": _grid("cell_size = 0.25", "cell_size = nan"),
    "cell_size_inf": _grid("cell_size = 0.25", "cell_size = inf"),
    "cell_size_huge_integer": _grid("cell_size = 0.25", "cell_size = 99999999999999999999"),
    "cell_size_bool": _grid("cell_size = 0.25", "cell_size = true"),
    "cell_size_twice": _grid("cell_size = 0.25", "cell_size = 0.25\ncell_size = 0.5"),
    "grid_table_twice": lambda: mazesim.World.from_toml(TOML + "\n[grid]\ncell_size = 0.5\n"),
    "floor_reflectance_nan": _grid("reflectance = 0.36", "reflectance = nan"),
    "floor_reflectance_negative_inf": _grid("reflectance = 0.36", "reflectance = -inf"),
    "floor_reflectance_subnormal_negative": _grid("reflectance = 0.36", "reflectance = -5e-324"),
    "version_huge_integer": _grid("version = 1", "version = 18446744073709551617"),
    "version_float": _grid("version = 1", "version = 1.0"),
    "version_negative_zero": _grid("version = 1", "version = -0"),
    "name_integer": _grid('name = "seed-maze"', "name = 7"),
    "origin_nan": _grid("origin = [\n    0.0,", "origin = [\n    nan,"),
    "map_with_tabs": _grid("|S             |", "|S\t\t\t\t\t\t\t\t\t\t\t\t\t|"),
    "map_with_carriage_returns_only": lambda: mazesim.World.from_toml(
        TOML.replace("+--+--+--+--+--+\n|  |", "+--+--+--+--+--+\r|  |", 1)
    ),
    "nul_inside_text": lambda: mazesim.World.from_toml(TOML.replace("seed-maze", "seed\x00maze")),
    "checkpoint_yaw_inf": _grid("yaw = 1.5707", "yaw = inf"),
    "checkpoint_width_negative_zero": _grid("width = 0.23", "width = -0.0"),
}


def _settings_cases() -> dict[str, Callable[[], Any]]:
    """Every numeric field of every settings object given NaN, an infinity and -0.0 where
    the field must be positive."""
    cases: dict[str, Callable[[], Any]] = {}
    classes = (
        mazesim.AvoidCollisionSettings,
        mazesim.DrivePerturbation,
        mazesim.SensingPerturbation,
        mazesim.MazeLayout,
    )
    for settings in classes:
        for each in inspect.signature(settings).parameters.values():
            default = each.default
            if isinstance(default, bool) or not isinstance(default, (int, float, tuple)):
                continue
            for label, bad in (("nan", math.nan), ("inf", math.inf)):
                value: Any = (bad,) * len(default) if isinstance(default, tuple) else bad
                cases[f"{settings.__name__}_{each.name}_{label}"] = (
                    lambda s=settings, n=each.name, v=value: s(**{n: v})
                )
    return cases


SETTINGS = _settings_cases()

#: Counts, seeds and steps given as values of the wrong kind.
NUMBERS: dict[str, Callable[[], Any]] = {
    "num_envs_bool": lambda: mazesim.BatchSimulator(WORLD, num_envs=True),
    "num_envs_one_element_array": lambda: mazesim.BatchSimulator(WORLD, num_envs=np.array([2])),
    "num_envs_float_numpy": lambda: mazesim.BatchSimulator(WORLD, num_envs=np.float64(2.5)),
    "seed_bool": lambda: mazesim.Simulator(WORLD, seed=True),
    "seed_numpy_negative": lambda: mazesim.Simulator(WORLD, seed=np.int64(-1)),
    "seed_past_u64": lambda: mazesim.Simulator(WORLD, seed=2**64),
    "seed_float_numpy": lambda: mazesim.Simulator(WORLD, seed=np.float32(1.5)),
    "control_step_nan": lambda: mazesim.Simulator(WORLD, control_step_ms=math.nan),
    "control_step_negative_zero": lambda: mazesim.Simulator(WORLD, control_step_ms=-0.0),
    "control_step_subnormal": lambda: mazesim.Simulator(WORLD, control_step_ms=5e-324),
    "max_steps_bool": lambda: mazesim.EpisodeLimits(max_steps=True),
    "max_steps_nan": lambda: mazesim.EpisodeLimits(max_steps=math.nan),
    "max_steps_float": lambda: mazesim.EpisodeLimits(max_steps=2.5),
    "wheel_speeds_nan": lambda: mazesim.Simulator(WORLD).set_wheel_speeds(math.nan, 1.0),
    "wheel_speeds_inf_right": lambda: mazesim.Simulator(WORLD).set_wheel_speeds(1.0, -math.inf),
    "layout_cell_size_in_centimetres": lambda: mazesim.MazeLayout(cell_size=25.0),
    "generated_cell_size_in_millimetres": lambda: mazesim.generate_maze(
        width=3, height=3, layout=mazesim.MazeLayout(cell_size=250.0)
    ),
    "set_pose_inf": lambda: mazesim.Simulator(WORLD).set_pose(math.inf, 0.1, 0.0),
    "generate_maze_bool": lambda: mazesim.generate_maze(width=True, height=3),
    "generate_maze_huge": lambda: mazesim.generate_maze(width=2**40, height=2**40),
}


def _batch() -> tuple[Any, tuple[Any, ...]]:
    batch = mazesim.BatchSimulator(WORLD, num_envs=2)
    return batch, batch.output_buffers()


def _step_into(change: Callable[[list[Any]], None]) -> None:
    batch, buffers = _batch()
    out = list(buffers)
    change(out)
    batch.step(np.zeros((2, 2), np.float32), *out)


def _read_only(out: list[Any]) -> None:
    out[0].flags.writeable = False


def _strided(out: list[Any]) -> None:
    out[0] = np.zeros((2, out[0].shape[1] * 2), np.float32)[:, ::2]


def _wrong_dtype(out: list[Any]) -> None:
    out[1] = out[1].astype(np.float64)


def _byte_swapped(out: list[Any]) -> None:
    out[1] = out[1].astype(out[1].dtype.newbyteorder())


def _wrong_rows(out: list[Any]) -> None:
    out[2] = np.zeros(3, bool)


def _aliased(out: list[Any]) -> None:
    out[1] = out[0][:, :3]


def _snapshot(cut: Callable[[bytes], bytes]) -> Callable[[], Any]:
    def run() -> None:
        sim = mazesim.Simulator(WORLD)
        sim.step(1.0, 1.0)
        data = sim.snapshot()
        sim.restore(cut(bytes(data)))

    return run


BUFFERS_AND_SNAPSHOTS: dict[str, Callable[[], Any]] = {
    "read_only_observations": lambda: _step_into(_read_only),
    "strided_observations": lambda: _step_into(_strided),
    "float64_poses": lambda: _step_into(_wrong_dtype),
    "byte_swapped_poses": lambda: _step_into(_byte_swapped),
    "colliding_of_other_length": lambda: _step_into(_wrong_rows),
    "poses_aliasing_observations": lambda: _step_into(_aliased),
    "snapshot_truncated": _snapshot(lambda b: b[: len(b) // 2]),
    "snapshot_empty": _snapshot(lambda b: b""),
    "snapshot_one_byte_flipped": _snapshot(lambda b: b[:8] + bytes([b[8] ^ 0xFF]) + b[9:]),
    "snapshot_doubled": _snapshot(lambda b: b + b),
    "snapshot_as_text": _snapshot(lambda b: b.hex()),  # type: ignore[arg-type, return-value]
}


def _bounds(low: float, high: float) -> tuple[Any, Any]:
    """Bounds of the seed maze robot's 11 readings, every pair ``low``..``high``."""
    return np.full(11, low, np.float32), np.full(11, high, np.float32)


#: Values that were taken without a word and gave a result nobody asked for: an angle of
#: infinity wrapped to NaN (None read as NaN), clamp bounds with low above high that clamped
#: every reading to high, a level of 1.7 cut to 1.
SILENT: dict[str, Callable[[], Any]] = {
    "wrap_angle_inf": lambda: mazesim.odometry.wrap_angle([0.5, math.inf]),
    "wrap_angle_none": lambda: mazesim.odometry.wrap_angle(None),  # type: ignore[arg-type]
    "step_observe_low_above_high": lambda: mazesim.Simulator(WORLD).step_observe(
        1.0, 1.0, *_bounds(1.0, 0.0)
    ),
    "step_observe_nan_bound": lambda: mazesim.Simulator(WORLD).step_observe(
        1.0, 1.0, *_bounds(math.nan, 1.0)
    ),
    "step_bounds_low_above_high": lambda: _core.StepBounds(*_bounds(5.0, -5.0), 6.28),
    "encode_state_fraction": lambda: mazesim.learn.encode_state([1.7, 0, 0, 0, 0, 0]),
    "decode_state_fraction": lambda: mazesim.learn.decode_state(4.9),
    # Indices: numpy cut 1.5 to 1 and took -1 as the last row, action, world or robot.
    "greedy_negative_state": lambda: greedy(np.zeros((4, 3)), [-1]),
    "epsilon_greedy_fractional_state": lambda: epsilon_greedy(
        np.zeros((4, 3)), [1.5], 0.0, np.random.default_rng(0)
    ),
    "batch_update_fractional_action": lambda: batch_update(
        np.zeros((4, 3)),
        np.zeros((4, 3), np.int64),
        [0],
        [0.5],
        [1.0],
        [0],
        0.0,
        LearningRate(),
    ),
    "robot_batch_fractional_world": lambda: RobotBatch([WORLD], [0.5]),
    "robot_batch_negative_action": lambda: RobotBatch([WORLD], [0]).speeds_of([-1]),
    "robot_batch_place_fractional_env": lambda: RobotBatch([WORLD], [0, 0]).place(
        [0.5], [WORLD.start], [0]
    ),
    "breadth_first_source_off_the_grid": lambda: breadth_first_distances(
        np.ones((1, 2, 3, 4), bool), np.array([[0, -1]])
    ),
    # Seeds: numpy wrapped an int64 -1 to 2**64 - 1 and cut 1.5 to 1.
    "robot_batch_reset_negative_seed": lambda: RobotBatch([WORLD], [0]).reset(seeds=np.array([-1])),
    "robot_batch_place_fractional_seed": lambda: RobotBatch([WORLD], [0]).place(
        [0], [WORLD.start], [1.5]
    ),
    "higher_level_fractional_world": lambda: HigherLevel([[1, 2]]).states([0.5], [1]),
    "higher_learner_negative_option": lambda: HigherLearner(HigherLevel([[1, 2]]), 2).decide(
        [0], [0], [-1]
    ),
    "higher_learner_forget_fractional_env": lambda: HigherLearner(HigherLevel([[1, 2]]), 2).forget(
        [1.5]
    ),
    "episode_batch_start_negative_env": lambda: EpisodeBatch([WORLD]).start([-1], [0]),
}

REFUSED: dict[str, Callable[[], Any]] = {
    **WORLD_TEXTS,
    **SETTINGS,
    **NUMBERS,
    **BUFFERS_AND_SNAPSHOTS,
    **SILENT,
}


def test_seeds_up_to_two_to_the_64_beside_small_ones_are_taken_exactly() -> None:
    # numpy reads [2**64 - 1, 0] as floats (2**64 - 1 rounding up to 2**64); the seed check
    # takes the Python ints as they are.
    batch = RobotBatch([WORLD], [0, 0])
    batch.reset(seeds=[2**64 - 1, 0])
    assert mazesim._sizes.seed_array([2**64 - 1, 0], "seeds", 2).tolist() == [2**64 - 1, 0]
    # Too many seeds are refused by the bound's own words, once (not wrapped in the seed check's).
    with pytest.raises(mazesim.InvalidArgumentError) as raised:
        mazesim._sizes.seed_array(range(10), "seeds", 3)
    assert str(raised.value) == "expected seeds to hold at most 3 values, found 10 (a range)"


@pytest.mark.parametrize("case", sorted(REFUSED))
def test_a_hostile_value_is_refused_saying_what_was_expected(case: str) -> None:
    with pytest.raises(mazesim.MazesimError) as raised:
        REFUSED[case]()
    message = str(raised.value).lower()
    assert any(word in message for word in ("expected", "must", "duplicate")), message


@pytest.mark.parametrize(
    ("line", "field", "shown"),
    [
        ("cell_size = 1e300", "grid.cell_size", "1e300"),
        ("cell_size = 1e-300", "grid.wall_thickness", "1e-300"),  # the wall is the thicker
    ],
)
def test_a_grid_size_refused_is_named_and_shown_as_written(
    line: str, field: str, shown: str
) -> None:
    # A huge cell size was reported under grid.wall_thickness, a tiny one with hundreds of zeros.
    with pytest.raises(mazesim.WorldFormatError) as raised:
        _grid("cell_size = 0.25", line)()
    message = str(raised.value)
    assert f"`{field}`" in message and shown in message and "0.0000" not in message, message


def test_an_output_overlapping_another_is_said_to_share_its_memory() -> None:
    # The refusal read "expected ..., writable and not borrowed elsewhere, found an ndarray of
    # dtype float32 and shape (2, 3)": what was found looked like what was expected.
    def overlapping(out: list[Any]) -> None:
        out[1] = out[0].reshape(-1)[: out[1].size].reshape(out[1].shape)  # contiguous, aligned

    with pytest.raises(mazesim.InvalidArgumentError, match="sharing memory with another argument"):
        _step_into(overlapping)


def _write(path: Path, fail: BaseException) -> None:
    """Writes ``path`` through the atomic writer while the writes of the disk fail with
    ``fail`` once half the content is written."""
    with _atomic.atomic_file(path) as out:
        out.write(b"x" * 10)
        out.flush()
        raise fail


def _disk_full_in_write(path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    real = os.fsync

    def full(descriptor: int) -> None:
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(os, "fsync", full)
    try:
        with _atomic.atomic_file(path) as out:
            out.write(b"new content")
    finally:
        monkeypatch.setattr(os, "fsync", real)


def test_a_full_disk_in_the_middle_of_a_save_keeps_the_old_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    target = tmp_path / "table.json"
    target.write_bytes(b"old")
    with pytest.raises(mazesim.MazesimIOError) as raised:
        _disk_full_in_write(target, monkeypatch)
    assert "No space" in str(raised.value) and str(target) in str(raised.value)
    assert target.read_bytes() == b"old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["table.json"]


def test_ctrl_c_in_the_middle_of_a_save_keeps_the_old_file(tmp_path: Path) -> None:
    target = tmp_path / "table.json"
    target.write_bytes(b"old")
    with pytest.raises(KeyboardInterrupt):
        _write(target, KeyboardInterrupt())
    assert target.read_bytes() == b"old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["table.json"]


def test_a_full_disk_saving_a_world_through_a_stream_is_an_io_error(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    reader = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)
    try:

        def full(descriptor: int, data: Any) -> int:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

        monkeypatch.setattr(os, "write", full)
        with pytest.raises(mazesim.MazesimIOError) as raised:
            with _atomic.atomic_file(fifo) as out:
                out.write(b"content")
        assert "No space" in str(raised.value)
    finally:
        os.close(reader)


def test_two_threads_stepping_one_simulator_end_whole_or_busy() -> None:
    sim = mazesim.Simulator(WORLD, noise=False)
    alone = mazesim.Simulator(WORLD, noise=False)
    outcomes: list[str] = []

    def drive() -> None:
        for _ in range(200):
            try:
                sim.step(2.0, 2.0)
                outcomes.append("stepped")
            except mazesim.SimulatorBusyError:
                outcomes.append("busy")

    threads = [threading.Thread(target=drive) for _ in range(2)]
    for each in threads:
        each.start()
    for each in threads:
        each.join()
    stepped = outcomes.count("stepped")
    assert stepped + outcomes.count("busy") == 400
    for _ in range(stepped):
        alone.step(2.0, 2.0)
    assert sim.steps == stepped
    assert sim.pose == alone.pose


def test_a_world_saved_into_a_folder_path_or_a_nul_path_is_refused(tmp_path: Path) -> None:
    for bad in (str(tmp_path), str(tmp_path / "a\x00b.toml")):
        with pytest.raises(mazesim.MazesimError) as raised:
            WORLD.save(bad)
        assert "expected" in str(raised.value).lower() or "folder" in str(raised.value)


def test_a_wheel_command_not_finite_is_refused_when_given() -> None:
    sim = mazesim.Simulator(WORLD, noise=False)
    sim.set_wheel_speeds(1.0, 2.0)
    with pytest.raises(mazesim.InvalidActionError, match="expected finite wheel speeds"):
        sim.set_wheel_speeds(math.nan, 1.0)
    with pytest.raises(mazesim.InvalidActionError, match=r"found \(NaN, 1\)"):
        sim.step(math.nan, 1.0)
    assert sim.steps == 0
    sim.step(1.0, 2.0)
    assert sim.steps == 1


@pytest.mark.parametrize(
    ("field", "value", "named"),
    [("axle_length", "1e-300", "axle_length"), ("wheel_radius", "1e9", "wheel_radius")],
)
def test_a_profile_too_fast_names_the_field_that_makes_it_so(
    field: str, value: str, named: str
) -> None:
    # A top turn rate beyond the physics comes of a short axle: the refusal names that field
    # (it named wheel_radius, whose value was the e-puck's own).
    text = mazesim.RobotProfile.builtin("e-puck").to_toml()
    lines = [
        f"{field} = {value}" if line.startswith(f"{field} =") else line
        for line in text.splitlines()
    ]
    with pytest.raises(mazesim.WorldFormatError) as raised:
        mazesim.RobotProfile.from_toml("\n".join(lines))
    assert raised.value.field == named, str(raised.value)


def test_a_maze_of_ten_metre_cells_is_still_taken() -> None:
    layout = mazesim.MazeLayout(cell_size=10.0)
    assert layout.cell_size == 10.0


def _python_side_numbers() -> list[tuple[str, Callable[[], object]]]:
    """Numbers the Python side takes itself (not through the core's ranges), each given a value
    its arithmetic cannot use, with the parameter the refusal must name (NaN and infinities given
    from outside are refused by the surface before these checks, tests/test_nan_arguments.py)."""
    from mazesim.actions import wheel_speeds
    from mazesim.batch import cruise_step_length
    from mazesim.controllers import AvoidCollision, Explore
    from mazesim.episodes import StartJitter, shortest_path_steps
    from mazesim.sensor_rays import SensorRays

    world = mazesim.load_world("seed-maze")
    robot = mazesim.RobotProfile.builtin("seed")
    return [
        ("control_step_ms", lambda: shortest_path_steps(world, 0.0)),
        ("control_step_ms", lambda: cruise_step_length(robot, math.inf)),
        ("position", lambda: StartJitter(position=-1.0)),
        ("yaw", lambda: StartJitter(yaw=math.inf)),
        ("threshold", lambda: AvoidCollision(threshold=math.inf)),
        ("turn", lambda: Explore(turn=-math.inf)),
        ("max_speed", lambda: wheel_speeds("00", math.inf)),
        ("ray_length", lambda: SensorRays(world, robot, -1.0)),
    ]


@pytest.mark.parametrize("index", range(8))
def test_a_python_side_number_is_refused_naming_it_before_any_arithmetic(index: int) -> None:
    # shortest_path_steps(world, 0.0) divided by zero: an InternalError asking for a report.
    name, call = _python_side_numbers()[index]
    words = f"expected {name} to be a finite|{name} refused: expected a finite number"
    with pytest.raises(mazesim.InvalidArgumentError, match=words):
        call()


@pytest.mark.parametrize(
    ("call", "written"),
    [
        (
            lambda: mazesim.Simulator(mazesim.load_world("seed-maze"), control_step_ms=1e300),
            "1e+300",
        ),
        (
            lambda: mazesim.Simulator(mazesim.load_world("seed-maze"), control_step_ms=1e-300),
            "1e-300",
        ),
        (lambda: mazesim.RobotProfile.builtin("e-puck").with_infrared_elevation(1e308), "1e+308"),
    ],
)
def test_the_cores_messages_write_a_huge_or_tiny_number_as_python_does(
    call: Callable[[], object], written: str
) -> None:
    # Rust's `{}` of an f64 wrote 1e300 as 301 digits and 1e-300 as 0.000...0001.
    with pytest.raises(mazesim.InvalidArgumentError) as refused:
        call()
    message = str(refused.value)
    assert f"found {written}" in message and "00000000000000000000" not in message


def test_numpy_integers_are_ints_everywhere_and_numpy_bools_no_ints() -> None:
    # BatchSimulator(seeds=np.int64(2)) was refused while Simulator(seed=np.int64(2)) was taken;
    # CodeBook ids read from an array (np.int64) were refused; np.True_ passed for an int.
    from mazesim.barcode import Alg7Decoder, CodeBook

    world = mazesim.load_world("seed-maze")
    batch = mazesim.BatchSimulator(world, num_envs=2, seeds=np.int64(2))
    plain = mazesim.BatchSimulator(world, num_envs=2, seeds=2)
    assert batch.snapshot_env(1) == plain.snapshot_env(1)
    assert CodeBook({np.int64(1): "10110"}).code(1) == "10110"
    with pytest.raises(mazesim.InvalidArgumentError, match="positive integers"):
        CodeBook({np.True_: "10110"})
    with pytest.raises(mazesim.WrongTypeError, match="max_samples refused: expected int"):
        Alg7Decoder(CodeBook.default(), max_samples=np.True_)  # type: ignore[arg-type]


def test_one_off_refusals_say_what_was_wrong(tmp_path: Path) -> None:
    # Each named the wrong thing or said what was found as if it were what was expected.
    from mazesim.cli import main
    from mazesim.replay import save_run
    from mazesim.replay.run import RecordedRun
    from mazesim.transfer.randomise import parse_spec

    with pytest.raises(mazesim.InvalidArgumentError, match=r"^expected floor_reflectance in"):
        mazesim.MazeLayout(floor_reflectance=math.nan)
    simulator = mazesim.Simulator(mazesim.load_world("seed-maze"))
    with pytest.raises(mazesim.InvalidArgumentError, match=r"found a list$"):
        simulator.step_robots([[1.0, 1.0]])
    with pytest.raises(mazesim.InvalidArgumentError, match="the range of wheel_radius as finite"):
        parse_spec("wheel_radius=nan:1")
    empty = RecordedRun(
        world=mazesim.load_world("arena"),
        robot="seed",
        controller="x",
        seed=0,
        control_step_ms=64.0,
    )
    save_run(empty, tmp_path / "none.json")
    code = main(["replay", str(tmp_path / "none.json"), "-o", str(tmp_path / "p.html")])
    assert code == 2
