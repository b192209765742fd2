"""The recorded-run format: round trips, versions, size, and what the navigator's run holds."""

from __future__ import annotations

import gzip
import json
import os
import tracemalloc
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import mazesim
from mazesim.cli import main
from mazesim.errors import MazesimError, RunFormatError
from mazesim.learn.subtasks import SUBTASK_NAMES
from mazesim.replay import FORMAT_VERSION, RecordedRun, load_run, save_run
from mazesim.replay.html import replay_html, write_html
from mazesim.replay.recorder import FleetRecorder
from mazesim.replay.run import MAX_RUN_BYTES


def long_run(steps: int = 4000) -> RecordedRun:
    """The seed robot wandering ``steps`` control steps in seed-maze, every field filled."""
    simulator = mazesim.Simulator(mazesim.load_world("seed-maze"), robot="seed", seed=3)
    recorder = FleetRecorder.of_simulator(simulator, "wander", seed=3)
    rng = np.random.default_rng(3)
    for _ in range(steps):
        left, right = rng.uniform(-3.0, 6.28, size=2)
        recorder.capture_simulator(simulator)
        recorder.acted(0, float(left), float(right))
        recorder.recorders[0].set_action(code="00", subtask=int(rng.integers(4)))
        simulator.step(float(left), float(right))
    recorder.capture_simulator(simulator)
    run = recorder.run("time up")
    run.subtask_names = list(SUBTASK_NAMES)
    return run


def test_a_run_round_trips_within_its_units(tmp_path: Path) -> None:
    run = long_run(300)
    path = tmp_path / "run.json"
    save_run(run, path)
    again = load_run(path)
    first, second = run.episodes[0], again.episodes[0]
    assert again.world == run.world
    assert (again.robot, again.controller, again.seed) == ("seed", "wander", 3)
    assert second.frames == first.frames == 301
    assert np.max(np.abs(second.poses[:, :2] - first.poses[:, :2])) <= 0.5e-4 + 1e-12
    assert np.max(np.abs(second.poses[:, 2] - first.poses[:, 2])) <= 0.5e-3 + 1e-12
    assert np.max(np.abs(second.readings - first.readings)) <= 0.5e-3 + 1e-9
    assert np.array_equal(second.colliding, first.colliding)
    assert np.array_equal(second.events, first.events)
    assert second.actions == first.actions
    assert first.levels is not None and np.array_equal(second.levels, first.levels)
    assert first.subtasks is not None and np.array_equal(second.subtasks, first.subtasks)


@pytest.mark.parametrize(
    ("damage", "field"),
    [("nan pose", "episodes[0].x"), ("inf wheel", "wheel_speeds"), ("far pose", "episodes[0].x")],
)
def test_a_run_its_loader_would_refuse_is_not_saved_and_the_file_kept(
    tmp_path: Path, damage: str, field: str
) -> None:
    path = tmp_path / "run.json"
    save_run(long_run(20), path)
    before = path.read_bytes()
    run = long_run(20)
    episode = run.episodes[0]
    if damage == "nan pose":
        episode.poses[3, 0] = np.nan
    elif damage == "far pose":
        episode.poses[3, 0] = 1e8
    else:
        assert episode.wheel_speeds is not None
        episode.wheel_speeds[2, 0] = np.inf
    with pytest.raises(mazesim.InvalidArgumentError, match="load_run reads back") as refused:
        save_run(run, path)
    assert field in str(refused.value)
    assert path.read_bytes() == before, "a good file is never replaced by one it cannot read"


def test_a_run_saved_with_a_byte_order_mark_reads_and_one_in_utf16_is_named(
    tmp_path: Path,
) -> None:
    # As every reader of text of mazesim's: a BOM (a Windows editor's) is no part of the text.
    path = tmp_path / "run.json"
    save_run(long_run(10), path)
    text = path.read_bytes()
    path.write_bytes(b"\xef\xbb\xbf" + text)
    assert load_run(path).episodes[0].frames == 11
    path.write_bytes(text.decode("utf-8").encode("utf-16"))
    with pytest.raises(RunFormatError, match="found UTF-16 text .* save it as UTF-8"):
        load_run(path)


