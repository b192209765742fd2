"""``robot=`` of training and evaluation reaches every batch they build, as given."""

from __future__ import annotations

import contextlib
import pickle
import re
from pathlib import Path
from typing import Any

import pytest

import mazesim
from mazesim.batch import RobotBatch
from mazesim.learn.evaluate import evaluate_navigator, unseen_mazes
from mazesim.learn.higher_training import HigherTraining
from mazesim.learn.lower import LowerSettings
from mazesim.learn.tables import load_policy
from mazesim.learn.train import run_training


@pytest.fixture
def robots_seen(monkeypatch: pytest.MonkeyPatch) -> list[Any]:
    seen: list[Any] = []
    original = RobotBatch.__init__

    def spy(self: RobotBatch, *args: Any, **options: Any) -> None:
        seen.append(options.get("robot", "seed"))
        original(self, *args, **options)

    monkeypatch.setattr(RobotBatch, "__init__", spy)
    return seen


def test_training_hands_the_robot_to_both_stages(robots_seen: list[Any]) -> None:
    lower = LowerSettings(num_envs=4, total_steps=40, round_steps=10, maze_pool=2)
    higher = HigherTraining(episodes_per_world=1, envs_per_world=1, max_steps=20)
    world = mazesim.load_world("seed-maze")
    run = run_training(lower, higher, world, threads=1, robot="e-puck")
    assert run is not None
    assert robots_seen == ["e-puck", "e-puck"]
    robots_seen.clear()
    run_training(lower, higher, world, threads=1)
    assert robots_seen == ["seed", "seed"]


def test_evaluation_hands_the_robot_to_adaptation_and_episodes(robots_seen: list[Any]) -> None:
    policy = load_policy(None)
    summaries = evaluate_navigator(policy, unseen_mazes(1, 0), 1, max_steps=30, robot="e-puck")
    assert summaries["truth"].adapted
    assert robots_seen and set(robots_seen) == {"e-puck"}
    # A profile object is handed on as it is (the batch decides what it takes).
    profile = mazesim.RobotProfile.builtin("e-puck")
    robots_seen.clear()
    with contextlib.suppress(mazesim.InvalidArgumentError):
        evaluate_navigator(
            policy, [mazesim.load_world("seed-maze")], 1, max_steps=30, robot=profile
        )
    assert robots_seen and robots_seen[0] is profile


def test_a_spread_evaluation_sends_a_profile_file_as_itself(tmp_path: Path) -> None:
    # An edited seed robot, still named seed: the chunks must drive it, not the built-in one.
    text = mazesim.RobotProfile.builtin("seed").to_toml()
    edited = re.sub(r"(?m)^max_wheel_speed = .*$", "max_wheel_speed = 4.0", text)
    assert edited != text
    path = tmp_path / "slow-seed.toml"
    path.write_text(edited)
    policy = load_policy(None)
    worlds = [mazesim.load_world("seed-maze")]
    options: dict[str, Any] = {"max_steps": 1500, "seed": 3}
    here = evaluate_navigator(policy, worlds, 4, robot=str(path), **options)["truth"]
    builtin = evaluate_navigator(policy, worlds, 4, robot="seed", **options)["truth"]
    assert here.as_json() != builtin.as_json()

    def spread(chunk: Any, episodes: int) -> Any:
        path.unlink(missing_ok=True)  # the machines running the chunks have no copy of the file
        travelled = pickle.loads(pickle.dumps(chunk))  # as Ray sends a chunk to a worker
        return [*travelled(0, 2), *travelled(2, episodes - 2)]

    spread_out = evaluate_navigator(policy, worlds, 4, robot=str(path), spread=spread, **options)
    assert spread_out["truth"].as_json() == here.as_json()


def test_a_spread_evaluation_refuses_a_profile_per_robot() -> None:
    def spread(chunk: Any, episodes: int) -> Any:
        raise AssertionError("not reached")

    with pytest.raises(mazesim.InvalidArgumentError, match="one robot profile .* sequence of 2"):
        evaluate_navigator(
            load_policy(None),
            [mazesim.load_world("seed-maze")],
            1,
            spread=spread,
            robot=["e-puck", "e-puck"],
        )
