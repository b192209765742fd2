"""Misuse of the multi-robot envs raises the package's errors, the same as the single-robot
gymnasium envs: bad seeds and options, ``step`` before ``reset``, any call after ``close()``,
for the parallel env, the AEC env and the native batch."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

pytest.importorskip("pettingzoo", reason="needs mazesim[marl] (make marl-deps)")

from gymnasium.error import ClosedEnvironmentError, ResetNeeded  # noqa: E402

import mazesim  # noqa: E402
from mazesim.envs import EnvClosedError, ResetNeededError  # noqa: E402
from mazesim.marl import aggregation_v0, maze_goals_v0  # noqa: E402

OPTIONS = {"num_robots": 2, "maze_size": (3, 3), "max_cycles": 10}
BAD_SEEDS = [-1, 2**64, 1.5, True, "7", [1]]


@pytest.mark.parametrize("seed", BAD_SEEDS)
def test_a_bad_seed_is_refused_by_the_parallel_env_and_the_batch(seed: Any) -> None:
    # the latter two: a text, or an int beyond 64 bits, checked first by the argument check
    expected = "expected seed|seed refused: expected (int|an integer that fits in 64 bits)"
    env = maze_goals_v0.parallel_env(**OPTIONS)
    with pytest.raises(mazesim.InvalidArgumentError, match=expected):
        env.reset(seed=seed)
    batch = maze_goals_v0.batch_env(2, **OPTIONS)
    with pytest.raises(mazesim.InvalidArgumentError, match=expected):
        batch.reset(seed=seed)


def test_options_that_are_not_a_dict_are_refused() -> None:
    env = maze_goals_v0.parallel_env(**OPTIONS)
    with pytest.raises(mazesim.InvalidArgumentError, match="expected options"):
        env.reset(options=123)  # type: ignore[arg-type]


def test_a_mistyped_option_names_the_options_and_the_one_meant() -> None:
    with pytest.raises(mazesim.InvalidArgumentError) as caught:
        maze_goals_v0.parallel_env(num_robot=3)
    message = str(caught.value)
    assert "expected no argument named 'num_robot', found one" in message
    assert "its arguments: num_robots, maze_size, loops, max_cycles" in message
    assert message.endswith("; did you mean 'num_robots'?")


@pytest.mark.parametrize("make", [aggregation_v0.parallel_env, aggregation_v0.batch_env])
def test_an_option_the_task_does_not_take_is_refused_by_name(make: Any) -> None:
    with pytest.raises(mazesim.InvalidArgumentError) as caught:
        make(*([2] if make is aggregation_v0.batch_env else []), num_robot=3, world="arena")
    message = str(caught.value)
    assert message.startswith("aggregation_v0: expected no argument named 'num_robot'")
    assert "its arguments: render_mode, control_step_ms, noise, num_robots, arena_side" in message
    assert message.endswith("; did you mean 'num_robots'?")


def test_the_largest_seed_is_taken_and_the_batch_wraps_past_it() -> None:
    batch = maze_goals_v0.batch_env(2, **OPTIONS)
    wrapped, _ = batch.reset(seed=2**64 - 1)
    listed, _ = batch.reset(seed=[2**64 - 1, 0])
    assert np.array_equal(wrapped, listed)
    observations, _ = maze_goals_v0.parallel_env(**OPTIONS).reset(seed=np.uint64(2**64 - 1))
    assert len(observations) == 2


def test_step_before_reset_and_after_close() -> None:
    env = maze_goals_v0.parallel_env(**OPTIONS)
    with pytest.raises(ResetNeededError):
        env.step({})
    env.reset(seed=0)
    env.close()
    for call in (lambda: env.reset(seed=0), lambda: env.step({}), env.render):
        with pytest.raises(EnvClosedError) as raised:
            call()
        assert isinstance(raised.value, ClosedEnvironmentError)


def test_the_aec_env_asks_for_reset_with_the_package_error() -> None:
    env = maze_goals_v0.env(**OPTIONS)
    for call in (lambda: env.step(np.zeros(2, np.float32)), lambda: env.observe("epuck_0")):
        with pytest.raises(ResetNeededError) as raised:
            call()
        assert isinstance(raised.value, ResetNeeded)
    env.reset(seed=0)
    env.step(np.zeros(2, np.float32))
    assert env.agent_selection == "epuck_1"


@pytest.mark.parametrize("agent", ["zz", ["epuck_0"], 0])
def test_the_aec_env_observes_only_its_agents(agent: Any) -> None:
    # PettingZoo's conversion looks the agent up in a dict: a bare KeyError (TypeError for a
    # list); the parallel env's spaces already named the agents.
    for task in (maze_goals_v0, aggregation_v0):
        env = task.env(**OPTIONS) if task is maze_goals_v0 else task.env()
        env.reset(seed=0)
        with pytest.raises(mazesim.UnknownNameError, match="expected one of the agents"):
            env.observe(agent)
        assert env.observe("epuck_0") is not None


@pytest.mark.parametrize("action", ["fast", [1.0, "x"], {"left": 1.0}, object()])
def test_an_action_that_is_not_two_numbers_names_the_agent(action: Any) -> None:
    """numpy's "could not convert string to float: 'fast'" came out as an InvalidArgumentError
    naming neither the agent nor what an action is."""
    env = maze_goals_v0.parallel_env(**OPTIONS)
    env.reset(seed=0)
    actions = {agent: np.zeros(2, np.float32) for agent in env.agents}
    actions[env.agents[1]] = action
    with pytest.raises(mazesim.InvalidActionError) as caught:
        env.step(actions)
    assert f"expected the action of {env.agents[1]} to be two wheel speeds" in str(caught.value)


@pytest.mark.parametrize("action", [[np.nan, 0.0], [0.0, np.inf], "fast", [1.0, 2.0, 3.0]])
def test_the_aec_env_refuses_a_bad_action_at_its_agents_step_and_goes_on(action: Any) -> None:
    """PettingZoo's parallel_to_aec held the actions until the last agent's step: a NaN of the
    first agent was refused there, not naming it, and every later step raised until reset."""
    env = maze_goals_v0.env(**OPTIONS)
    env.reset(seed=0)
    first = env.agent_selection
    with pytest.raises(mazesim.InvalidActionError, match=f"the action of {first}"):
        env.step(np.asarray(action) if not isinstance(action, str) else action)
    assert env.agent_selection == first, "nothing was taken"
    for _ in env.possible_agents:
        env.step(np.zeros(2, np.float32))  # the env goes on with valid actions
    assert env.agent_selection == first


@pytest.mark.parametrize(
    ("module", "option", "value"),
    [
        (maze_goals_v0, "step_penalty", float("nan")),
        (maze_goals_v0, "collision_penalty", float("inf")),
        (maze_goals_v0, "body_radius", -0.037),
        (aggregation_v0, "arena_side", float("nan")),
        (aggregation_v0, "arena_side", float("inf")),
        (aggregation_v0, "arena_side", -5.0),
    ],
)
def test_a_task_parameter_that_is_no_finite_number_is_refused_by_name(
    module: Any, option: str, value: Any
) -> None:
    """NaN weights made every reward NaN; a NaN, infinite or negative arena was taken and reset
    failed blaming the seed."""
    # NaN and infinities are refused by the surface check, before the task's own check.
    words = f"expected {option} to be a finite|{option} refused: expected a (finite )?number"
    with pytest.raises(mazesim.InvalidArgumentError, match=words):
        module.parallel_env(**{option: value})


def test_the_batch_steps_actions_in_fortran_order_as_in_c_order() -> None:
    """Fortran-ordered actions kept their order through the batch's clipping and were refused
    by the core as "not C-contiguous"."""
    results = []
    for layout in (np.ascontiguousarray, np.asfortranarray):
        batch = maze_goals_v0.batch_env(2, **OPTIONS)
        batch.reset(seed=3)
        actions = np.linspace(-1.0, 1.0, 2 * batch.num_robots * 2, dtype=np.float32)
        results.append(batch.step(layout(actions.reshape(2, batch.num_robots, 2)))[0])
    assert np.array_equal(results[0], results[1])