def test_an_episode_the_run_lacks_is_refused_before_a_video_is_begun(tmp_path: Path) -> None:
    from mazesim.replay.video import video_frames, write_video

    run = long_run(5)
    assert run.episode(0) is run.episodes[0]
    for bad in (1, -1):
        with pytest.raises(mazesim.InvalidArgumentError, match=f"from 0 to 0, found {bad}"):
            run.episode(bad)
    with pytest.raises(mazesim.InvalidArgumentError, match="from 0 to 0, found 1"):
        next(video_frames(run, episode=1))
    with pytest.raises(mazesim.InvalidArgumentError, match="from 0 to 0, found 1"):
        write_video(run, tmp_path / "run.gif", episode=1)
    assert not list(tmp_path.iterdir())


def test_gzip_run_files_are_read_by_their_content(tmp_path: Path) -> None:
    run = long_run(20)
    save_run(run, tmp_path / "run.json.gz")
    data = (tmp_path / "run.json.gz").read_bytes()
    assert data[:2] == b"\x1f\x8b"
    assert json.loads(gzip.decompress(data))["format"] == "mazesim-run"
    assert load_run(tmp_path / "run.json.gz").episodes[0].frames == 21


def test_a_newer_major_version_is_refused_clearly(tmp_path: Path) -> None:
    values = long_run(5).as_json()
    values["version"] = f"{FORMAT_VERSION[0] + 1}.0"
    path = tmp_path / "future.json"
    path.write_text(json.dumps(values))
    with pytest.raises(RunFormatError, match=r"version 2\.0 \(a newer format\).*upgrade mazesim"):
        load_run(path)


def test_a_newer_minor_version_is_refused_naming_the_version_to_upgrade_to(
    tmp_path: Path,
) -> None:
    # A newer minor version adds fields this reader would misread by ignoring them (as a 1.2
    # reader would draw a 1.3 run's own profile named e-puck as the built-in e-puck).
    values = long_run(5).as_json()
    values["version"] = newer = f"{FORMAT_VERSION[0]}.{FORMAT_VERSION[1] + 1}"
    values["something_new"] = [1, 2, 3]
    path = tmp_path / "minor.json"
    path.write_text(json.dumps(values))
    reads = "{}.0 to {}.{}".format(FORMAT_VERSION[0], *FORMAT_VERSION)
    with pytest.raises(
        RunFormatError,
        match=rf"reads run format {reads}; the file is version {newer} \(a newer format\): "
        rf"upgrade mazesim to one that reads run format {newer}",
    ):
        load_run(path)


@pytest.mark.parametrize("version", ["1", "1.0", "1.1", "1.2", "1.3"])
def test_every_older_minor_version_still_loads(tmp_path: Path, version: str) -> None:
    values = long_run(5).as_json()
    values["version"] = version
    path = tmp_path / "older.json"
    path.write_text(json.dumps(values))
    assert load_run(path).episodes[0].frames == 6


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("not json at all", "expected a mazesim run"),
        ('{"format": "something-else"}', "expected format 'mazesim-run', found 'something-else'"),
        ('{"format": "mazesim-run", "version": "1.0"}', "expected a field world, found none"),
    ],
)
def test_what_is_not_a_run_raises_a_format_error(tmp_path: Path, text: str, message: str) -> None:
    path = tmp_path / "bad.json"
    path.write_text(text)
    with pytest.raises(RunFormatError, match=message) as caught:
        load_run(path)
    assert isinstance(caught.value, MazesimError)
    assert str(path) in str(caught.value)


def test_a_4000_step_episode_replays_in_well_under_2_mb() -> None:
    run = long_run(4000)
    page = replay_html(run).encode("utf-8")
    assert len(page) < 1_000_000, f"{len(page)} bytes"


