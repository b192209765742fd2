"""The ``mazesim`` command line, run as ``python -m mazesim`` in a subprocess."""

from __future__ import annotations

import json
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

import mazesim
from mazesim.cli import main
from mazesim_process import mazesim_command

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
BUILTIN_WORLDS = ("seed-maze", "line-follow", "arena")


def assert_one_line_error(result: subprocess.CompletedProcess[str]) -> str:
    assert result.returncode == 2, result.stderr
    assert "Traceback" not in result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith("mazesim: error: ")
    return lines[0]


def test_worlds_lists_each_builtin(tmp_path: Path) -> None:
    result = mazesim_command("worlds", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.strip().splitlines()
    assert len(lines) == len(BUILTIN_WORLDS)
    by_name = {line.split()[0]: line for line in lines}
    assert set(by_name) == set(BUILTIN_WORLDS)
    assert "7 checkpoints" in by_name["seed-maze"]
    assert "0 checkpoints" in by_name["arena"]
    assert " m " in by_name["arena"]


def test_worlds_exports_a_builtin_world_to_edit_and_keeps_an_existing_file(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    import mazesim

    mine = tmp_path / "my-maze.toml"
    assert main(["worlds", "--export", "seed-maze", "--out", str(mine)]) == 0
    assert f"wrote {mine}" in capsys.readouterr().out
    assert mazesim.load_world(str(mine)) == mazesim.World.builtin("seed-maze")
    assert "|S  " in mine.read_text()  # the [grid] map, to edit
    mine.write_text(mine.read_text() + "# my edit\n")
    assert main(["worlds", "--export", "arena", "-o", str(mine)]) == 2
    assert "exists: name another file, or add --force" in capsys.readouterr().err
    assert mine.read_text().endswith("# my edit\n")
    assert main(["worlds", "--export", "arena", "-o", str(mine), "--force"]) == 0
    assert mazesim.load_world(str(mine)) == mazesim.World.builtin("arena")
    assert main(["worlds", "--export", "seed-maz", "-o", str(tmp_path / "x.toml")]) == 2
    assert "did you mean 'seed-maze'?" in capsys.readouterr().err
    assert main(["worlds", "--export", str(mine), "-o", str(tmp_path / "y.toml")]) == 2
    assert "expected the name of a built-in world to export" in capsys.readouterr().err
    for suffix in (".wbt", ".png", ""):  # a world file's name says it is one
        assert main(["worlds", "--export", "arena", "-o", str(tmp_path / f"w{suffix}")]) == 2
        assert "expected a world file ending in .toml" in capsys.readouterr().err
        assert not (tmp_path / f"w{suffix}").exists()
    assert main(["worlds", "--force"]) == 2
    assert main(["worlds", "--out", str(tmp_path / "x.toml")]) == 2
    assert "expected --out with --export NAME" in capsys.readouterr().err
    monkeypatch.chdir(tmp_path)  # without --out: NAME.toml in the current folder
    assert main(["worlds", "--export", "arena"]) == 0
    assert mazesim.load_world(str(tmp_path / "arena.toml")) == mazesim.World.builtin("arena")
    assert not (tmp_path / "x.toml").exists() and not (tmp_path / "y.toml").exists()


def test_worlds_exported_to_stdout_pipes_a_world_file_alone(tmp_path: Path) -> None:
    import mazesim

    result = mazesim_command(
        "worlds", "--export", "arena", "--out", "/dev/stdout", "--force", cwd=tmp_path
    )
    assert result.returncode == 0, result.stderr
    piped = tmp_path / "piped.toml"
    piped.write_text(result.stdout)
    assert mazesim.load_world(str(piped)) == mazesim.World.builtin("arena")
    assert "wrote /dev/stdout" in result.stderr


def test_help_names_the_commands(tmp_path: Path) -> None:
    result = mazesim_command("--help", cwd=tmp_path)
    assert result.returncode == 0
    assert "worlds" in result.stdout and "demo" in result.stdout
    demo_help = mazesim_command("demo", "--help", cwd=tmp_path)
    assert demo_help.returncode == 0
    for option in ("--world", "--seconds", "--seed", "--out", "--robot"):
        assert option in demo_help.stdout


def test_demo_writes_picture_and_summary(tmp_path: Path) -> None:
    result = mazesim_command("demo", "--seconds", "5", "--out", "tmp", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "distance travelled" in result.stdout
    out = tmp_path / "tmp"
    assert sorted(p.name for p in out.iterdir()) == ["summary.json", "trajectory.png"]
    picture = (out / "trajectory.png").read_bytes()
    assert picture.startswith(PNG_MAGIC) and len(picture) > 10_000
    summary = json.loads((out / "summary.json").read_text())
    assert summary["world"] == "seed-maze"
    assert summary["robot"] == "e-puck"
    assert summary["seed"] == 0
    assert 5.0 <= summary["simulated_seconds"] < 5.1
    assert summary["steps"] == 157
    assert 0.1 < summary["distance_m"] < 5.1 * 0.13
    assert isinstance(summary["collisions"], int) and summary["collisions"] >= 0
    assert summary["wall_clock_seconds"] > 0
    assert summary["real_time_factor"] > 1
    assert summary["goal_reached"] is False


def test_demo_is_reproducible_from_its_seed(tmp_path: Path) -> None:
    runs = []
    for out in ("a", "b"):
        code = main(
            [
                "demo",
                "--world",
                "arena",
                "--seconds",
                "3",
                "--seed",
                "5",
                "--out",
                str(tmp_path / out),
            ]
        )
        assert code == 0
        runs.append(json.loads((tmp_path / out / "summary.json").read_text()))
    for field in ("distance_m", "collisions", "steps", "simulated_seconds"):
        assert runs[0][field] == runs[1][field]


def test_bad_world_path_is_a_one_line_error(tmp_path: Path) -> None:
    result = mazesim_command(
        "demo", "--world", "no/such/world.toml", "--seconds", "1", cwd=tmp_path
    )
    line = assert_one_line_error(result)
    assert "no/such/world.toml" in line
    for name in BUILTIN_WORLDS:
        assert name in line
    assert not (tmp_path / "mazesim-demo").exists()


def test_malformed_world_file_is_a_one_line_error(tmp_path: Path) -> None:
    (tmp_path / "broken.toml").write_text(
        'format = "mazesim-world"\nversion = 1\n\n[floor]\nreflectance = "grey"\n'
    )
    result = mazesim_command("demo", "--world", "broken.toml", "--seconds", "1", cwd=tmp_path)
    line = assert_one_line_error(result)
    assert "broken.toml" in line and "reflectance" in line


def test_unknown_robot_is_a_one_line_error(tmp_path: Path) -> None:
    result = mazesim_command("demo", "--robot", "no-such-robot", "--seconds", "1", cwd=tmp_path)
    line = assert_one_line_error(result)
    assert "no-such-robot" in line and "e-puck" in line


def test_robot_without_eight_proximity_sensors_is_refused(tmp_path: Path) -> None:
    result = mazesim_command("demo", "--robot", "seed", "--seconds", "1", cwd=tmp_path)
    line = assert_one_line_error(result)
    assert "8 raw proximity sensors" in line and "'seed'" in line


def test_output_folder_that_is_a_file_is_a_one_line_error(tmp_path: Path) -> None:
    (tmp_path / "taken").write_text("not a folder")
    result = mazesim_command("demo", "--seconds", "1", "--out", "taken", cwd=tmp_path)
    line = assert_one_line_error(result)
    assert "taken" in line


@pytest.mark.parametrize("seconds", ["0", "-3", "soon", "nan"])
def test_bad_seconds_is_a_usage_error(seconds: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["demo", "--seconds", seconds]) == 2
    assert "--seconds" in capsys.readouterr().err


def test_missing_command_is_a_usage_error(capsys: pytest.CaptureFixture[str]) -> None:
    assert main([]) == 2
    assert "usage: mazesim" in capsys.readouterr().err


def test_make_demo_command_drives_seed_maze_to_the_goal(tmp_path: Path) -> None:
    """`make demo` runs this: the shipped navigator reaches the goal and the picture is written."""
    out = tmp_path / "demo"
    done = subprocess.run(
        [sys.executable, "-m", "mazesim", "demo", "--controller", "hrl", "--out", str(out)],
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    assert (out / "trajectory.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    summary = json.loads((out / "summary.json").read_text())
    assert summary["goal_reached"] is True
    assert summary["collisions"] == 0
    # Every figure is told what it is where it is printed: the decisions' signed numbers too.
    decisions = next(line for line in done.stdout.splitlines() if line.startswith("decisions"))
    assert decisions.startswith("decisions          +1: Left turn on a door, "), decisions
    assert decisions.endswith(
        "(the sub-task chosen at each barcode: +N arriving at checkpoint N, -N leaving it)"
    ), decisions


def test_demo_drives_the_e_puck2_with_its_proximity_sensors(tmp_path: Path) -> None:
    # The e-puck2 lists its ToF beside ps0-ps7; Alg. 1 reads ps0-ps7 by name.
    result = mazesim_command(
        "demo",
        "--robot",
        "e-puck2",
        "--world",
        "arena",
        "--seconds",
        "3",
        "--out",
        "out",
        cwd=tmp_path,
    )
    assert result.returncode == 0, result.stderr
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["robot"] == "e-puck2" and summary["distance_m"] > 0.1


def test_a_reader_closing_the_pipe_ends_the_command_quietly() -> None:
    # `mazesim worlds | head -0`: the reader is gone before the first line is written.
    process = subprocess.Popen(
        [sys.executable, "-m", "mazesim", "worlds"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    assert process.stdout is not None and process.stderr is not None
    process.stdout.close()
    with process.stderr:
        error = process.stderr.read()
    assert process.wait(timeout=300) == 141  # 128 + SIGPIPE, as shells report it
    assert error == b""


#: What ``next`` says when a run command wrote no replay page.
NO_REPLAY = "; add --html run.html for a replay to watch in a browser"


@pytest.mark.parametrize(
    ("arguments", "then"),
    [
        (["demo", "--seconds", "1", "--out", "run"], f"open run/trajectory.png{NO_REPLAY}"),
        (
            ["demo", "--seconds", "1", "--out", "run", "--html", "run/replay.html"],
            "open run/replay.html in a browser to watch the run (offline)",
        ),
        (
            ["demo", "--seconds", "1", "--out", "my runs", "--html", "my runs/replay.html"],
            "open 'my runs/replay.html' in a browser to watch the run (offline)",
        ),
        (
            ["demo", "--seconds", "1", "--out", "l'essai"],
            "open 'l'\"'\"'essai/trajectory.png'" + NO_REPLAY,
        ),
        (
            ["webots", "run", "CONTROLLER", "--seconds", "1"],
            "open TMP/mazesim-webots/trajectory.png" + NO_REPLAY,
        ),
    ],
)
def test_a_run_command_ends_with_what_to_open_next(
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
    arguments: list[str],
    then: str,
) -> None:
    example = Path(__file__).resolve().parents[2] / "examples" / "webots" / "avoid_collision.py"
    monkeypatch.chdir(tmp_path)
    assert main([str(example) if word == "CONTROLLER" else word for word in arguments]) == 0
    last = capsys.readouterr().out.splitlines()[-1]
    assert last == f"next               {then.replace('TMP', str(tmp_path))}"


def test_the_paths_a_run_command_prints_paste_into_a_shell_as_the_files_it_wrote(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    out = "my runs/d\u00e9mo $1"
    assert main(["demo", "--seconds", "1", "--out", out, "--html", f"{out}/replay.html"]) == 0
    lines = capsys.readouterr().out.splitlines()
    wrote = lines[-2].removeprefix("wrote").strip()
    files = [shlex.split(word)[0] for word in wrote.split(", ")]
    assert files and all((tmp_path / file).is_file() for file in files), files
    (page,) = shlex.split(lines[-1])[2:3]
    assert page == f"{out}/replay.html" and (tmp_path / page).is_file()


def test_a_demo_of_a_robot_profile_file_names_the_file(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # The docs' recipe: a copy of the e-puck's profile, edited; its name inside is still e-puck.
    monkeypatch.chdir(tmp_path)
    text = mazesim.RobotProfile.builtin("e-puck").to_toml()
    Path("my-robot.toml").write_text(text.replace("wheel_radius = 0.02\n", "wheel_radius = 0.03\n"))
    assert main(["demo", "--robot", "my-robot.toml", "--seconds", "1", "--out", "mine"]) == 0
    assert "(robot e-puck from my-robot.toml, seed 0)" in capsys.readouterr().out
    mine = json.loads(Path("mine/summary.json").read_text())
    assert (mine["robot"], mine["robot_file"]) == ("e-puck", "my-robot.toml")
    assert main(["demo", "--robot", "e-puck", "--seconds", "1", "--out", "builtin"]) == 0
    builtin = json.loads(Path("builtin/summary.json").read_text())
    assert builtin["robot"] == "e-puck" and "robot_file" not in builtin
