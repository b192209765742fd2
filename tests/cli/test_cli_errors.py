"""Issue 15: no command writes over one of its inputs; every error is one line and exit 2."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from mazesim.cli import main
from mazesim.errors import MazesimIOError
from mazesim_process import mazesim_command
from ros_support import needs_ros

REPO = Path(__file__).resolve().parents[2]
WBT = REPO / "tests" / "data" / "webots-worlds" / "e-puck.R2023b.wbt"


def _one_error_line(result: subprocess.CompletedProcess[str]) -> str:
    assert result.returncode == 2, result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("mazesim: error: "), result.stderr
    return lines[0]


@pytest.mark.parametrize(
    "spelling",
    ["same", "absolute", "dotted", "symlink to it", "symlinked folder", "hard link"],
)
def test_import_wbt_refuses_to_overwrite_the_webots_source(tmp_path: Path, spelling: str) -> None:
    source = tmp_path / "worlds" / "x.wbt"
    source.parent.mkdir()
    shutil.copyfile(WBT, source)
    original = source.read_bytes()
    out = {
        "same": "worlds/x.wbt",
        "absolute": str(source),
        "dotted": "worlds/../worlds/./x.wbt",
        "symlink to it": "link.wbt",
        "symlinked folder": "linked/x.wbt",
        "hard link": "hard.wbt",
    }[spelling]
    if spelling == "symlink to it":
        (tmp_path / "link.wbt").symlink_to(source)
    elif spelling == "symlinked folder":
        (tmp_path / "linked").symlink_to(source.parent, target_is_directory=True)
    elif spelling == "hard link":
        os.link(source, tmp_path / "hard.wbt")
    line = _one_error_line(
        mazesim_command("import-wbt", "worlds/x.wbt", "--out", out, cwd=tmp_path)
    )
    assert "is the same file as the Webots world" in line
    assert "choose another --out" in line
    assert source.read_bytes() == original


def test_import_wbt_still_writes_another_file(tmp_path: Path) -> None:
    result = mazesim_command("import-wbt", str(WBT), "--out", "x.toml", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "x.toml").read_text().startswith('format = "mazesim-world"')


def test_eval_refuses_to_write_its_trace_over_the_navigator(tmp_path: Path) -> None:
    from mazesim.learn.tables import shipped_policy_dir

    navigator = tmp_path / "navigator"
    shutil.copytree(shipped_policy_dir(), navigator)
    before = (navigator / "policy.json").read_bytes()
    code = main(["eval", "--policy", str(navigator), "--trace", str(navigator / "policy.json")])
    assert code == 2
    assert (navigator / "policy.json").read_bytes() == before


@pytest.mark.parametrize("command", [["demo"], ["webots", "run", "--world", "arena"]])
def test_a_recording_too_long_to_hold_is_refused_before_the_run(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], command: list[str]
) -> None:
    # 1e6 simulated seconds of --html grew ~10 MB/s towards ~58 GB, to fail at the end.
    out = tmp_path / "out"
    args = [*command, "--seconds", "1000000", "--html", str(tmp_path / "r.html")]
    if command[0] == "webots":
        args.append(str(REPO / "tests" / "data" / "controllers" / "left_wall_state_machine.py"))
    code = main([*args, "--out", str(out), "--no-progress"])
    error = capsys.readouterr().err
    assert code == 2, error
    assert "expected --seconds of at most 10000 with --html" in error
    assert not (tmp_path / "r.html").exists() and not (out / "summary.json").exists()


@pytest.mark.parametrize(
    ("address", "said"),
    [
        ("127.0.0.1:1", "nothing answers there within 5 s"),
        ("localhost:99999", "a port from 1 to 65535"),
        ("ray://nohost", "a port from 1 to 65535"),
    ],
)
def test_a_ray_address_where_nothing_answers_is_refused_at_once(
    capsys: pytest.CaptureFixture[str], address: str, said: str
) -> None:
    # Ray itself retried a silent address for over a minute, printing its own log lines.
    pytest.importorskip("ray")
    code = main(["eval", "--episodes", "1", "--address", address, "--no-progress"])
    error = capsys.readouterr().err
    assert code == 2 and said in error, error
    assert error.count("\n") == 1, error


def test_sweep_refuses_an_output_folder_holding_its_sweep_file(tmp_path: Path) -> None:
    config = tmp_path / "sweep.toml"
    config.write_text('[sweep]\nname = "x"\n[grid]\ntrainer = "flat-q"\n')
    result = mazesim_command("sweep", "sweep.toml", "--out", ".", "--sequential", cwd=tmp_path)
    assert "is the same file as the sweep file" in _one_error_line(result)


def test_an_unexpected_error_is_one_line_not_a_traceback(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    import mazesim.cli.worlds

    def broken(out: object) -> int:
        raise TypeError("unsupported operand")

    monkeypatch.setattr(mazesim.cli.worlds, "run_worlds", broken)
    assert main(["worlds"]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert lines == [
        "mazesim: error: internal error, please report it with the command that caused it: "
        "TypeError: unsupported operand"
    ]


def test_a_package_error_that_is_also_an_os_error_keeps_its_own_message(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    import mazesim.cli.worlds
    from mazesim.errors import ClusterConnectionError

    def unreachable(out: object) -> int:
        raise ClusterConnectionError("could not join the Ray cluster at 127.0.0.1:1: set X")

    monkeypatch.setattr(mazesim.cli.worlds, "run_worlds", unreachable)
    assert main(["worlds"]) == 2
    assert capsys.readouterr().err.strip().splitlines() == [
        "mazesim: error: could not join the Ray cluster at 127.0.0.1:1: set X"
    ]


def test_running_out_of_memory_is_one_line(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    import mazesim.cli.worlds

    def greedy(out: object) -> int:
        raise MemoryError

    monkeypatch.setattr(mazesim.cli.worlds, "run_worlds", greedy)
    assert main(["worlds"]) == 2
    assert capsys.readouterr().err.startswith("mazesim: error: out of memory")


@pytest.mark.parametrize(
    "arguments",
    [
        ["demo", "--seconds", "1e300"],
        ["bench", "--block-steps", "-1"],
        ["bench", "--threads", "1" + "0" * 30],
        ["bench", "--envs", "1,99999999999"],
        ["train", "--steps", "1e40"],
        ["eval", "--episodes", "99999999999"],
        # ``mazesim ros`` checks for ROS 1 before it parses (a quick failure where it is missing).
        pytest.param(["ros", "bridge", "--speed", "1e300"], marks=needs_ros),
    ],
    ids=" ".join,
)
def test_numbers_beyond_the_limits_are_refused_by_the_parser(
    arguments: list[str], capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(arguments) == 2
    last = capsys.readouterr().err.strip().splitlines()[-1]
    assert "error: argument" in last, last
    assert any(limit in last for limit in ("at most", "at least", "in [")), last


def test_a_resume_with_no_checkpoint_is_refused_in_one_line_before_any_plan(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["train", "--out", str(tmp_path / "never-trained"), "--resume"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "no checkpoint to resume from" in err, err
    assert "whole round" not in err


def test_an_empty_output_path_is_refused_not_taken_for_the_current_folder(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    assert main(["train", "--out", ""]) == 2
    assert "--out: expected a path to write to, found ''" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_an_output_file_that_is_a_folder_is_refused_before_the_run(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["eval", "--episodes", "1", "--trace", str(tmp_path)]) == 2
    assert "is a folder; expected the path of a file" in capsys.readouterr().err


def test_an_os_error_names_the_file_and_the_reason_not_its_errno(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    device = Path(os.devnull)
    assert main(["webots", "run", str(WBT), "--seconds", "1", "--out", str(device)]) == 2
    assert capsys.readouterr().err == (
        f"mazesim: error: {device}: expected an output folder, found a character device; "
        "choose another --out\n"
    )
    assert device.is_char_device()


def test_an_unusable_output_folder_is_named_as_the_user_gave_it(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The one message names the command's option on the command line, the function's parameter
    in Python, and Python's again after a command has run."""
    from mazesim.learn import load_policy, save_policy

    (tmp_path / "a-file").write_text("kept\n")
    out = str(tmp_path / "a-file")
    assert main(["demo", "--seconds", "1", "--out", out]) == 2
    assert capsys.readouterr().err == (
        f"mazesim: error: {out}: expected an output folder, found a file; choose another --out\n"
    )
    with pytest.raises(MazesimIOError) as refused:
        save_policy(load_policy(), out)
    assert str(refused.value).endswith("found a file; choose another folder")
    assert (tmp_path / "a-file").read_text() == "kept\n"


