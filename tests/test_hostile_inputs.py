"""Hostile and careless input (issue #15): each case runs in a fresh process under a 4 GiB
address-space cap and 120 s, and must end in a correct result or a MazesimError: no abort, no
PanicException, no other exception, no hang, no memory blow-up."""

from __future__ import annotations

import multiprocessing
import os
import random
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mazesim
from hostile import run_hostile
from mazesim import _core
from mazesim.errors import _with_article

#: One case per class of the issue: a name saying what broke, and the statements that broke it.
CASES = {
    "wall_far_from_origin": "_core.World.from_toml(HEADER + wall(1e20))",
    "wall_at_1e39": "_core.World.from_toml(HEADER + wall(1e39))",
    "yaw_of_3_5e38": "_core.World.from_toml(HEADER + wall(0.3, yaw=3.5e38))",
    "large_walls": (
        "_core.World.from_toml(HEADER + ''.join(wall(i * 1e-3, 0, 1000.0, 1000.0)"
        " for i in range(1000)))"
    ),
    "paint_rectangles_16400": (
        "text = HEADER + ''.join('[[paint]]\\nshape = \"rect\"\\ncenter = [0.0, 0.0]\\n"
        "size = [100.0, 100.0]\\nreflectance = 0.5\\n' for _ in range(16400))\n"
        "w = _core.World.from_toml(text)\n"
        "assert w.floor_reflectance(0.0, 0.0) == 0.5"
    ),
    "coincident_walls_30000": (
        "s = _core.Simulator(_core.World.from_toml(HEADER + wall(0.2) * 30000))\n"
        "for _ in range(60):\n    s.step(6.0, 6.0)\n"
        "assert s.collisions >= 1 and s.pose[0] < 0.2"
    ),
    "num_envs_million": "_core.BatchSimulator(_core.World.builtin('arena'), num_envs=10**6)",
    "num_envs_huge": "_core.BatchSimulator(_core.World.builtin('arena'), num_envs=10**15)",
    "num_envs_2_70": "_core.BatchSimulator(_core.World.builtin('arena'), num_envs=2**70)",
    "vector_env_num_envs_billion": (
        "import gymnasium\ngymnasium.make_vec('mazesim/EPuckMaze-v0', num_envs=10**9)"
    ),
    "threads_unbounded": (
        "_core.BatchSimulator(_core.World.builtin('arena'), num_envs=2, threads=10**9)"
    ),
    "control_step_32e9": "_core.Simulator(_core.World.builtin('arena'), control_step_ms=32e9)",
    "basic_time_step_tiny": (
        "_core.World.from_toml(HEADER + 'basic_time_step_ms = 1e-9\\n' + wall(0.3))"
    ),
    "start_1e39": "s = _core.Simulator(_core.World.builtin('arena'))\ns.set_start(1e39, 0, 0)",
    "pose_yaw_3_5e38": (
        "s = _core.Simulator(_core.World.builtin('arena'))\ns.set_pose(0, 0, 3.5e38)"
    ),
    "start_inside_wall": (
        "w = _core.World.from_toml(HEADER + wall(0.0, 0.0, 0.5, 0.5) + wall(2.0))\n"
        "_core.Simulator(w)"
    ),
    "maze_origin_1e5": (
        "_core.World.from_toml(HEADER + '[grid]\\ncell_size = 0.25\\nwall_thickness = 0.01\\n"
        'origin = [1e5, 1e5]\\nmap = """\\n+--+\\n|S |\\n+--+\\n"""\\n\')'
    ),
    "sharp_volts_nan": "_core.sharp_volts_to_cm(float('nan'))",
    "seed_2_70": "_core.Simulator(_core.World.builtin('arena'), seed=2**70)",
    "set_world_index_2_70": (
        "b = _core.BatchSimulator(_core.World.builtin('arena'), num_envs=2)\n"
        "b.set_world(2**70, _core.World.builtin('arena'), 0)"
    ),
    "unaligned_actions": (
        "b = _core.BatchSimulator(_core.World.builtin('arena'), num_envs=4)\n"
        "a = np.zeros(33, np.uint8)[1:].view(np.float32).reshape(4, 2)\n"
        "b.step(a, *buffers(b))"
    ),
    "non_contiguous_actions": (
        "b = _core.BatchSimulator(_core.World.builtin('arena'), num_envs=4)\n"
        "b.step(np.zeros((4, 4), np.float32)[:, ::2], *buffers(b))"
    ),
    "read_only_output": (
        "b = _core.BatchSimulator(_core.World.builtin('arena'), num_envs=4)\n"
        "obs, poses, col, cr = buffers(b)\nposes.flags.writeable = False\n"
        "b.step(np.zeros((4, 2), np.float32), obs, poses, col, cr)"
    ),
    "wrong_dtype_output": (
        "b = _core.BatchSimulator(_core.World.builtin('arena'), num_envs=4)\n"
        "obs, poses, col, cr = buffers(b)\n"
        "b.step(np.zeros((4, 2), np.float32), obs.astype(np.float64), poses, col, cr)"
    ),
    "same_output_twice": (
        "b = _core.BatchSimulator(_core.World.builtin('arena'), num_envs=3)\n"
        "obs = np.zeros((3, 3), np.float32)\n"
        "b.step(np.zeros((3, 2), np.float32), np.zeros((3, b.observation_width), np.float32),"
        " obs, np.zeros(3, bool), np.zeros(3, np.int32))\n"
        "b.observe(obs, obs, np.zeros(3, bool), np.zeros(3, np.int32))"
    ),
    "wbt_def_use_explosion": (
        "t = '#VRML_SIM R2023b utf8\\n'\n"
        "t += 'DEF A0 Solid { boundingObject Box { size 0.1 0.1 0.1 } }\\n'\n"
        "t += ''.join(f'DEF A{i} Group {{ children [ USE A{i-1} USE A{i-1} ] }}\\n'"
        " for i in range(1, 40))\n"
        "_core.import_wbt_text(t)"
    ),
    "missing_world_file": "_core.World.load('/nonexistent/world.toml')",
    "perturbed_to_a_runaway_robot": (
        "p = _core.RobotProfile.builtin('seed')\n"
        "faster = _core.DrivePerturbation(wheel_radius_scale=10.0)\n"
        "for _ in range(400):\n    p = p.perturbed(faster)\n"
        "s = _core.Simulator(_core.World.builtin('arena'), robot=p)\ns.step(6.0, 6.0)"
    ),
    "profile_of_huge_wheels": (
        "t = _core.RobotProfile.builtin('seed').to_toml()\n"
        "t = t.replace('wheel_radius = 0.0205', 'wheel_radius = 1e298')\n"
        "s = _core.Simulator(_core.World.builtin('arena'), robot=_core.RobotProfile.from_toml(t))\n"
        "s.step(6.0, 6.0)"
    ),
    "perturbed_offset_1e300": (
        "_core.RobotProfile.builtin('seed').perturbed("
        "sensing=_core.SensingPerturbation(ir_offset_error=1e300))"
    ),
    "robot_list_of_other_things": (
        "_core.BatchSimulator(_core.World.builtin('arena'), num_envs=2, robot=[None, b'x'])"
    ),
    # Endless files: each reader stops at its size bound instead of filling the memory.
    "world_file_dev_zero": "_core.World.load('/dev/zero')",
    "wbt_file_dev_zero": "_core.import_wbt('/dev/zero')",
    "sweep_file_dev_zero": (
        "from mazesim.distributed.config import load_sweep_config\nload_sweep_config('/dev/zero')"
    ),
    "key_script_dev_zero": "from mazesim.webots.keyboard import read_keys\nread_keys('/dev/zero')",
    "run_file_dev_zero": "from mazesim.replay import load_run\nload_run('/dev/zero')",
    # Counts the command line allows (up to 2^31 - 1) that made a world or a maze per unit
    # before any check: the process aborted in the core, or the system killed it.
    "barcode_study_envs_2_31": (
        "from mazesim.barcode.study import run_setting\n"
        "run_setting(_core.World.builtin('seed-maze'), 1.4, 3.0, readings=1, envs=2**31 - 1)"
    ),
    "unseen_mazes_2_31": (
        "from mazesim.learn.evaluate import unseen_mazes\nunseen_mazes(2**31 - 1, 0)"
    ),
    "bench_distinct_mazes_2_31": (
        "from mazesim.benchmark.steady import BenchSettings, SteadyState\n"
        "SteadyState(BenchSettings(envs=2**31 - 1))"
    ),
    # Text where a number is expected: numpy (and float()) read "3" as one, so the call did not
    # fail and its arguments were never checked.
    "text_for_an_angle": "from mazesim.odometry import wrap_angle\nwrap_angle('3')",
    # Texts given in memory, beyond the bound of the file each stands for: the parser asked for
    # more memory than the process may have (an abort), or parsed for minutes. Each is just past
    # the bound (64 MiB, 256 MiB for a .wbt) and refused by it before it is parsed
    # (BOUND_REFUSALS): a text ten times as long crosses the same check and only costs more.
    "world_text_of_a_3400_by_3400_maze": (
        "row = '+' + '--+' * 3400 + '\\n'\nmiddle = '|' + '  |' * 3400 + '\\n'\n"
        "_core.World.from_toml(HEADER + '[grid]\\ncell_size = 0.25\\nwall_thickness = 0.01\\n"
        'map = """\\n\' + (row + middle) * 3400 + row + \'"""\\n\')'
    ),
    "world_text_of_34_million_numbers": (
        "_core.World.from_toml(HEADER + 'x = [' + '0,' * 34_000_000 + ']\\n')"
    ),
    "profile_text_past_its_bound": (
        "text = _core.RobotProfile.builtin('seed').to_toml()\n"
        "_core.RobotProfile.from_toml(text + '#' * (64 << 20))"
    ),
    # More tables than a world within the limits has: parsed for seconds (a minute for a text
    # near the byte bound) before the wall count refused it.
    "world_text_of_300000_inline_walls": (
        "_core.World.from_toml(HEADER + 'walls = [' + '{center=[0,0],size=[1,1]},' * 300_000"
        " + ']\\n')"
    ),
    # A field value that is no number, taken for the next field's name.
    "wbt_box_size_nan": (
        "_core.import_wbt_text('#VRML_SIM R2023b utf8\\n"
        "Solid { boundingObject Box { size -1 1e300 nan } }\\n')"
    ),
    "wbt_text_of_27_million_nodes": (
        "_core.import_wbt_text('#VRML_SIM R2023b utf8\\nE-puck { }\\nGroup { children [ '"
        " + 'Group { } ' * 27_000_000 + ' ] }\\n')"
    ),
    # A frame field short of numbers: Webots reads the next field's name as the missing number
    # and refuses the world; the import warned and put the Solid at the origin.
    "wbt_translation_of_two_numbers": (
        "_core.import_wbt_text('#VRML_SIM R2023b utf8\\n"
        "Solid { translation 1 2 rotation 0 0 1 0 }\\n')"
    ),
    # An array of the right dtype and shape but a strided view: "expected X, found X".
    "strided_actions_of_the_right_shape": (
        "b = _core.BatchSimulator(_core.World.builtin('arena'), num_envs=2)\n"
        "obs, poses, col, cr = buffers(b)\nb.step(poses[:, :2], obs, poses, col, cr)"
    ),
}

