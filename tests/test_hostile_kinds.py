"""Hostile values of unusual kinds where numbers, arrays and paths are taken (#35, #15): a
complex number (numpy's converts to a float with a warning only), a masked array (whose mask a
borrowed slice or ``np.asarray`` drops), a path object whose own ``__fspath__`` fails, and a
vector env used after ``close()``. Each is refused by the package's own errors, saying what was
expected and found."""

from __future__ import annotations

import warnings

import gymnasium
import numpy as np
import pytest

import mazesim
from mazesim.envs.errors import EnvClosedError
from mazesim.errors import InvalidActionError, WrongTypeError

WORLD = mazesim.World.builtin("seed-maze")

COMPLEX = {
    "numpy complex128": lambda: np.complex128(0.25 + 1j),
    "numpy complex64": lambda: np.complex64(0.25),
    "0-d complex array": lambda: np.array(0.25 + 0j),
}


@pytest.mark.parametrize("kind", sorted(COMPLEX))
@pytest.mark.parametrize(
    "call",
    [
        lambda v: mazesim.Simulator(WORLD).step(v, 0.0),
        lambda v: mazesim.Simulator(WORLD).set_goal(0.1, 0.1, v),
        lambda v: WORLD.floor_reflectance(v, 0.1),
        lambda v: mazesim.sharp_volts_to_cm(v),
        lambda v: mazesim.SensingPerturbation(noise_scale=v),
    ],
    ids=["step", "set_goal", "floor_reflectance", "sharp_volts_to_cm", "SensingPerturbation"],
)
def test_a_complex_number_is_no_real_one(kind: str, call: object) -> None:
    with warnings.catch_warnings():
        # Not turned into an error: numpy's ComplexWarning alone is no refusal.
        warnings.simplefilter("ignore")
        with pytest.raises(
            WrongTypeError, match=r"to be a real number, found an? (complex|ndarray)"
        ):
            call(COMPLEX[kind]())  # type: ignore[operator]


def test_numbers_of_other_real_kinds_are_still_taken() -> None:
    simulator = mazesim.Simulator(WORLD)
    simulator.set_goal(0.1, 0.1, np.float16(0.25))
    simulator.step(np.array(1.0), np.int64(1))
    assert simulator.goal == pytest.approx((0.1, 0.1, 0.25))


def test_a_masked_array_is_refused_saying_how_to_fill_it() -> None:
    commands = np.ma.masked_array(np.full((1, 2), 5.0), mask=[[True, False]])
    simulator = mazesim.Simulator(WORLD)
    with pytest.raises(
        WrongTypeError, match=r"commands .* found a MaskedArray.*mask would be dropped.*filled"
    ):
        simulator.step_robots(commands)
    assert simulator.steps == 0
    batch = mazesim.BatchSimulator(WORLD, num_envs=2)
    with pytest.raises(WrongTypeError, match=r"starts .*MaskedArray.*array\.filled\(value\)"):
        batch.set_starts(np.ma.masked_array(np.zeros((2, 3)), mask=True))
    simulator.step_robots(commands.filled(0.0))  # a plain array, as the message says
    assert simulator.steps == 1


@pytest.mark.parametrize("vector", [False, True], ids=["env", "vector env"])
def test_a_masked_action_is_refused_not_read_without_its_mask(vector: bool) -> None:
    """The envs' actions are read in Python before the core's buffers see them: a masked
    array's mask would be dropped there, so the one action reader refuses it too."""
    if vector:
        env: object = gymnasium.make_vec("mazesim/EPuckMaze-v0", num_envs=2)
        action = np.ma.masked_array(np.full((2, 2), 0.5, np.float32), mask=[[True, False]] * 2)
    else:
        env = gymnasium.make("mazesim/EPuckMaze-v0")
        action = np.ma.masked_array(np.full(2, 0.5, np.float32), mask=[True, False])
    env.reset(seed=1)  # type: ignore[attr-defined]
    with pytest.raises(InvalidActionError, match=r"masked array .*array\.filled\(value\)"):
        env.step(action)  # type: ignore[attr-defined]
    env.step(action.filled(0.0))  # type: ignore[attr-defined]
    env.close()  # type: ignore[attr-defined]


class RaisingPath:
    def __fspath__(self) -> str:
        raise RuntimeError("no path today")