def test_the_navigator_demo_records_its_decisions_and_why(navigator_demo: dict[str, Path]) -> None:
    run = load_run(navigator_demo["run"])
    summary = json.loads((navigator_demo["out"] / "summary.json").read_text())
    episode = run.episodes[0]
    assert run.robot == "seed" and run.subtask_names == list(SUBTASK_NAMES)
    assert episode.outcome == "goal reached"
    assert episode.frames == summary["steps"] + 1
    # The decisions are the ones the summary lists, in order, each with its values.
    assert [(d.checkpoint if d.arrival else -d.checkpoint) for d in episode.decisions] == [
        d["event"] for d in summary["decisions"]
    ]
    assert [SUBTASK_NAMES[d.chosen] for d in episode.decisions] == [
        d["subtask"] for d in summary["decisions"]
    ]
    codes = {int(c["id"]): str(c["code"]) for c in run.world.checkpoints()}  # type: ignore[call-overload]
    for number, decision in enumerate(episode.decisions, 1):
        assert decision.number == number
        assert len(decision.q_values) == len(SUBTASK_NAMES)
        assert decision.greedy and decision.chosen == int(np.argmax(decision.q_values))
        expected = codes[decision.checkpoint]
        assert decision.code == (expected if decision.arrival else expected[::-1])
        # The decision was made on the frame that followed the crossing of the code.
        event = decision.checkpoint if decision.arrival else -decision.checkpoint
        assert episode.events[decision.frame] == event
        assert episode.subtasks is not None and episode.subtasks[decision.frame] == decision.chosen
    assert episode.levels is not None and episode.levels.shape == (episode.frames, 6)
    assert episode.actions is not None and all(len(code) == 2 for code in episode.actions[:-1])