def test_an_unfinished_run_is_told_to_pass_the_option_that_resumes_it(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "run").mkdir()
    (tmp_path / "run" / "checkpoint.npz").write_bytes(b"")
    command = ["train", "--out", str(tmp_path / "run"), "--no-progress"]
    assert main(command) == 2
    err = capsys.readouterr().err
    assert err.endswith("pass --resume to continue it, or choose another --out\n"), err


@pytest.mark.parametrize("command", ["show", "demo", "eval", "train"])
def test_a_mistyped_world_name_gets_the_name_meant(tmp_path: Path, command: str) -> None:
    world = ["seed_maze"] if command == "show" else ["--world", "seed_maze"]
    line = _one_error_line(mazesim_command(command, *world, cwd=tmp_path))
    assert line.endswith(
        "built-in worlds: arena, line-follow, seed-maze (or a path to a .toml "
        "or .wbt world file); did you mean 'seed-maze'?"
    ), line


def _mazesim_without(
    module: str, arguments: list[str], cwd: Path
) -> subprocess.CompletedProcess[str]:
    """``mazesim ARGUMENTS`` run as if ``module`` were not installed: its import fails."""
    return subprocess.run(
        [
            sys.executable,
            "-c",
            f"import sys; sys.modules[{module!r}] = None; "
            "from mazesim.cli import main; sys.exit(main(sys.argv[1:]))",
            *arguments,
        ],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )


@pytest.mark.parametrize(("module", "package"), [("matplotlib", "matplotlib"), ("PIL", "pillow")])
def test_a_missing_dependency_says_what_to_install(
    tmp_path: Path, module: str, package: str
) -> None:
    result = _mazesim_without(module, ["show", "seed-maze", "-o", "seed-maze.png"], tmp_path)
    line = _one_error_line(result)
    assert f"this command needs the Python package {package!r}, which is not installed" in line
    assert line.endswith(f"install it with {sys.executable} -m pip install {package}")
    assert "internal error" not in line


def test_a_dependency_that_fails_to_load_says_what_to_do_not_internal_error(tmp_path: Path) -> None:
    # A compiled module that the system cannot map (a ulimit on memory, a broken install) fails
    # with an ImportError that is no ModuleNotFoundError: installed, but it cannot be loaded.
    fake = tmp_path / "site-packages" / "matplotlib"
    fake.mkdir(parents=True)
    (fake / "__init__.py").write_text(
        "raise ImportError('_path.so: failed to map segment from shared object', "
        f"path={str(fake / '_path.so')!r})\n"
    )
    result = subprocess.run(
        [sys.executable, "-m", "mazesim", "show", "seed-maze", "-o", "seed-maze.png"],
        cwd=tmp_path,
        env={**os.environ, "PYTHONPATH": str(fake.parent)},
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    line = _one_error_line(result)
    assert "the Python package 'matplotlib', which is installed but could not be loaded" in line
    assert "failed to map segment from shared object" in line
    assert line.endswith(f"{sys.executable} -m pip install --force-reinstall matplotlib")
    assert "internal error" not in line


#: The commands that take ``--world``, as a mistaken ``--world`` is told of them.
TAKING_WORLD = ", ".join(
    f"mazesim {command}"
    for command in (
        "barcode-study",
        "demo",
        "eval",
        "ros bridge",
        "ros demo",
        "ros2 bridge",
        "ros2 demo",
        "train",
        "webots run",
    )
)


@pytest.mark.parametrize(
    ("arguments", "usage", "error"),
    [
        (
            ["demo", "--seeed", "3"],
            "mazesim demo",
            "--seeed 3; did you mean '--seed' for '--seeed'?",
        ),
        (
            ["eval", "--episods=3"],
            "mazesim eval",
            "--episods=3; did you mean '--episodes' for '--episods'?",
        ),
        (["webots", "run", "x.wbt", "--secnds", "3"], "mazesim webots run", "--secnds 3; did "),
        (["bench", "--world", "seed-maze"], "mazesim bench", "--world seed-maze"),
    ],
)
def test_an_option_the_command_does_not_take_shows_its_usage_and_the_one_meant(
    capsys: pytest.CaptureFixture[str], arguments: list[str], usage: str, error: str
) -> None:
    assert main(arguments) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert lines[0].startswith(f"usage: {usage} "), lines
    assert lines[-1].startswith(f"{usage}: error: unrecognized arguments: {error}"), lines
    if arguments[0] == "bench":  # --world is not --workload: no guess, but who takes --world
        assert "did you mean" not in lines[-1], lines
        assert lines[-1].endswith("; --world is an option of " + TAKING_WORLD), lines


@pytest.mark.parametrize(
    ("arguments", "usage", "error"),
    [
        (["trian"], "mazesim", "argument COMMAND: invalid choice: 'trian' (choose from "),
        (["webots", "rn", "x.py"], "mazesim webots", "argument COMMAND: invalid choice: 'rn' "),
        (["demo", "--controller", "hrll"], "mazesim demo", "argument --controller: invalid "),
        (["bench", "--workload", "contcat"], "mazesim bench", "argument --workload: invalid "),
        # A name cut short: the one choice it starts (#35).
        (["demo", "--controller", "avoid"], "mazesim demo", "argument --controller: invalid "),
    ],
)
def test_a_mistyped_command_or_choice_gets_the_one_meant(
    capsys: pytest.CaptureFixture[str], arguments: list[str], usage: str, error: str
) -> None:
    meant = {
        "trian": "train",
        "rn": "run",
        "hrll": "hrl",
        "contcat": "contact",
        "avoid": "avoid-collision",
    }
    typed = next(word for word in arguments if word in meant)
    assert main(arguments) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line.startswith(f"{usage}: error: {error}"), line
    assert line.endswith(f"; did you mean {meant[typed]!r}?"), line


def test_a_choice_like_none_of_them_gets_no_guess(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["bench", "--workload", "xyz"]) == 2
    assert capsys.readouterr().err.strip().splitlines()[-1] == (
        "mazesim bench: error: argument --workload: invalid choice: 'xyz' (choose from "
        "'braitenberg', 'contact', 'random')"
    )


def test_a_list_of_names_gets_the_ones_meant(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["transfer-study", "--axes", "latncy,robot,slpi,zzz"]) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line.endswith(
        "found 'latncy,robot,slpi,zzz'; did you mean 'latency' for 'latncy', 'slip' for 'slpi'?"
    ), line


def test_eval_gets_random_meant_for_its_typo(tmp_path: Path) -> None:
    line = _one_error_line(mazesim_command("eval", "--world", "randm", cwd=tmp_path))
    assert line.endswith(
        "world file), or 'random' for unseen generated 5 x 5 mazes; did you mean 'random'?"
    ), line


def test_eval_gets_the_shipped_navigator_meant_for_its_typo(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    for typed, meant in (("randomized", "; did you mean 'randomised'?"), ("my-run", "")):
        assert main(["eval", "--policy", typed, "--episodes", "1"]) == 2
        line = capsys.readouterr().err.strip().splitlines()[-1]
        assert line.endswith(f"('randomised'; without --policy, the seed-maze navigator){meant}"), (
            line
        )


def test_eval_gets_the_trained_navigator_beside_meant_for_its_typo(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    from mazesim.learn import load_policy, save_policy

    monkeypatch.chdir(tmp_path)
    save_policy(load_policy("randomised"), tmp_path / "runs" / "my nav")
    (tmp_path / "runs" / "my-notes").mkdir()  # a folder, but no navigator: never meant
    for typed, meant in (
        ("runs/my-nav", "; did you mean 'runs/my nav'?"),
        ("runs/my-note", ""),
    ):
        assert main(["eval", "--policy", typed, "--episodes", "1"]) == 2
        line = capsys.readouterr().err.strip().splitlines()[-1]
        assert line.endswith(f"the seed-maze navigator){meant}"), line


def _walled_in(start: str) -> str:
    """A 2 x 2-cell world named walled-in whose [start] table is ``start``."""
    rows = ["+--+--+", "|S    |", "+--+  +", "|G    |", "+--+--+"]
    return (
        'format = "mazesim-world"\nversion = 1\nname = "walled-in"\n'
        f"[start]\n{start}\n[grid]\nmap = '''\n" + "\n".join(rows) + "\n'''\n"
    )


def test_every_command_names_the_world_file_whose_start_is_in_a_wall(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "walled.toml").write_text(_walled_in("x = 0.0\ny = 0.375"))
    for command in (["demo"], ["demo", "--robot", "e-puck2"], ["barcode-study"], ["train"]):
        assert main([*command, "--world", "walled.toml", "--out", "out"]) == 2
        line = capsys.readouterr().err.strip().splitlines()[-1]
        assert "world 'walled-in' (walled.toml): expected a start pose where the robot" in line
        assert "found (0, 0.375, 0) with its centre" in line, line
        assert line.endswith(
            ": move the [start] pose to the middle of a cell, or put an S in a cell of the "
            "[grid] map"
        ), line
    assert not (tmp_path / "out").exists()


def test_a_start_in_a_wall_of_a_world_without_cells_is_told_to_move_to_open_floor(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "pillar.toml").write_text(
        'format = "mazesim-world"\nversion = 1\n[start]\nx = 0.5\ny = 0.5\n'
        "[[walls]]\ncenter = [0.5, 0.5]\nsize = [0.2, 0.2]\n"
    )
    assert main(["demo", "--world", "pillar.toml", "--out", "out"]) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert "world 'pillar' (pillar.toml): expected a start pose" in line, line
    assert line.endswith(
        ": move the [start] pose to open floor, farther from every wall than the robot's radius"
    ), line


def test_sweep_without_ray_names_the_sequential_run(tmp_path: Path) -> None:
    shutil.copyfile(REPO / "examples" / "sweep.toml", tmp_path / "my sweep.toml")
    result = _mazesim_without("ray", ["sweep", "my sweep.toml"], tmp_path)
    line = _one_error_line(result)
    assert "running on Ray needs the 'ray' package: pip install 'mazesim[ray]'" in line
    assert line.endswith("without Ray: mazesim sweep 'my sweep.toml' --sequential"), line
    assert not (tmp_path / "mazesim-sweep").exists()


@pytest.mark.parametrize(
    ("file", "language"),
    [
        ("Avoid.java", "Java"),
        ("avoid.jar", "Java"),
        ("avoid.m", "MATLAB"),
    ],
)
def test_webots_run_refuses_a_controller_in_another_language(
    tmp_path: Path, file: str, language: str
) -> None:
    (tmp_path / file).write_text("public class Avoid {}\n", encoding="utf-8")
    line = _one_error_line(mazesim_command("webots", "run", file, "--seconds", "1", cwd=tmp_path))
    assert line == (
        f"mazesim: error: {tmp_path / file}: expected a Python, C, C++ or BotStudio controller "
        f"(.py, .c, .cpp, .cc, .cxx, .bsg), found a {language} controller, which mazesim does not "
        "run"
    )


def test_webots_run_names_the_other_language_a_controller_folder_holds(tmp_path: Path) -> None:
    folder = tmp_path / "controllers" / "avoid"
    folder.mkdir(parents=True)
    (folder / "avoid.m").write_text("wb_robot_init();\n", encoding="utf-8")
    line = _one_error_line(
        mazesim_command("webots", "run", "controllers/avoid", "--seconds", "1", cwd=tmp_path)
    )
    assert line.endswith("found a folder with avoid.m (MATLAB), which mazesim does not run"), line


@pytest.mark.parametrize(
    ("arguments", "said"),
    [
        (
            ["show", "--world", "seed-maze"],
            "mazesim show: error: unrecognized arguments: --world; WORLD is given without "
            "'--world': mazesim show WORLD",
        ),
        (
            ["replay", "--run", "x.json", "-o", "x.html"],
            "mazesim replay: error: unrecognized arguments: --run; RUN is given without '--run': "
            "mazesim replay RUN",
        ),
        (
            [],
            "mazesim: error: the following arguments are required: COMMAND (one of: worlds, demo, "
            "bench, ros, ros2, barcode-study, transfer-study, import-wbt, webots, sweep, train, "
            "eval, replay, show, info; 'mazesim COMMAND --help' gives its options)",
        ),
        (
            ["webots"],
            "mazesim webots: error: the following arguments are required: COMMAND (one of: run; "
            "'mazesim webots COMMAND --help' gives its options)",
        ),
    ],
)
def test_a_usage_error_says_how_the_command_takes_its_arguments(
    capsys: pytest.CaptureFixture[str], arguments: list[str], said: str
) -> None:
    # An argument given with an option it is taken without; a command without its subcommand.
    assert main(arguments) == 2
    assert capsys.readouterr().err.strip().splitlines()[-1] == said


def test_a_world_file_without_a_name_is_called_after_the_file(tmp_path: Path) -> None:
    (tmp_path / "corridor.toml").write_text(
        'format = "mazesim-world"\nversion = 1\n'
        '[grid]\nmap = """\n+--+--+\n|S   G|\n+--+--+\n"""\n',
        encoding="utf-8",
    )
    line = _one_error_line(mazesim_command("train", "--world", "corridor.toml", cwd=tmp_path))
    assert line.startswith(
        "mazesim: error: the navigator cannot learn world 'corridor' (corridor.toml): "
    ), line
    shown = mazesim_command("demo", "--world", "corridor.toml", "--seconds", "1", cwd=tmp_path)
    assert shown.stdout.startswith("world              corridor (robot e-puck, seed 0)\n")


NO_WAY_TO_THE_GOAL = '''format = "mazesim-world"
version = 1
name = "walled-in"

[grid]
map = """
+--+--+--+
|S       |
+--+--+--+
|       G|
+--+--+--+
"""
'''


@pytest.mark.parametrize(
    ("command", "verb"),
    [
        (["train", "--world", "walled.toml", "--out", "nav", "--steps", "1k"], "learn"),
        (["eval", "--world", "walled.toml", "--episodes", "2"], "drive"),
        (["demo", "--controller", "hrl", "--world", "walled.toml"], "drive"),
    ],
)
def test_every_navigator_command_refuses_a_maze_without_a_way_alike(
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
    command: list[str],
    verb: str,
) -> None:
    (tmp_path / "walled.toml").write_text(NO_WAY_TO_THE_GOAL)
    monkeypatch.chdir(tmp_path)
    assert main(command) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line.startswith(
        f"mazesim: error: the navigator cannot {verb} world 'walled-in' (walled.toml): its goal "
        "(cell column 2, row 1) cannot be reached from the start (cell column 0, row 0): open a "
        "way through the walls of the [grid] map, or move S or G"
    ), line
    assert sorted(path.name for path in tmp_path.iterdir()) == ["walled.toml"]


@pytest.mark.parametrize(
    ("command", "missing", "meant"),
    [
        (["import-wbt", "boxs.wbt"], "boxs.wbt", "'boxes.wbt"),
        (["show", "boxs.wbt"], "boxs.wbt", "'boxes.wbt"),
        (
            ["webots", "run", "avoid_collision", "--world", "boxes.wbt"],
            "avoid_collision",
            "/avoid_collision.py",
        ),
        (["replay", "ru.json.gz", "-o", "replay.html"], "ru.json.gz", "'run.json.gz"),
    ],
)
def test_a_mistyped_input_file_names_the_folder_and_the_file_meant(
    monkeypatch: pytest.MonkeyPatch,
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    command: list[str],
    missing: str,
    meant: str,
) -> None:
    monkeypatch.chdir(tmp_path)
    shutil.copyfile(REPO / "examples" / "worlds" / "boxes.wbt", tmp_path / "boxes.wbt")
    shutil.copyfile(REPO / "examples" / "webots" / "avoid_collision.py", "avoid_collision.py")
    Path("boxes.png").write_bytes(b"")
    Path("run.json.gz").write_bytes(b"")
    assert main(command) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert "No such file or directory: there is no " in line or "there is no file" in line, line
    assert missing in line and str(tmp_path) in line, line
    assert "; did you mean '" in line and line.endswith(f"{meant}'?"), line


def test_an_input_file_in_a_missing_folder_names_the_folder(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    assert main(["import-wbt", "worlds/boxes.wbt"]) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line.endswith(f"No such file or directory: there is no folder 'worlds' in {tmp_path}")


def test_an_option_of_another_command_names_the_commands_that_take_it(
    capsys: pytest.CaptureFixture[str],
) -> None:
    # A navigator trained with `mazesim train` is watched with eval, not demo.
    assert main(["demo", "--controller", "hrl", "--policy", "my-navigator"]) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line.startswith("mazesim demo: error: unrecognized arguments: --policy my-navigator; ")
    assert "--policy is an option of mazesim eval, " in line, line
    assert "mazesim demo," not in line
    assert main(["show", "seed-maze", "--episodes", "3"]) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line.endswith("--episodes is an option of mazesim eval, mazesim transfer-study"), line
    assert main(["eval", "--no-such-option"]) == 2  # nobody takes it: nothing added
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line.endswith("unrecognized arguments: --no-such-option"), line


def test_a_slip_of_the_commands_own_option_is_told_that_option_before_other_commands(
    capsys: pytest.CaptureFixture[str],
) -> None:
    # `mazesim eval --episode 3` was told that replay takes --episode, not eval's --episodes.
    assert main(["eval", "--episode", "3"]) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line.endswith("did you mean '--episodes' for '--episode'?"), line
    assert "mazesim replay" not in line, line


def test_the_navigator_demo_refuses_a_robot_it_would_not_drive(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # It drove the seed robot whatever --robot said, and its summary said "robot seed".
    monkeypatch.chdir(tmp_path)
    assert main(["demo", "--controller", "hrl", "--robot", "e-puck2", "--out", "out"]) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line.endswith(
        "--robot e-puck2: mazesim demo --controller hrl drives the shipped navigator on the seed "
        "robot it was trained for, and takes no other robot; to watch the navigator drive "
        "e-puck2: mazesim eval --robot e-puck2 --episodes 1 --html run.html"
    ), line
    assert not (tmp_path / "out").exists()
    assert main(["demo", "--robot", "e-puck2", "--seconds", "1", "--out", "out"]) == 0
    assert "(robot e-puck2, seed 0)" in capsys.readouterr().out


def test_training_on_a_world_without_cells_says_how_to_make_one(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    shutil.copyfile(REPO / "examples" / "worlds" / "boxes.wbt", tmp_path / "boxes.wbt")
    assert main(["train", "--world", "boxes.wbt", "--out", "nav", "--steps", "1M"]) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line.endswith(
        "found none in 'boxes' (its walls are boxes, as every imported Webots world's are): draw "
        "the maze as a [grid] map of +--+ and | in a .toml world file (docs/world-format.md), or "
        "generate one with mazesim.generate_maze"
    ), line
    assert not (tmp_path / "nav").exists()


def test_an_option_is_taken_by_its_whole_name_only(
    capsys: pytest.CaptureFixture[str],
) -> None:
    # `webots run C.py --robot my-robot.toml` was read as the prefix of --robot-controller and
    # refused with a message about that option, which the newcomer never typed.
    # `webots run` now takes --robot itself: the error is the missing controller's.
    assert main(["webots", "run", "c.py", "--robot", "my-robot.toml"]) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert "--robot" not in line and "cannot read the controller" in line, line
    assert main(["show", "seed-maze", "--robot", "my-robot.toml"]) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line.startswith("mazesim show: error: unrecognized arguments: --robot "), line
    assert "--robot is an option of mazesim " in line and "mazesim webots run" in line, line
    assert main(["demo", "--sec", "2"]) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line.endswith("unrecognized arguments: --sec 2; did you mean '--seconds' for '--sec'?")


@pytest.mark.parametrize(
    ("typed", "meant", "where"),
    [
        ("braitenburg", "braitenberg", "mazesim bench --workload"),
        ("avoid-colision", "avoid-collision", "mazesim demo --controller"),
        ("e-puck_avoid_obstacle", "e-puck_avoid_obstacles", "its PROTO's default"),
    ],
)
def test_a_mistyped_built_in_controller_is_told_the_one_meant(
    capsys: pytest.CaptureFixture[str], typed: str, meant: str, where: str
) -> None:
    assert main(["webots", "run", "world.wbt", typed]) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line.startswith(f"mazesim webots run: error: unrecognized arguments: {typed}; "), line
    assert f"did you mean the built-in controller {meant!r}? it runs in " in line, line
    assert where in line, line


def test_a_stray_word_far_from_every_built_in_controller_is_told_none(
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert main(["webots", "run", "world.wbt", "banana"]) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line == "mazesim webots run: error: unrecognized arguments: banana", line


@pytest.mark.parametrize(
    "argv",
    [
        ["q" * 200_000],
        ["worlds", "--export", "z" * 200_000],
        ["demo", "--robot", "r" * 200_000, "--seconds", "0.1"],
    ],
)
def test_a_word_of_200000_characters_is_quoted_shortened(
    argv: list[str], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The usage error names the word by its start and end, in a message of a few lines."""
    assert main([*argv, *(["--out", str(tmp_path / "out")] if argv[0] == "demo" else [])]) == 2
    err = capsys.readouterr().err
    assert "characters ...]" in err and len(err) < 6000, len(err)


def test_a_wbt_of_one_5_mb_line_is_refused_in_a_short_message(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    world = tmp_path / "one-line.wbt"
    world.write_text("#VRML_SIM R2023b utf8\n" + "A" * (5 << 20), encoding="utf-8")
    assert main(["import-wbt", str(world)]) in (1, 2)
    err = capsys.readouterr().err
    assert err.startswith("mazesim: error:") and len(err) < 6000, len(err)