@pytest.mark.parametrize(
    "call",
    [mazesim.load_world, mazesim.World.load, mazesim.RobotProfile.load, WORLD.save],
    ids=["load_world", "World.load", "RobotProfile.load", "World.save"],
)
def test_a_path_object_whose_fspath_raises_is_refused(call: object) -> None:
    with pytest.raises(WrongTypeError, match=r"os\.PathLike\)?, found a RaisingPath"):
        call(RaisingPath())  # type: ignore[operator]


def test_the_vector_env_refuses_render_after_close_as_the_single_env_does() -> None:
    single = gymnasium.make("mazesim/EPuckMaze-v0", render_mode="rgb_array")
    vector = gymnasium.make_vec("mazesim/EPuckMaze-v0", num_envs=2, render_mode="rgb_array")
    for env in (single, vector):
        env.reset(seed=0)
        env.close()
        with pytest.raises(EnvClosedError, match="closed"):
            env.render()


UNKNOWN = "no-such-name"


def _unknown_name_calls() -> dict[str, object]:
    from mazesim.learn.evaluate import EvalSettings
    from mazesim.learn.trained_policy import shipped_policy_dir
    from mazesim.transfer.study import StudyOptions

    return {
        "EvalSettings events": lambda: EvalSettings(events=UNKNOWN),
        "StudyOptions events": lambda: StudyOptions(events=UNKNOWN),
        "StudyOptions odometry": lambda: StudyOptions(odometry=UNKNOWN),
        "shipped_policy_dir": lambda: shipped_policy_dir(UNKNOWN),
    }


@pytest.mark.parametrize("where", sorted(_unknown_name_calls()))
def test_an_unknown_name_is_refused_listing_the_known_ones(where: str) -> None:
    with pytest.raises(mazesim.UnknownNameError, match=r"to be one of \w.*; found 'no-such-name'"):
        _unknown_name_calls()[where]()  # type: ignore[operator]


def test_sb3_refuses_an_unknown_env_id_listing_mazesims() -> None:
    pytest.importorskip("stable_baselines3")
    from mazesim.integrations.sb3 import make_vec_env

    with pytest.raises(mazesim.UnknownNameError, match="mazesim/EPuckMaze-v0") as refused:
        make_vec_env("mazesim/EPuckMaz-v0")
    assert refused.value.suggestion == "mazesim/EPuckMaze-v0"


def _hostile_actions(shape: tuple[int, ...]) -> dict[str, tuple[object, bool]]:
    """Actions of ``shape`` in each hostile dress, and whether each must be refused: masked,
    of objects, of text, of complex numbers or booleans (refused); non-contiguous, read-only or
    big-endian (read by their values)."""
    plain = np.full(shape, 0.25, np.float32)
    wide = np.full((*shape[:-1], shape[-1] * 2), 0.25, np.float32)
    read_only = plain.copy()
    read_only.setflags(write=False)
    return {
        "masked": (np.ma.masked_array(plain, mask=np.ones(shape, bool)), True),
        "objects": (plain.astype(object), True),
        "text": (plain.astype(str), True),
        "complex": (plain.astype(np.complex64), True),
        "booleans": (np.ones(shape, bool), True),
        "non-contiguous": (wide[..., ::2], False),
        "read-only": (read_only, False),
        "big-endian": (plain.astype(">f4"), False),
    }


@pytest.mark.parametrize("dress", sorted(_hostile_actions((2,))))
def test_the_multi_robot_envs_read_actions_through_the_one_reader(dress: str) -> None:
    """The multi-robot batch takes its actions as the single-robot envs do
    (``mazesim.envs.spaces.real_actions``): what is no array of real numbers is refused with an
    InvalidActionError, any layout of real numbers is read by its values."""
    from mazesim.marl import maze_goals_v0

    batch = maze_goals_v0.batch_env(2)
    batch.reset(seed=3)
    shape = (batch.num_envs, batch.num_robots, 2)
    action, refused = _hostile_actions(shape)[dress]
    if refused:
        with pytest.raises(InvalidActionError):
            batch.step(action)
        return
    moved = batch.step(action)[0]
    again = maze_goals_v0.batch_env(2)
    again.reset(seed=3)
    assert np.array_equal(moved, again.step(np.full(shape, 0.25, np.float32))[0])