def test_replay_command_writes_a_page_from_a_run(
    navigator_demo: dict[str, Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    page = tmp_path / "again.html"
    assert main(["replay", str(navigator_demo["run"]), "-o", str(page)]) == 0
    assert page.read_text().startswith("<!DOCTYPE html>")
    assert f"wrote {page}" in capsys.readouterr().out
    assert main(["replay", str(navigator_demo["run"]), "-o", str(tmp_path / "x.txt")]) == 2
    assert "expected -o FILE.html, FILE.mp4 or FILE.gif" in capsys.readouterr().err


@pytest.mark.parametrize("episode", ["99", "-1"])
def test_replay_refuses_an_episode_the_run_does_not_have_for_a_page_too(
    navigator_demo: dict[str, Path],
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    episode: str,
) -> None:
    """``--episode 99`` of a run of one episode wrote a page as if it were not given (#35)."""
    page = tmp_path / "page.html"
    assert main(["replay", str(navigator_demo["run"]), "-o", str(page), "--episode", episode]) == 2
    assert f"--episode {episode}: expected an episode of " in capsys.readouterr().err
    assert not page.exists()


def test_webots_run_records_every_step_of_the_controller(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    controller = Path(__file__).parents[2] / "examples" / "webots" / "avoid_collision.py"
    run_file = tmp_path / "run.json"
    code = main(
        [
            "webots", "run", str(controller), "--world", "arena", "--seconds", "3",
            "--out", str(tmp_path / "out"), "--record", str(run_file),
            "--html", str(tmp_path / "replay.html"),
        ]
    )  # fmt: skip
    assert code == 0
    assert f"{run_file}, {tmp_path / 'replay.html'}" in capsys.readouterr().out
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    run = load_run(run_file)
    episode = run.episodes[0]
    assert run.robot == "e-puck" and run.controller == "avoid_collision.py"
    assert episode.frames == summary["steps"] + 1
    assert episode.wheel_speeds is not None and np.any(episode.wheel_speeds != 0.0)
    assert episode.readings.shape == (episode.frames, 11)  # ps0-7, gs0-2
    travelled = np.sum(np.hypot(*np.diff(episode.poses[:, :2], axis=0).T))
    assert travelled == pytest.approx(summary["distance_m"], abs=0.01)


def test_demo_records_the_avoid_collision_run(tmp_path: Path) -> None:
    run_file = tmp_path / "run.json"
    assert main(["demo", "--seconds", "4", "--out", str(tmp_path), "--record", str(run_file)]) == 0
    summary = json.loads((tmp_path / "summary.json").read_text())
    episode = load_run(run_file).episodes[0]
    assert episode.frames == summary["steps"] + 1
    assert episode.levels is None  # the e-puck reads raw values, Table 4.1 is for the Sharps
    assert episode.rays.shape == (episode.frames, 8)
    assert np.all((episode.rays >= 0.0) & (episode.rays <= 0.07 + 1e-9))


def test_recording_does_not_change_an_evaluation() -> None:
    from mazesim.learn.evaluate import EvaluationRecord, evaluate_navigator
    from mazesim.learn.tables import load_policy
    from mazesim.replay.navigator import Recording

    world = mazesim.load_world("seed-maze")
    plain_record, recorded_record = (
        EvaluationRecord(paths=2),
        EvaluationRecord(paths=2, recorder=Recording(2)),
    )
    plain = evaluate_navigator(
        load_policy(), [world], 4, seed=9, max_steps=700, record=plain_record
    )
    recorded = evaluate_navigator(
        load_policy(), [world], 4, seed=9, max_steps=700, record=recorded_record
    )
    assert plain_record.run is None and recorded_record.run is not None
    assert recorded == plain
    first, second = plain_record.outcomes, recorded_record.outcomes
    assert first == second and sorted(second) == [0, 1]
    # Each recorded episode has a frame per step and the start.
    steps = {number: r.steps for number, r in second.items()}
    assert [episode.number for episode in recorded_record.run.episodes] == [0, 1]
    for episode in recorded_record.run.episodes:
        assert episode.frames == steps[episode.number] + 1


#: Damaged or hostile fields of a run file (a path into its JSON, the value) and the field the
#: error must name; each once crashed the reader, the page or the video, or was read silently.
HOSTILE_FIELDS = [
    (("seed",), float("inf"), "seed"),
    (("seed",), -1, "seed"),
    (("control_step_ms",), 0, "control_step_ms"),
    (("control_step_ms",), float("nan"), "control_step_ms"),
    (("reading_scale",), 0, "reading_scale"),
    (("robot",), "r2d2", "robot"),
    (("robot",), ["seed"], "robot"),
    (("world",), [], "world"),
    (("episodes",), {}, "episodes"),
    (("episodes", 0, "frames"), 10**30, "episodes[0].frames"),
    (("episodes", 0, "frames"), 0, "episodes[0].frames"),
    (("episodes", 0, "x"), [10**400] * 21, "episodes[0].x"),
    (("episodes", 0, "x"), "abc", "episodes[0].x"),
    (("episodes", 0, "yaw"), [[1, 2]] * 21, "episodes[0].yaw"),
    (("episodes", 0, "readings"), [[1.0]] * 20 + [[1.0, 2.0]], "episodes[0].readings"),
    (("episodes", 0, "contacts"), [-1], "episodes[0].contacts[0]"),
    (("episodes", 0, "contacts"), [21], "episodes[0].contacts[0]"),
    (("episodes", 0, "events"), [[1, 2, 3]], "episodes[0].events[0]"),
    (("episodes", 0, "events"), [[99, 2]], "episodes[0].events[0][0]"),
    (("episodes", 0, "actions"), [], "episodes[0].actions"),
    # Issue 35: finite but beyond the worlds' limits, or past what an int64 holds.
    (("episodes", 0, "x"), [1e300] * 21, "episodes[0].x"),
    (("episodes", 0, "y"), [2e7] * 21, "episodes[0].y"),
    (("episodes", 0, "yaw"), [1e30] * 21, "episodes[0].yaw"),
    (("episodes", 0, "rays"), [[1e300]] * 21, "episodes[0].rays"),
    (("episodes", 0, "wheel_speeds"), [[1, 2, 3]] * 21, "episodes[0].wheel_speeds"),
    (("episodes", 0, "subtasks"), "9" * 21, "episodes[0].subtasks"),
    (("episodes", 0, "levels"), ["x"] * 21, "episodes[0].levels"),
    (("episodes", 0, "decisions"), [{"chosen": 0}], "episodes[0].decisions[0]"),
    # A list of the right length is refused for the item that does not fit, by its index.
    (("episodes", 0, "x"), [0.0] * 5 + ["a"] + [0.0] * 15, "episodes[0].x[5]: expected a number"),
    (("episodes", 0, "x"), [0.0] * 20 + [float("nan")], "episodes[0].x[20]: expected a number"),
    (
        ("episodes", 0, "readings"),
        [[1.0]] * 20 + [[1.0, 2.0]],
        "episodes[0].readings[20]: expected",
    ),
]


def _hostile_run_file(tmp_path: Path, place: tuple[str | int, ...], value: object) -> Path:
    values = long_run(20).as_json()
    values["episodes"][0]["decisions"] = []
    target: Any = values
    for key in place[:-1]:
        target = target[key]
    target[place[-1]] = value
    path = tmp_path / "hostile.json"
    path.write_text(json.dumps(values))
    return path


@pytest.mark.parametrize(("place", "value", "field"), HOSTILE_FIELDS)
def test_a_damaged_field_is_a_format_error_naming_it(
    tmp_path: Path, place: tuple[str | int, ...], value: object, field: str
) -> None:
    path = _hostile_run_file(tmp_path, place, value)
    with pytest.raises(RunFormatError) as caught:
        load_run(path)
    assert f"{path}: {field}" in str(caught.value) or f"field {field}" in str(caught.value)


@pytest.mark.parametrize("out", ["page.html", "video.gif"])
def test_the_replay_command_refuses_a_damaged_run_in_one_line(
    tmp_path: Path, out: str, capsys: pytest.CaptureFixture[str]
) -> None:
    path = _hostile_run_file(tmp_path, ("control_step_ms",), 0)
    assert main(["replay", str(path), "-o", str(tmp_path / out), "--no-progress"]) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and "control_step_ms: expected a finite number above 0" in error
    assert not (tmp_path / out).exists()


def test_deep_nesting_and_a_gzip_bomb_are_format_errors(tmp_path: Path) -> None:
    deep = tmp_path / "deep.json"
    deep.write_text("[" * 200_000)
    with pytest.raises(RunFormatError, match="deeper nesting"):
        load_run(deep)
    bomb = tmp_path / "bomb.json.gz"
    bomb.write_bytes(gzip.compress(b" " * (MAX_RUN_BYTES + 1), 9))
    assert bomb.stat().st_size < MAX_RUN_BYTES // 500
    with pytest.raises(RunFormatError, match=f"at most {MAX_RUN_BYTES} bytes"):
        load_run(bomb)
    cut = tmp_path / "cut.json.gz"
    cut.write_bytes(gzip.compress(json.dumps(long_run(5).as_json()).encode())[:-40])
    with pytest.raises(RunFormatError, match="expected a mazesim run"):
        load_run(cut)


def test_a_run_under_a_file_name_of_another_encoding_replays(tmp_path: Path) -> None:
    """A file name with a byte that is not UTF-8 (Python keeps it as a surrogate) names the run
    in messages, shown as U+FFFD, instead of failing with 'expected source to be a str, found a
    str'."""
    path = tmp_path / os.fsdecode(b"run\xff.json")
    save_run(long_run(5), path)
    assert load_run(path).episodes[0].frames == 6
    page = tmp_path / os.fsdecode(b"page\xff.html")
    write_html(load_run(path), page)
    assert page.stat().st_size > 10_000
    with pytest.raises(mazesim.WorldFormatError, match="run\ufffd.toml"):
        mazesim.World.from_toml("walls = 3", os.fsdecode(b"run\xff.toml"))


def test_a_controller_name_cannot_break_out_of_the_page_script() -> None:
    run = long_run(3)
    run.controller = "<!--<script></script>--></script><b>x"
    page = replay_html(run)
    opening = '<script type="application/json" id="scene">'
    block = page[page.index(opening) + len(opening) :]
    block = block[: block.index("</script>")]
    assert "<" not in block
    assert json.loads(block)["run"]["controller"] == run.controller


def test_a_gzip_of_empty_lists_is_refused_before_parsing(tmp_path: Path) -> None:
    # 255 MiB of empty lists, under the byte limit, in a file of about 250 KiB: parsed, it took
    # 3.9 GB.
    bomb = tmp_path / "lists.json.gz"
    chunk = b"[]," * (1 << 20)
    with gzip.open(bomb, "wb", compresslevel=9) as handle:
        handle.write(b"[")
        for _ in range(85):
            handle.write(chunk)
        handle.write(b"[]]")
    assert bomb.stat().st_size < 400_000
    tracemalloc.start()
    try:
        with pytest.raises(RunFormatError, match="at most 4194304 lists and objects, found more"):
            load_run(bomb)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    # Refused after the first pieces are decompressed: 0.1 s and 75 MB in all, measured.
    assert peak < 64 * 2**20, f"{peak / 2**20:.0f} MiB"


def test_a_run_far_away_never_reaches_a_replay_page(tmp_path: Path) -> None:
    path = _hostile_run_file(tmp_path, ("episodes", 0, "x"), [1e300] * 21)
    page = tmp_path / "page.html"
    assert main(["replay", str(path), "-o", str(page), "--no-progress"]) == 2
    assert not page.exists()
    run = long_run(20)
    run.episodes[0].poses[:, 0] = 999.9
    write_html(run, page)
    assert "-9223372036854775808" not in page.read_text()
