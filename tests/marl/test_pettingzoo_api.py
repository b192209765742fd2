"""PettingZoo's own API and seeding tests pass on every multi-robot task, parallel and AEC."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

pytest.importorskip("pettingzoo", reason="needs mazesim[marl] (make marl-deps)")

from pettingzoo.test import (  # noqa: E402
    api_test,
    parallel_api_test,
    parallel_seed_test,
    render_test,
    seed_test,
    state_test,
)

from mazesim.marl import aggregation_v0, maze_goals_v0  # noqa: E402

#: Every task's module, with small settings that keep the tests quick.
TASKS: dict[str, tuple[Any, dict[str, Any]]] = {
    "maze_goals_v0": (maze_goals_v0, {"num_robots": 2, "maze_size": (3, 3), "max_cycles": 30}),
    "aggregation_v0": (aggregation_v0, {"num_robots": 3, "max_cycles": 30}),
}


@pytest.mark.parametrize("name", TASKS)
def test_parallel_api_test_passes(name: str) -> None:
    module, options = TASKS[name]
    env = module.parallel_env(**options)
    assert env.metadata["name"] == name
    parallel_api_test(env, num_cycles=70)


@pytest.mark.parametrize("name", TASKS)
def test_parallel_seed_test_passes(name: str) -> None:
    module, options = TASKS[name]
    parallel_seed_test(lambda: module.parallel_env(**options))


@pytest.mark.parametrize("name", TASKS)
def test_aec_api_and_seed_tests_pass(name: str) -> None:
    module, options = TASKS[name]
    api_test(module.env(**options), num_cycles=40)
    seed_test(lambda: module.env(**options), num_cycles=40)


@pytest.mark.parametrize("name", TASKS)
def test_the_global_state_is_every_observation_then_every_true_pose(name: str) -> None:
    """PettingZoo's ``state()``/``state_space`` (a centralised critic's input): PettingZoo's
    own state tests on the AEC env, ``parallel_api_test`` with the state present, and the
    state's layout read back from the observations and the batch's poses."""
    module, options = TASKS[name]
    state_test(module.env(**options), module.parallel_env(**options), num_cycles=30)
    env = module.parallel_env(**options)
    parallel_api_test(env, num_cycles=30)
    observations, _ = env.reset(seed=5)
    for _ in range(3):
        observations, *_ = env.step({agent: np.array([0.6, 1.0]) for agent in env.agents})
    state = env.state()
    width = env.observation_space(env.possible_agents[0]).shape[0]
    robots = len(env.possible_agents)
    assert env.state_space.contains(state) and state.shape == (robots * (width + 3),)
    seen = np.concatenate([observations[agent] for agent in env.possible_agents])
    np.testing.assert_array_equal(state[: robots * width], seen)
    np.testing.assert_array_equal(state[robots * width :], env.batch.poses[0].ravel())
    assert not np.array_equal(state[robots * width :], np.zeros(robots * 3))


@pytest.mark.parametrize("name", TASKS)
def test_render_draws_every_robot(name: str) -> None:
    module, options = TASKS[name]
    env = module.parallel_env(render_mode="rgb_array", **options)
    env.reset(seed=3)
    frame = env.render()
    assert frame is not None and frame.dtype == np.uint8 and frame.shape == (400, 400, 3)
    env.step({agent: np.array([1.0, 1.0], np.float32) for agent in env.agents})
    moved = env.render()
    assert moved is not None and not np.array_equal(frame, moved)
    assert module.parallel_env(**options).render() is None


@pytest.mark.parametrize("name", TASKS)
def test_render_test_passes_in_every_render_mode(
    name: str, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """PettingZoo's ``render_test`` makes the AEC env with ``render_mode="human"`` first, then
    one of each declared mode: ``"human"`` shows the picture (here headless, said once per env)
    and answers None, ``"rgb_array"`` the picture itself."""
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    module, options = TASKS[name]
    render_test(lambda render_mode=None: module.env(render_mode=render_mode, **options))
    env = module.parallel_env(render_mode="human", **options)
    assert env.metadata["render_modes"] == ["human", "rgb_array"]
    capsys.readouterr()
    env.reset(seed=2)
    env.step({agent: np.array([1.0, 1.0]) for agent in env.agents})
    assert env.render() is None
    said = capsys.readouterr().err
    assert said.count('render_mode="human" shows no window here') == 1, said
    env.close()


#: Settings a MARL user tries beside the defaults: one robot (JaxNav's single-agent case), eight
#: robots, a maze of 2 x 2 cells as full as it gets, a swarm of twenty (#33).
UNUSUAL: dict[str, tuple[Any, dict[str, Any]]] = {
    "maze_goals_v0, one robot": (maze_goals_v0, {"num_robots": 1, "max_cycles": 30}),
    "maze_goals_v0, eight robots": (maze_goals_v0, {"num_robots": 8, "max_cycles": 30}),
    "maze_goals_v0, 2 x 2 cells": (
        maze_goals_v0,
        {"num_robots": 4, "maze_size": (2, 2), "max_cycles": 30},
    ),
    "aggregation_v0, twenty robots": (
        aggregation_v0,
        {"num_robots": 20, "arena_side": 2.0, "max_cycles": 20},
    ),
}


@pytest.mark.parametrize("name", UNUSUAL)
def test_pettingzoo_tests_pass_with_unusual_settings(name: str) -> None:
    module, options = UNUSUAL[name]
    env = module.parallel_env(**options)
    assert len(env.possible_agents) == options["num_robots"]
    parallel_api_test(env, num_cycles=40)
    parallel_seed_test(lambda: module.parallel_env(**options))


def test_aggregation_needs_two_robots_and_says_so() -> None:
    from mazesim.errors import InvalidArgumentError

    with pytest.raises(InvalidArgumentError, match="expected 2 to 64 robots, found 1"):
        aggregation_v0.parallel_env(num_robots=1)