#: What the texts past the bound of their file are refused with: the bound, before any parsing.
BOUND_REFUSALS = {
    "world_text_of_a_3400_by_3400_maze": "at most 67108864 bytes",
    "world_text_of_34_million_numbers": "at most 67108864 bytes",
    "profile_text_past_its_bound": "at most 67108864 bytes",
    "wbt_text_of_27_million_nodes": "at most 268435456 bytes",
    "world_text_of_300000_inline_walls": "at most 211069 tables",
}

#: What other refusals say: the field and what was found, not a misreading of the input.
REFUSALS_SAY = {
    **BOUND_REFUSALS,
    "wbt_box_size_nan": (
        ":2:44: field `Solid.boundingObject.Box.size`: expected the field `size` to hold finite"
        " numbers, found `nan`"
    ),
    "wbt_translation_of_two_numbers": (
        ":2:25: field `Solid.translation`: expected the field `translation` to hold 3 numbers,"
        " found 2, then `rotation`"
    ),
    "strided_actions_of_the_right_shape": (
        "found an ndarray of dtype float32 and shape (2, 2), not C-contiguous"
    ),
}


#: The cases that gave silent nonsense (inf poses, a frozen robot, 40 cm from NaN) and must now be
#: refused, not merely survived.
MUST_BE_REFUSED = {
    "vector_env_num_envs_billion",
    "wall_far_from_origin",
    "wall_at_1e39",
    "yaw_of_3_5e38",
    "num_envs_million",
    "threads_unbounded",
    "control_step_32e9",
    "basic_time_step_tiny",
    "start_1e39",
    "pose_yaw_3_5e38",
    "start_inside_wall",
    "maze_origin_1e5",
    "sharp_volts_nan",
    "seed_2_70",
    "unaligned_actions",
    "same_output_twice",
    "wbt_def_use_explosion",
    "missing_world_file",
    "perturbed_to_a_runaway_robot",
    "profile_of_huge_wheels",
    "perturbed_offset_1e300",
    "robot_list_of_other_things",
    "world_file_dev_zero",
    "wbt_file_dev_zero",
    "sweep_file_dev_zero",
    "key_script_dev_zero",
    "run_file_dev_zero",
    "barcode_study_envs_2_31",
    "unseen_mazes_2_31",
    "bench_distinct_mazes_2_31",
    "text_for_an_angle",
    *REFUSALS_SAY,
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_hostile_input_ends_in_a_mazesim_error_or_a_result(name: str) -> None:
    outcome = run_hostile(CASES[name])
    assert outcome.ok, f"{name}: {outcome.describe()}"
    if name in MUST_BE_REFUSED:
        assert outcome.refused, f"{name} was accepted: {outcome.describe()}"
    if name in REFUSALS_SAY:
        assert REFUSALS_SAY[name] in outcome.stdout, outcome.describe()


#: Numbers that break careless code: huge, tiny, negative, not finite.
HOSTILE_NUMBERS = [
    "0.0",
    "-0.0",
    "1e-300",
    "-1e300",
    "1e39",
    "3.5e38",
    "1e20",
    "999.99",
    "-1000.0001",
    "nan",
    "inf",
    "-inf",
    "1e5",
    "4294967296.0",
    "0.25",
    "-3.0",
]


def _mutated_world(rng: random.Random) -> str:
    """A world file of a few walls, paint, a checkpoint and a start, with hostile numbers."""

    def number() -> str:
        return rng.choice(HOSTILE_NUMBERS) if rng.random() < 0.5 else repr(rng.uniform(-2, 2))

    def positive() -> str:
        return rng.choice(["1e-300", "1e39", "2000.0", "0.1", "1e20"])

    parts = [f"basic_time_step_ms = {rng.choice(['32.0', '1e-9', '1e12', '0.1', '8'])}\n"]
    for _ in range(rng.randint(0, 4)):
        parts.append(
            f"[[walls]]\ncenter = [{number()}, {number()}]\nsize = [{positive()}, {positive()}]\n"
            f"yaw = {number()}\n"
        )
    for _ in range(rng.randint(0, 2)):
        parts.append(
            f'[[paint]]\nshape = "rect"\ncenter = [{number()}, {number()}]\n'
            f"size = [{positive()}, {positive()}]\nreflectance = 0.5\n"
        )
    if rng.random() < 0.5:
        parts.append(
            f'[[checkpoints]]\nid = 1\ncode = "10110"\ncenter = [{number()}, {number()}]\n'
            f"yaw = {number()}\nwidth = {positive()}\n"
        )
    parts.insert(1, f"[start]\nx = {number()}\ny = {number()}\nyaw = {number()}\n")
    return "".join(parts)


@pytest.mark.parametrize("seed", range(6))
def test_mutated_worlds_end_in_a_mazesim_error_or_a_result(seed: int) -> None:
    rng = random.Random(seed)
    worlds = [_mutated_world(rng) for _ in range(25)]
    body = (
        f"for text in {worlds!r}:\n"
        "    try:\n"
        "        w = _core.World.from_toml(HEADER + text)\n"
        "        s = _core.Simulator(w, control_step_ms=w.basic_time_step_ms * 2)\n"
        "        s.step(6.0, 5.0)\n"
        "        assert all(np.isfinite(s.pose)), s.pose\n"
        "        b = _core.BatchSimulator(w, num_envs=3, threads=2)\n"
        "        b.step(np.full((3, 2), 3.0, np.float32), *buffers(b))\n"
        "    except mazesim.MazesimError:\n"
        "        pass\n"
    )
    outcome = run_hostile(body)
    assert outcome.ok, outcome.describe()


def test_a_panic_is_an_internal_error() -> None:
    for on_helper_thread in (False, True):
        with pytest.raises(mazesim.InternalError, match="internal error, please report: boom"):
            _core._panic_for_tests("boom", on_helper_thread=on_helper_thread)


def test_io_errors_keep_errno_and_reason(tmp_path: object) -> None:
    with pytest.raises(mazesim.MazesimIOError) as caught:
        _core.World.load("/nonexistent/world.toml")
    assert caught.value.errno == 2
    assert caught.value.strerror == "No such file or directory"
    assert caught.value.filename == "/nonexistent/world.toml"
    assert "No such file or directory" in str(caught.value)
    assert "None" not in str(caught.value)


def test_set_starts_applies_no_row_when_one_is_bad() -> None:
    batch = _core.BatchSimulator(_core.World.builtin("arena"), num_envs=2)
    buffers = (
        np.zeros((2, batch.observation_width), np.float32),
        np.zeros((2, 3), np.float32),
        np.zeros(2, bool),
        np.zeros(2, np.int32),
    )
    with pytest.raises(mazesim.InvalidArgumentError, match="environment 1"):
        batch.set_starts(np.array([[0.1, 0.1, 0.0], [1e39, 0.0, 0.0]]))
    batch.reset(*buffers)
    start = _core.World.builtin("arena").start
    np.testing.assert_allclose(buffers[1][0], start, atol=1e-6)


def test_reset_with_its_own_output_as_mask_works() -> None:
    batch = _core.BatchSimulator(_core.World.builtin("arena"), num_envs=4)
    obs = np.zeros((4, batch.observation_width), np.float32)
    poses = np.zeros((4, 3), np.float32)
    colliding = np.array([True, False, True, False])
    crossings = np.zeros(4, np.int32)
    poses[:] = 9.0
    batch.reset(obs, poses, colliding, crossings, mask=colliding)
    assert (poses[[1, 3]] == 9.0).all()
    assert (poses[[0, 2]] != 9.0).all()


def test_large_integers_and_non_numbers_are_invalid_arguments() -> None:
    world = _core.World.builtin("arena")
    for call in (
        lambda: _core.Simulator(world, seed=2**70),
        lambda: _core.Simulator(world, seed=-1),
        lambda: _core.BatchSimulator(world, num_envs=2**64),
        lambda: _core.BatchSimulator(world, num_envs=2, threads=2**70),
        lambda: _core.BatchSimulator(world, num_envs=2, seeds=[0, 2**64]),
        lambda: _core.generate_maze(width=2**80),
        lambda: _core.MazeLayout(cell_size=10**400),
        lambda: _core.Simulator(world, control_step_ms=10**400),
        lambda: _core.Simulator(world).set_start(10**400, 0.0, 0.0),
        lambda: _core.Simulator(world).step("fast", 1.0),  # type: ignore[arg-type]
        lambda: _core.sharp_volts_to_cm(-(10**400)),
    ):
        with pytest.raises(mazesim.InvalidArgumentError):
            call()
    with pytest.raises(mazesim.InvalidActionError):
        _core.Simulator(world).step(10**400, 0.0)


def _step_a_batch_in_a_child(_: int) -> float:
    batch = _core.BatchSimulator(_core.World.builtin("seed-maze"), num_envs=64)
    obs = np.zeros((64, batch.observation_width), np.float32)
    out = (obs, np.zeros((64, 3), np.float32), np.zeros(64, bool), np.zeros(64, np.int32))
    batch.reset(*out)
    for _ in range(5):
        batch.step(np.full((64, 2), 4.0, np.float32), *out)
    return float(out[1][:, 0].sum())


# Python 3.12+ warns that forking a process with threads may deadlock: the fork guard is what
# keeps mazesim's batches from doing so.
@pytest.mark.filterwarnings("ignore:This process .* is multi-threaded:DeprecationWarning")
def test_a_forked_child_makes_and_steps_batches() -> None:
    expected = _step_a_batch_in_a_child(0)
    with multiprocessing.get_context("fork").Pool(2) as pool:
        result = pool.map_async(_step_a_batch_in_a_child, range(2))
        assert result.get(timeout=300) == [expected, expected]


def test_ctrl_c_stops_a_long_batch_step_midway() -> None:
    body = """
    import os, signal, threading
    w = _core.World.builtin("arena")
    b = _core.BatchSimulator(w, num_envs=2048, control_step_ms=w.basic_time_step_ms * 10000)
    out = buffers(b)
    threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
    try:
        b.step(np.full((2048, 2), 6.0, np.float32), *out)
        print("NOT INTERRUPTED")
    except KeyboardInterrupt:
        print("INTERRUPTED, UNSTEPPED", int((b.steps() == 0).sum()))
    """
    outcome = run_hostile(body)
    # (2,048 envs of 10,000 physics steps each take seconds, so the signal comes mid-call.)
    assert outcome.ok and "INTERRUPTED, UNSTEPPED" in outcome.stdout, outcome.describe()
    # Stopped inside the call, not after it: some environments were never stepped.
    assert int(outcome.stdout.split("UNSTEPPED")[1].split()[0]) > 0, outcome.stdout


@st.composite
def _careless_array(draw: st.DrawFn, shape: tuple[int, ...]) -> np.ndarray:
    """An array meant to be of `shape`, drawn wrong in any way: dtype, shape, strides, alignment,
    writability."""
    dtype = draw(st.sampled_from([np.float32, np.float64, np.int32, np.uint64, np.bool_]))
    if draw(st.booleans()):
        shape = tuple(draw(st.integers(0, 5)) for _ in range(draw(st.integers(0, 3))))
    size = int(np.prod(shape)) * np.dtype(dtype).itemsize
    layout = draw(st.sampled_from(["plain", "unaligned", "strided", "read-only"]))
    if layout == "unaligned":
        array = np.zeros(size + 1, np.uint8)[1:].view(dtype).reshape(shape)
    elif layout == "strided":
        array = np.zeros(shape + (2,), dtype)[..., 0]
    else:
        array = np.zeros(shape, dtype)
        array.flags.writeable = layout != "read-only"
    return array


@settings(max_examples=60, deadline=None)
@given(data=st.data())
def test_careless_buffers_raise_invalid_argument_or_work(data: st.DataObject) -> None:
    batch = _core.BatchSimulator(_core.World.builtin("arena"), num_envs=3, threads=1)
    shapes = {
        "actions": (3, 2),
        "observations": (3, batch.observation_width),
        "poses": (3, 3),
        "colliding": (3,),
        "crossings": (3,),
    }
    arrays = {name: data.draw(_careless_array(shape), label=name) for name, shape in shapes.items()}
    try:
        batch.step(*arrays.values())
    except mazesim.InvalidArgumentError:
        return
    assert all(a.flags.c_contiguous and a.flags.aligned for a in arrays.values())


_INHERITED: list[_core.BatchSimulator] = []


def _step_the_inherited_batch(_: int) -> float:
    batch = _INHERITED[0]
    out = (
        np.zeros((64, batch.observation_width), np.float32),
        np.zeros((64, 3), np.float32),
        np.zeros(64, bool),
        np.zeros(64, np.int32),
    )
    batch.reset(*out)
    batch.step(np.full((64, 2), 4.0, np.float32), *out)
    return float(out[1][:, 0].sum())


@pytest.mark.filterwarnings("ignore:This process .* is multi-threaded:DeprecationWarning")
@pytest.mark.parametrize("threads", [0, 2])
def test_a_forked_child_steps_a_batch_its_parent_made(threads: int) -> None:
    _INHERITED[:] = [
        _core.BatchSimulator(_core.World.builtin("seed-maze"), num_envs=64, threads=threads)
    ]
    expected = _step_the_inherited_batch(0)
    with multiprocessing.get_context("fork").Pool(1) as pool:
        assert pool.map_async(_step_the_inherited_batch, [0]).get(timeout=300) == [expected]


#: A str Python made of bytes it could not decode (a file name, a command-line argument): name
#: -> (statement with ``S``, such a str, in scope). Each used to end in pyo3's
#: ``UnicodeEncodeError`` or "expected name to be a str, found a str".
NOT_UNICODE = {
    "robot": "_core.Simulator(_core.World.builtin('arena'), robot=S)",
    "batch robots": "_core.BatchSimulator(_core.World.builtin('arena'), num_envs=2, robot=[S, S])",
    "world name": "_core.World.builtin(S)",
    "profile name": "_core.RobotProfile.builtin(S)",
    "world text": "_core.World.from_toml(S)",
    "codes": "mazesim.validate_codes([S])",
}


@pytest.mark.parametrize("name", sorted(NOT_UNICODE))
def test_a_str_that_is_not_unicode_text_is_refused_saying_so(name: str) -> None:
    outcome = run_hostile("S = 'maze-\\udcff'\n" + NOT_UNICODE[name])
    assert outcome.refused, outcome.describe()
    assert "InvalidArgumentError" in outcome.stdout and "not Unicode text" in outcome.stdout, (
        outcome.stdout
    )


def test_a_wbt_time_step_the_world_refuses_is_a_warning_of_its_line() -> None:
    text = "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 0.05 }\n"
    world, report = _core.import_wbt_text(text)
    assert world.basic_time_step_ms == 32.0
    assert any(w.startswith("line 2: basicTimeStep:") and "0.05" in w for w in report["warnings"])


def test_an_imported_world_the_world_check_refuses_names_the_wbt_file(tmp_path: Path) -> None:
    # 100,000 boxes piled up: the world made from them has more crowded walls than its index
    # holds; the refusal used to point at "imported:5:1", a line of a text the user never saw.
    path = tmp_path / "crowd.wbt"
    solids = "".join(
        f"Solid {{ translation {i * 1e-4:.4f} 0 0 boundingObject Box {{ size 0.01 0.1 0.1 }} }}\n"
        for i in range(100_000)
    )
    path.write_text("#VRML_SIM R2023b utf8\n" + solids)
    with pytest.raises(mazesim.WorldFormatError) as caught:
        _core.import_wbt(str(path))
    assert str(caught.value).startswith(f"{path}: field `(imported world).walls`: expected walls")
    assert caught.value.source == str(path) and caught.value.line is None


@pytest.mark.parametrize("target", ["/dev/full", "a-file", "a-fifo"])
def test_saving_a_navigator_into_something_not_a_folder_says_what_it_is(
    tmp_path: Path, target: str
) -> None:
    from mazesim.learn.tables import load_policy, save_policy

    folder = tmp_path
    (folder / "a-file").write_text("kept\n")
    os.mkfifo(folder / "a-fifo")
    path = target if target.startswith("/") else str(folder / target)
    kind = {"/dev/full": "a character device", "a-file": "a file", "a-fifo": "a FIFO"}[target]
    with pytest.raises(mazesim.MazesimIOError, match=f"expected an output folder, found {kind}"):
        save_policy(load_policy(), path)
    assert (folder / "a-file").read_text() == "kept\n"


#: A Webots controller's calls of its devices with arguments of the wrong type: each must be
#: refused with a WrongTypeError (an InvalidArgumentError and a TypeError) naming the method and
#: the parameter.
WRONG_TYPED_DEVICE_CALLS = {
    "motor velocity": "robot.getDevice('left wheel motor').setVelocity('fast')",
    "emitter channel": "robot.getDevice('emitter').setChannel('seven')",
    "distance sensor period": "robot.getDevice('ps0').enable('often')",
    "led value": "robot.getDevice('led0').set([1])",
    # Text read as a number by float(): accepted as 64 ms.
    "step duration": "robot.step('64')",
    # Read by int() as another number, without a word (Webots refuses them).
    "receiver channel of 1.5": "robot.getDevice('receiver').setChannel(1.5)",
    "sampling period of True": "robot.getDevice('ps0').enable(True)",
    # Plain values of another type that no line of the call failed on: True was a step of 1 ms
    # and a speed of 1 rad/s, None and 3 the names of devices "None" and "3".
    "step duration of True": "robot.step(True)",
    "motor velocity of True": "robot.getDevice('left wheel motor').setVelocity(True)",
    "device name None": "robot.getDevice(None)",
    "device name 3": "robot.getDevice(3)",
}


def _run_controller(controller: Path, out: Path) -> subprocess.CompletedProcess[str]:
    """``mazesim webots run`` of ``controller`` for one second in the arena."""
    return subprocess.run(
        [sys.executable, "-m", "mazesim", "webots", "run", str(controller)]
        + ["--world", "arena", "--seconds", "1", "--out", str(out)],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )


def test_a_controllers_wrong_typed_device_calls_are_refused_naming_the_method(
    tmp_path: Path,
) -> None:
    """The controller runs inside ``mazesim webots run``: its calls were taken for the package's
    calls to itself and not checked (a ``ValueError`` from a line deep in the package)."""
    calls = "".join(
        f"try:\n    {call}\n    print('ACCEPTED', {name!r})\n"
        f"except mazesim.MazesimError as e:\n    print('REFUSED', {name!r}, type(e).__name__, e)\n"
        f"except Exception as e:\n    print('ESCAPED', {name!r}, type(e).__name__, e)\n"
        for name, call in WRONG_TYPED_DEVICE_CALLS.items()
    )
    controller = tmp_path / "wrong_types.py"
    controller.write_text("import mazesim\nfrom controller import Robot\nrobot = Robot()\n" + calls)
    done = _run_controller(controller, tmp_path / "run")
    refused = [line for line in done.stdout.splitlines() if line.startswith("REFUSED")]
    assert len(refused) == len(WRONG_TYPED_DEVICE_CALLS), done.stdout + done.stderr
    assert all("WrongTypeError" in line and " refused: " in line for line in refused), refused


#: Controllers that end in an exception, and what the end of their run must say.
ENDED_CONTROLLERS = {
    # Webots' None for a device the robot lacks, then a call on it: the AttributeError on None
    # did not say which name was asked for or what the robot has.
    "robot.getDevice('ps9').enable(64)": [
        "getDevice returned None for 'ps9': robot 'e-puck' has no device of that name",
        "'ps0'",
    ],
    # A call the package refused: the trace went on into the package's checking frames.
    "robot.step(-1)": [
        "Robot.step expects a duration in ms from 0 to 2147483647 (Webots' C int), found -1.0"
    ],
}


@pytest.mark.parametrize("line", sorted(ENDED_CONTROLLERS))
def test_a_controller_ended_by_an_exception_says_why_at_its_own_line(
    tmp_path: Path, line: str
) -> None:
    controller = tmp_path / "ended.py"
    controller.write_text(f"from controller import Robot\nrobot = Robot()\n{line}\n")
    done = _run_controller(controller, tmp_path / "run")
    assert done.returncode == 1, done.stderr
    for expected in ENDED_CONTROLLERS[line]:
        assert expected in done.stderr, done.stderr
    trace = done.stderr[done.stderr.index("Traceback") :]
    frames = [f for f in trace.splitlines() if f.strip().startswith("File ")]
    assert frames and all(str(controller) in f for f in frames), trace


def _core_instances() -> dict[str, object]:
    from surface.registry import INSTANCES

    world = _core.World.builtin("seed-maze")
    made = {}
    for path, recipe in INSTANCES.items():
        if path.startswith("mazesim._core."):
            made[path.rsplit(".", 1)[1]] = eval(recipe, {"mazesim": mazesim, "world": world})  # noqa: S307
    return made


@pytest.mark.parametrize("how", ["pickle", "copy", "deepcopy"])
def test_every_core_object_pickles_or_is_refused_saying_so(how: str) -> None:
    """Every class of the core, pickled or copied: a working copy, or WrongTypeError (an
    InvalidArgumentError that is also a TypeError, as pickle's own refusal) naming the class; a
    batch, a navigator, the settings of a run call and three more failed with pickle's bare
    TypeError (a PettingZoo env holding a batch with them)."""
    import copy
    import pickle

    action = {
        "pickle": lambda o: pickle.loads(pickle.dumps(o)),
        "copy": copy.copy,
        "deepcopy": copy.deepcopy,
    }[how]
    instances = _core_instances()
    classes = {n for n in dir(_core) if isinstance(getattr(_core, n), type)}
    assert {n for n in classes if not issubclass(getattr(_core, n), BaseException)} <= set(
        instances
    )
    refused = []
    for name, instance in sorted(instances.items()):
        try:
            action(instance)
        except mazesim.WrongTypeError as error:
            assert isinstance(error, TypeError), name
            assert f"found {_with_article(name)}, which cannot be" in str(error), error
            refused.append(name)
    assert "BatchSimulator" in refused and "World" not in refused and "Simulator" not in refused
