"""Issue 37: a robot profile of one's own, a built-in profile's TOML saved to a file and edited, is
taken wherever a robot is (``RobotProfile.load``, the simulators' and environments' ``robot``,
the commands' ``--robot``), as a world file is wherever a world is; a name that is neither says
what it looked for and the file meant."""

from __future__ import annotations

import json
from pathlib import Path

import gymnasium
import pytest

import mazesim
from mazesim import BatchSimulator, RobotProfile, Simulator
from mazesim.cli import main
from mazesim.errors import UnknownNameError


def _slow_epuck(folder: Path) -> Path:
    """The e-puck's profile with a motor limit of 3 rad/s, saved as ``slow-epuck.toml``."""
    text = RobotProfile.builtin("e-puck").to_toml()
    assert "max_wheel_speed = 6.28" in text
    path = folder / "slow-epuck.toml"
    path.write_text(text.replace("max_wheel_speed = 6.28", "max_wheel_speed = 3.0"))
    return path


def test_a_profile_file_is_loaded_by_path_and_an_unedited_copy_is_the_builtin(
    tmp_path: Path,
) -> None:
    slow = _slow_epuck(tmp_path)
    assert RobotProfile.load(str(slow)).max_wheel_speed == 3.0
    assert RobotProfile.load(slow).max_wheel_speed == 3.0  # an os.PathLike too
    copy = tmp_path / "copy.toml"
    copy.write_text(RobotProfile.builtin("seed").to_toml())
    assert RobotProfile.load(str(copy)) == RobotProfile.builtin("seed")
    assert RobotProfile.load("seed") == RobotProfile.builtin("seed")


def test_every_robot_argument_takes_a_profile_file(tmp_path: Path) -> None:
    slow = _slow_epuck(tmp_path)
    world = mazesim.load_world("seed-maze")
    assert Simulator(world, robot=str(slow)).robot.max_wheel_speed == 3.0
    assert Simulator(world, robot=slow).robot.max_wheel_speed == 3.0
    batch = BatchSimulator(world, num_envs=2, robot=[str(slow), "e-puck"])
    assert batch.num_envs == 2
    env = gymnasium.make("mazesim/EPuckMaze-v0", robot=str(slow))
    assert env.unwrapped.options.robot.max_wheel_speed == 3.0
    env.close()


def test_the_demo_drives_a_profile_file(tmp_path: Path) -> None:
    slow = _slow_epuck(tmp_path)
    out = tmp_path / "demo"
    assert main(["demo", "--robot", str(slow), "--seconds", "1", "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["robot"] == "e-puck"  # the profile's own name, not the file's


def test_a_builtin_name_wins_over_a_file_of_that_name(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "seed").write_text("not a profile")
    assert RobotProfile.load("seed") == RobotProfile.builtin("seed")


def test_a_mistyped_profile_file_is_told_the_file_beside_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    _slow_epuck(tmp_path)
    monkeypatch.chdir(tmp_path)
    with pytest.raises(UnknownNameError) as raised:
        Simulator(mazesim.load_world("seed-maze"), robot="slow-epuk.toml")
    said = str(raised.value)
    assert said.startswith(
        f"no robot profile file 'slow-epuk.toml': there is no file 'slow-epuk.toml' in {tmp_path}"
    )
    assert str(tmp_path) in said and "built-in robot profiles: alphabot2, e-puck" in said
    assert "a robot profile .toml file" in said and "to_toml()" in said
    assert said.endswith("did you mean 'slow-epuck.toml'?")
    assert main(["demo", "--robot", "epuck", "--seconds", "1"]) == 2


def test_a_folder_or_a_broken_profile_file_says_what_it_is(tmp_path: Path) -> None:
    with pytest.raises(UnknownNameError, match="it is a folder, not a robot profile file"):
        RobotProfile.load(str(tmp_path))
    broken = tmp_path / "broken.toml"
    broken.write_text(_slow_epuck(tmp_path).read_text().replace("max_wheel_speed = 3.0", ""))
    with pytest.raises(mazesim.WorldFormatError, match="broken.toml"):
        RobotProfile.load(str(broken))
    with pytest.raises(mazesim.WrongTypeError, match="found an int"):
        RobotProfile.load(3)  # type: ignore[arg-type]


def test_a_distance_sensors_table_is_the_profile_files_rows(tmp_path: Path) -> None:
    text = RobotProfile.builtin("seed").to_toml()
    assert "[0.03, 3.03, 0.005], [0.035, 2.78, 0.005]" in text
    edited = tmp_path / "edited-seed.toml"
    edited.write_text(text.replace("[0.03, 3.03, 0.005]", "[0.03, 3.5, 0.005]"))
    table = RobotProfile.load(edited).distance_sensor_table(0)
    assert table.shape == (18, 3)
    assert table[:2].tolist() == [[0.03, 3.5, 0.005], [0.035, 2.78, 0.005]]
    assert RobotProfile.builtin("seed").distance_sensor_table(5)[0].tolist() == [0.03, 3.03, 0.005]
    with pytest.raises(mazesim.InvalidArgumentError, match="below 6, found 6"):
        RobotProfile.builtin("seed").distance_sensor_table(6)
