"""Barcode code books, the Alg. 7 and robust decoders, and the readers (report section 4.2)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mazesim
from mazesim.barcode import (
    Alg7Decoder,
    BarcodeReader,
    BatchBarcodeReader,
    CodeBook,
    Odometry,
    RobustDecoder,
    WheelEncoders,
    barcode_sensor_index,
    make_decoder,
)
from mazesim.errors import InvalidArgumentError, UnknownNameError

DEFAULT_BOOK = CodeBook.default()
WHITE, BLACK, FLOOR = 856.0, 300.0, 599.0
MAX_SPEED = 6.28
#: Wheel speed (rad/s) to linear speed (m/s) of the seed robot.
WHEEL_RADIUS = 0.0205
SENSOR_AHEAD = 0.03


def one_code_world(code: str, yaw: float) -> mazesim.World:
    """Checkpoint 1 with ``code`` at the origin of an open grey floor, no walls."""
    return mazesim.World.from_toml(
        f"""
format = "mazesim-world"
version = 1
name = "one-code"
[floor]
reflectance = 0.36
[[checkpoints]]
id = 1
code = "{code}"
center = [0.0, 0.0]
yaw = {yaw!r}
width = 0.3
"""
    )


# --- code books ---------------------------------------------------------------------------


def test_default_book_maps_both_ways() -> None:
    assert len(DEFAULT_BOOK) == 12
    assert DEFAULT_BOOK.code_length == 5
    for checkpoint, code in DEFAULT_BOOK:
        assert DEFAULT_BOOK.lookup(code) == (checkpoint, "arrival")
        assert DEFAULT_BOOK.lookup(code[::-1]) == (checkpoint, "departure")
        assert DEFAULT_BOOK.reading(checkpoint, "arrival") == code
        assert DEFAULT_BOOK.reading(checkpoint, "departure") == code[::-1]
        assert DEFAULT_BOOK.signed_id(code[::-1]) == -checkpoint
    # 24 of the 32 five-bit readings name a checkpoint; the 8 palindromes name none.
    readings = [f"{value:05b}" for value in range(32)]
    assert sum(DEFAULT_BOOK.lookup(bits) is not None for bits in readings) == 24
    assert DEFAULT_BOOK.lookup("10101") is None and DEFAULT_BOOK.signed_id("11111") == 0


def test_book_of_seed_maze_matches_its_checkpoints() -> None:
    world = mazesim.load_world("seed-maze")
    book = CodeBook.from_world(world)
    assert book.ids == [1, 2, 3, 4, 5, 6, 7]
    for checkpoint in world.checkpoints():
        assert book.code(int(checkpoint["id"])) == checkpoint["code"]
    assert book == CodeBook({cp["id"]: cp["code"] for cp in world.checkpoints()})


@pytest.mark.parametrize(
    ("codes", "message"),
    [
        (["10101"], "palindrome"),
        (["10110", "00111", "10110"], "duplicate"),
        (["10110", "01101"], "backwards"),
        ({3: "10110", 9: "01101"}, "backwards"),
        (["1011", "10110"], "bits"),
        (["10x10"], "0 and 1"),
        ([], "at least one code"),
        ({0: "10110"}, "positive"),
        ("10110", "sequence"),
    ],
)
def test_ill_formed_books_are_rejected(codes: object, message: str) -> None:
    with pytest.raises(InvalidArgumentError, match=message):
        CodeBook(codes)


def test_world_without_checkpoints_has_no_book() -> None:
    with pytest.raises(InvalidArgumentError, match="no barcode checkpoints"):
        CodeBook.from_world(mazesim.load_world("arena"))


def test_unknown_checkpoint_and_direction() -> None:
    with pytest.raises(InvalidArgumentError, match="checkpoint ids"):
        DEFAULT_BOOK.code(13)
    with pytest.raises(InvalidArgumentError, match="direction"):
        DEFAULT_BOOK.reading(1, "sideways")


def test_decoders_by_name() -> None:
    assert isinstance(make_decoder("alg7", DEFAULT_BOOK), Alg7Decoder)
    assert isinstance(make_decoder("robust", DEFAULT_BOOK), RobustDecoder)
    with pytest.raises(UnknownNameError, match="alg7, robust"):
        make_decoder("best", DEFAULT_BOOK)


# --- Alg. 7 on synthetic streams -------------------------------------------------------------


def bars_stream(bits: str, samples_per_bar: list[int]) -> list[float]:
    """Floor, the bars with the given numbers of samples each, floor."""
    stream = [FLOOR]
    for bit, count in zip(bits, samples_per_bar):
        stream += [WHITE if bit == "1" else BLACK] * count
    return [*stream, FLOOR]


def feed(decoder: Alg7Decoder, stream: list[float]) -> list[mazesim.barcode.Reading]:
    return [r for r in (decoder.update(value) for value in stream) if r is not None]


@pytest.mark.parametrize("per_bar", [1, 2, 4, 7, 40])
def test_alg7_reads_even_streams_in_both_directions(per_bar: int) -> None:
    decoder = Alg7Decoder(DEFAULT_BOOK)
    for checkpoint, code in DEFAULT_BOOK:
        (arrival,) = feed(decoder, bars_stream(code, [per_bar] * 5))
        (departure,) = feed(decoder, bars_stream(code[::-1], [per_bar] * 5))
        assert (arrival.checkpoint, arrival.direction) == (checkpoint, "arrival")
        assert (departure.checkpoint, departure.direction) == (checkpoint, "departure")
        assert arrival.samples == 5 * per_bar


def test_alg7_takes_the_middle_of_each_fifth() -> None:
    # 10 samples: n = 2, bits at samples 1, 3, 5, 7, 9 (0-based); the others do not matter.
    values = [BLACK, WHITE, WHITE, BLACK, BLACK, WHITE, BLACK, WHITE, WHITE, BLACK]
    (reading,) = feed(Alg7Decoder(CodeBook({4: "10110"})), [FLOOR, *values, FLOOR])
    assert reading.bits == "10110" and reading.checkpoint == 4


def test_alg7_is_fooled_by_uneven_bars_and_threshold_700() -> None:
    decoder = Alg7Decoder(DEFAULT_BOOK)
    # The robot slowed down on the first bar: most samples are of bar 1.
    (reading,) = feed(decoder, bars_stream("10110", [12, 2, 2, 2, 2]))
    assert reading.bits != "10110"
    # 699 is black for Alg. 7, 700 white.
    assert feed(decoder, [FLOOR, 700.0, 699.0, 700.0, 700.0, 699.0, FLOOR])[0].bits == "10110"


def test_no_valid_read_for_a_reading_of_no_code() -> None:
    (reading,) = feed(Alg7Decoder(DEFAULT_BOOK), bars_stream("10101", [3] * 5))
    assert not reading.valid and reading.signed_id == 0
    assert reading.bits == "10101" and "no code of the book" in reading.reason


def test_floor_band_and_threshold_are_checked() -> None:
    with pytest.raises(InvalidArgumentError, match="floor_low < floor_high"):
        Alg7Decoder(DEFAULT_BOOK, floor_low=700, floor_high=600)
    with pytest.raises(InvalidArgumentError, match="outside the floor band"):
        Alg7Decoder(DEFAULT_BOOK, bit_threshold=600)
    with pytest.raises(InvalidArgumentError, match="CodeBook"):
        Alg7Decoder(["10110"])


@pytest.mark.parametrize("number", [math.nan, math.inf, -math.inf])
@pytest.mark.parametrize("name", ["bit_threshold", "floor_low", "floor_high", "floor_distance"])
def test_a_decoder_s_numbers_must_be_finite(name: str, number: float) -> None:
    # NaN fails every comparison, so a band check alone let it through (now the surface check
    # refuses NaN and infinities for any number before the decoder's own check of a finite one).
    words = f"expected {name} a finite number|{name} refused: expected a (finite )?number"
    with pytest.raises(InvalidArgumentError, match=words):
        Alg7Decoder(DEFAULT_BOOK, **{name: number})


@pytest.mark.parametrize(
    ("keyword", "number"),
    [
        ("resolution", math.nan),
        ("resolution", math.inf),
        ("resolution", -1.0),
        ("control_step_ms", math.inf),
    ],
)
def test_wheel_encoders_refuse_a_resolution_or_step_that_is_not_finite(
    keyword: str, number: float
) -> None:
    robot = mazesim.RobotProfile.builtin("e-puck")
    arguments = {"control_step_ms": 64.0, keyword: number}
    with pytest.raises(InvalidArgumentError, match="finite|expected a number, found NaN"):
        WheelEncoders(robot, 1, **arguments)


def test_a_barcode_reader_refuses_what_is_no_decoder() -> None:
    with pytest.raises(InvalidArgumentError, match="expected a Decoder, found an int"):
        BarcodeReader(5, mazesim.RobotProfile.builtin("e-puck"))  # type: ignore[arg-type]


def test_robust_decoder_needs_positions() -> None:
    with pytest.raises(InvalidArgumentError, match="position"):
        RobustDecoder(DEFAULT_BOOK).update(WHITE)


# --- the robust decoder on synthetic geometry ------------------------------------------------


def robust_stream(bits: str, path: np.ndarray, axis_angle: float) -> list[tuple[float, tuple]]:
    """Readings of an ideal sensor at the points of ``path`` over a code starting at the origin
    and running along ``axis_angle``."""
    axis = np.array([math.cos(axis_angle), math.sin(axis_angle)])
    samples = []
    for point in path:
        u = float(point @ axis) / 0.017
        value = FLOOR if not 0.0 <= u < 5.0 else (WHITE if bits[int(u)] == "1" else BLACK)
        samples.append((value, (float(point[0]), float(point[1]))))
    return samples


def test_robust_reads_a_curved_path_that_alg7_misreads() -> None:
    # The sensor sweeps over the code on an arc, slowing down on the first bars.
    s = np.linspace(0.0, 1.0, 120) ** 0.5
    angle = 0.6 * s
    path = np.column_stack([-0.02 + 0.13 * s * np.cos(0.3), 0.13 * s * np.sin(angle)])
    stream = robust_stream("10110", path, 0.3)
    robust = RobustDecoder(DEFAULT_BOOK)
    alg7 = Alg7Decoder(DEFAULT_BOOK)
    robust_reads = [r for v, p in stream if (r := robust.update(v, p)) is not None]
    alg7_reads = [r for v, _ in stream if (r := alg7.update(v)) is not None]
    assert [(r.checkpoint, r.direction) for r in robust_reads] == [DEFAULT_BOOK.lookup("10110")]
    assert alg7_reads[0].bits != "10110"


def test_robust_refuses_a_sensor_that_turns_back_on_the_code() -> None:
    there = np.column_stack([np.linspace(-0.01, 0.05, 40), np.zeros(40)])
    path = np.vstack([there, there[::-1]])
    stream = robust_stream("10110", path, 0.0)
    decoder = RobustDecoder(DEFAULT_BOOK)
    (reading,) = [r for v, p in stream if (r := decoder.update(v, p)) is not None]
    assert not reading.valid and "less than its length" in reading.reason


def test_robust_refuses_samples_that_do_not_fit_the_bars() -> None:
    # Odometry says the sensor moved evenly, but it saw six bars' worth of changes.
    path = np.column_stack([np.linspace(-0.004, 0.0955, 64), np.zeros(64)])
    values = [FLOOR] + [WHITE, BLACK] * 29 + [FLOOR] * 5
    decoder = RobustDecoder(DEFAULT_BOOK)
    readings = [
        r
        for v, p in zip(values, path)
        if (r := decoder.update(v, (float(p[0]), float(p[1])))) is not None
    ]
    assert len(readings) == 1 and not readings[0].valid


# --- the robust decoder in the simulator: the acceptance property ----------------------------


def drive_across(
    code: str,
    code_yaw: float,
    forward: bool,
    off_axis: float,
    speed: float,
    lateral: float,
    seed: int,
    wobble: float = 0.0,
) -> tuple[list[dict[str, object]], list[mazesim.barcode.Reading]]:
    """Drives the seed robot over a lone code; returns the ground truth and the robust reads."""
    world = one_code_world(code, code_yaw)
    sim = mazesim.Simulator(world, robot="seed", seed=seed, noise=True)
    travel = code_yaw if forward else code_yaw + math.pi
    heading = travel + off_axis
    # The sensor starts 12 cm before the code's centre, ``lateral`` beside its axis.
    sensor_x = -0.12 * math.cos(heading) - lateral * math.sin(travel)
    sensor_y = -0.12 * math.sin(heading) + lateral * math.cos(travel)
    sim.set_pose(
        sensor_x - SENSOR_AHEAD * math.cos(heading),
        sensor_y - SENSOR_AHEAD * math.sin(heading),
        heading,
    )
    reader = BarcodeReader(RobustDecoder(CodeBook({1: code})), sim.robot)
    reader.update(sim)
    rng = np.random.default_rng(seed)
    readings = []
    steps = math.ceil(0.25 / (speed * WHEEL_RADIUS * sim.control_step_ms / 1000.0)) + 4
    for _ in range(steps):
        factors = 1.0 + rng.uniform(-wobble, wobble, 2)
        sim.step(speed * factors[0], speed * factors[1])
        reading = reader.update(sim)
        if reading is not None:
            readings.append(reading)
    return sim.crossings(), readings


@settings(max_examples=150, deadline=None)
@given(
    checkpoint=st.integers(1, 12),
    code_yaw=st.floats(-math.pi, math.pi),
    forward=st.booleans(),
    off_axis=st.floats(-math.radians(30.0), math.radians(30.0)),
    speed=st.floats(0.3, MAX_SPEED),
    lateral=st.floats(-0.05, 0.05),
    seed=st.integers(0, 2**32 - 1),
)
def test_robust_decodes_every_code_across_angles_and_speeds(
    checkpoint: int,
    code_yaw: float,
    forward: bool,
    off_axis: float,
    speed: float,
    lateral: float,
    seed: int,
) -> None:
    code = DEFAULT_BOOK.code(checkpoint)
    truth, readings = drive_across(code, code_yaw, forward, off_axis, speed, lateral, seed)
    direction = "arrival" if forward else "departure"
    assert [(c["checkpoint"], c["direction"]) for c in truth] == [(1, direction)]
    assert [(r.checkpoint, r.direction) for r in readings] == [(1, direction)], readings


@settings(max_examples=100, deadline=None)
@given(
    checkpoint=st.integers(1, 12),
    forward=st.booleans(),
    off_axis=st.floats(-math.radians(30.0), math.radians(30.0)),
    speed=st.floats(0.3, MAX_SPEED / 1.3),
    seed=st.integers(0, 2**32 - 1),
)
def test_robust_tolerates_turns_and_speed_changes_during_the_crossing(
    checkpoint: int, forward: bool, off_axis: float, speed: float, seed: int
) -> None:
    # Each step both wheels get a random speed within 30 % of ``speed``: the robot weaves
    # and changes speed all the way over the code.
    code = DEFAULT_BOOK.code(checkpoint)
    truth, readings = drive_across(code, 0.4, forward, off_axis, speed, 0.0, seed, wobble=0.3)
    direction = "arrival" if forward else "departure"
    assert [(c["checkpoint"], c["direction"]) for c in truth] == [(1, direction)]
    assert [(r.checkpoint, r.direction) for r in readings] == [(1, direction)], readings


def test_crossing_every_code_of_the_default_book_both_ways() -> None:
    for checkpoint, code in DEFAULT_BOOK:
        for forward in (True, False):
            truth, readings = drive_across(code, 1.0, forward, 0.2, 3.14, 0.01, checkpoint)
            expected = (1, "arrival" if forward else "departure")
            assert [(r.checkpoint, r.direction) for r in readings] == [expected]
            assert [(c["checkpoint"], c["direction"]) for c in truth] == [expected]


# --- odometry, encoders and the batch reader -------------------------------------------------


def test_barcode_sensor_is_the_one_on_the_centre_line() -> None:
    assert barcode_sensor_index(mazesim.RobotProfile.builtin("e-puck")) == 1
    assert barcode_sensor_index(mazesim.RobotProfile.builtin("seed")) == 0


def test_wheel_encoders_match_the_simulator() -> None:
    world = mazesim.load_world("seed-maze")
    robot = mazesim.RobotProfile.builtin("seed")
    sim = mazesim.Simulator(world, robot="seed", seed=1)
    encoders = WheelEncoders(robot, 1, sim.control_step_ms)
    rng = np.random.default_rng(3)
    for _ in range(300):
        action = rng.uniform(-8.0, 8.0, size=(1, 2)).astype(np.float32)
        sim.step(float(action[0, 0]), float(action[0, 1]))
        encoders.step(action)
        np.testing.assert_allclose(encoders.values[0], sim.encoders, atol=0.0065)


def test_odometry_follows_the_robot_off_walls() -> None:
    sim = mazesim.Simulator(mazesim.load_world("arena"), robot="e-puck", seed=0)
    odometry = Odometry(sim.robot)
    odometry.update(sim.encoders)
    start_x, start_y, start_yaw = sim.pose
    for step in range(100):
        sim.step(3.0, 3.0 + 2.0 * math.sin(step / 10.0))
        odometry.update(sim.encoders)
    x, y, yaw = odometry.poses[0]
    # Back in the world frame.
    world_x = start_x + x * math.cos(start_yaw) - y * math.sin(start_yaw)
    world_y = start_y + x * math.sin(start_yaw) + y * math.cos(start_yaw)
    assert sim.collisions == 0
    assert math.hypot(world_x - sim.pose[0], world_y - sim.pose[1]) < 0.005
    assert abs(math.remainder(start_yaw + yaw - sim.pose[2], 2 * math.pi)) < 0.02


def test_batch_reader_equals_one_reader_per_simulator() -> None:
    world = mazesim.load_world("seed-maze")
    robot = mazesim.RobotProfile.builtin("seed")
    book = CodeBook.from_world(world)
    count, steps = 3, 220
    batch = mazesim.BatchSimulator(world, num_envs=count, robot="seed", seeds=[5, 6, 7])
    observations = np.zeros((count, batch.observation_width), dtype=np.float32)
    poses = np.zeros((count, 3), dtype=np.float32)
    colliding = np.zeros(count, dtype=bool)
    crossings = np.zeros(count, dtype=np.int32)
    batch.observe(observations, poses, colliding, crossings)
    encoders = WheelEncoders(robot, count, world.basic_time_step_ms)
    batch_reader = BatchBarcodeReader(
        [make_decoder(name, book) for name in ("robust", "alg7", "robust")], robot
    )
    batch_reader.update(observations[:, batch.distance_width], encoders.values)
    sims = [mazesim.Simulator(world, robot="seed", seed=seed) for seed in (5, 6, 7)]
    readers = [BarcodeReader(make_decoder(name, book), robot) for name in ("robust", "alg7")]
    readers.append(BarcodeReader(make_decoder("robust", book), robot))
    for sim, reader in zip(sims, readers):
        reader.update(sim)
    from_batch, from_sims = [], []
    actions = np.array([[3.14, 3.14], [4.0, 4.0], [2.0, 2.0]], dtype=np.float32)
    for step in range(steps):
        batch.step(actions, observations, poses, colliding, crossings)
        encoders.step(actions)
        for env, reading in batch_reader.update(
            observations[:, batch.distance_width], encoders.values
        ):
            from_batch.append((step, env, reading))
        for env, (sim, reader) in enumerate(zip(sims, readers)):
            sim.step(float(actions[env, 0]), float(actions[env, 1]))
            reading = reader.update(sim)
            if reading is not None:
                from_sims.append((step, env, reading))
    assert from_batch == from_sims
    assert {(env, r.checkpoint, r.direction) for _, env, r in from_batch} == {
        (0, 1, "arrival"),
        (1, 1, "arrival"),
        (2, 1, "arrival"),
    }


def test_batch_reader_mask_hides_the_sample_from_robots_outside_it() -> None:
    robot = mazesim.RobotProfile.builtin("seed")
    reader = BatchBarcodeReader([Alg7Decoder(DEFAULT_BOOK) for _ in range(2)], robot)
    bits = "10110"
    stream = [600.0] + [856.0 if b == "1" else 300.0 for b in bits for _ in range(4)]
    stream += [600.0]
    hidden = {5, 6, 7, 8}  # the second bar, all of it, never reaches robot 1
    found: dict[int, list[str]] = {0: [], 1: []}
    for index, value in enumerate(stream):
        mask = np.array([True, index not in hidden])
        for env, reading in reader.update(np.array([value, value]), None, mask):
            found[env].append(reading.bits)
    assert found == {0: [bits], 1: ["11110"]}  # 16 samples, 1111 1111 1111 0000
    with pytest.raises(InvalidArgumentError, match=r"mask of shape \(2,\)"):
        reader.update(np.zeros(2), None, np.ones(3, dtype=bool))
    with pytest.raises(InvalidArgumentError, match=r"mask of shape \(2,\), found \(1,\)"):
        reader.reset(np.ones(1, dtype=bool))


def test_a_reader_refuses_a_simulator_of_another_robot_naming_both() -> None:
    # An alphabot2 reader on the seed robot's simulator read a sensor index the robot lacks:
    # "IndexError: index 2 is out of bounds".
    simulator = mazesim.Simulator(mazesim.load_world("seed-maze"), robot="seed")
    reader = BarcodeReader(RobustDecoder(DEFAULT_BOOK), mazesim.RobotProfile.builtin("alphabot2"))
    with pytest.raises(InvalidArgumentError, match="robot 'alphabot2' .* found one of 'seed'"):
        reader.update(simulator)
    assert BarcodeReader(RobustDecoder(DEFAULT_BOOK), simulator.robot).update(simulator) is None


def test_batch_reader_checks_shapes() -> None:
    robot = mazesim.RobotProfile.builtin("seed")
    # One decoder repeated (`[decoder] * 2`) would mix two robots' samples: refused.
    shared = RobustDecoder(DEFAULT_BOOK)
    with pytest.raises(InvalidArgumentError, match=r"decoders\[0\] given again as decoders\[1\]"):
        BatchBarcodeReader([shared] * 2, robot)
    reader = BatchBarcodeReader([RobustDecoder(DEFAULT_BOOK) for _ in range(2)], robot)
    with pytest.raises(InvalidArgumentError, match=r"\(2,\)"):
        reader.update(np.zeros(3), np.zeros((2, 2)))
    with pytest.raises(InvalidArgumentError, match="encoders"):
        reader.update(np.zeros(2))
    with pytest.raises(InvalidArgumentError, match="one floor band"):
        BatchBarcodeReader(
            [Alg7Decoder(DEFAULT_BOOK), Alg7Decoder(DEFAULT_BOOK, floor_low=500.0)], robot
        )
