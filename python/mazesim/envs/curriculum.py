"""A curriculum over maze size for the random-maze tasks: small mazes first, larger ones once the
policy reaches their goals.

:class:`MazeSizeCurriculum` holds the stages (sizes in cells, e.g. 3 x 3, then 5 x 5, then 7 x 7)
and the rule that moves on: the success rate of the last ``window`` episodes of the current stage
reaching ``promote_at``. It counts the episodes it is told of (:meth:`MazeSizeCurriculum.record`)
and sets the size of the mazes that the env's next episodes draw
(:meth:`MazeSizeCurriculum.apply`): an episode under way keeps its maze, and the observation's
shape does not change with the size. It works with any env of a task made with ``world="random"``
(a single :class:`~mazesim.envs.EPuckMazeEnv` or the native vector env, and the goal-conditioned
tasks' :class:`~mazesim.envs.goal.MazeGoalEnv` and its vector env), under any wrapper. An
observation that holds positions in metres (the goal tasks' ``achieved_goal`` and
``desired_goal``, the raw readings' pose with ``include_pose=True``) has a space made for the
mazes of the env's ``maze_size``: :meth:`MazeSizeCurriculum.apply` refuses, before any stage
runs, a curriculum with a stage of larger mazes, and says to make the env with its largest size.

:class:`MazeSizeCurriculumWrapper` does both for gymnasium's vector API: it records the episodes
that end at each step (``info["is_success"]``) and applies the stage::

    import gymnasium
    import mazesim
    from mazesim.envs.curriculum import MazeSizeCurriculum, MazeSizeCurriculumWrapper

    envs = gymnasium.make_vec("mazesim/UnseenMazeExplore-v0", num_envs=64)
    envs = MazeSizeCurriculumWrapper(envs, MazeSizeCurriculum(((3, 3), (5, 5), (7, 7))))

A training loop of its own (Stable-Baselines3's callbacks, for one) calls ``record`` with the
dones and successes of each step and ``apply`` when it returns True.
"""

from __future__ import annotations

import dataclasses
from collections import deque
from collections.abc import Sequence
from typing import Any

import gymnasium
import numpy as np
import numpy.typing as npt

from mazesim.envs.goal import MazeGoalEnv, MazeGoalVectorEnv
from mazesim.envs.maze_env import EPuckMazeEnv
from mazesim.envs.options import MAX_ENV_CELLS, EnvOptions, _reaches_outside
from mazesim.envs.vector import EPuckMazeVectorEnv
from mazesim.errors import InvalidArgumentError, WrongTypeError, _a_type, _shown

__all__ = ["MazeSizeCurriculum", "MazeSizeCurriculumWrapper"]


class MazeSizeCurriculum:
    """Maze sizes in stages, moving to the next when the current one is mastered.

    Args:
        sizes: The stages' maze sizes, (width, height) in cells, in order; the last is the target.
        promote_at: The success rate over the last ``window`` episodes of a stage at which the
            next stage starts (0 to 1).
        window: The number of a stage's episodes that rate is taken over; a stage lasts at least
            that many episodes.

    Raises:
        InvalidArgumentError: No sizes, a size the envs refuse, a rate outside (0, 1] or a
            window below 1.
    """

    def __init__(
        self,
        sizes: Sequence[tuple[int, int]] = ((3, 3), (5, 5), (7, 7)),
        promote_at: float = 0.8,
        window: int = 200,
    ) -> None:
        checked = [_checked_size(size) for size in sizes]
        if not checked:
            raise InvalidArgumentError("expected at least one maze size, found none")
        if not 0.0 < float(promote_at) <= 1.0:
            raise InvalidArgumentError(
                f"expected promote_at to be a success rate in (0, 1], found {_shown(promote_at)}"
            )
        if int(window) < 1:
            raise InvalidArgumentError(f"expected window to be at least 1, found {_shown(window)}")
        self.sizes: tuple[tuple[int, int], ...] = tuple(checked)
        self.promote_at = float(promote_at)
        self.window = int(window)
        self.stage = 0
        #: The episodes recorded in each stage so far.
        self.episodes = [0] * len(self.sizes)
        self._recent: deque[bool] = deque(maxlen=self.window)

    @property
    def size(self) -> tuple[int, int]:
        """The maze size of the current stage."""
        return self.sizes[self.stage]

    @property
    def finished(self) -> bool:
        """Whether the last stage (the target size) is reached."""
        return self.stage == len(self.sizes) - 1

    @property
    def success_rate(self) -> float:
        """The success rate of the current stage's last ``window`` episodes (NaN before one)."""
        return float(np.mean(self._recent)) if self._recent else float("nan")

    def record(self, dones: npt.ArrayLike, successes: npt.ArrayLike) -> bool:
        """Counts the episodes that ended (``dones``, one bool per env) and whether each reached
        the goal (``successes``, read where ``dones`` is True); moves to the next stage when the
        rate reaches ``promote_at`` over a full window. Returns whether the stage changed (then
        :meth:`apply` the new size)."""
        ended = np.asarray(dones, dtype=bool).reshape(-1)
        reached = np.asarray(successes, dtype=bool).reshape(-1)
        if reached.shape != ended.shape:
            raise InvalidArgumentError(
                f"expected dones and successes of one shape, found {ended.shape} and "
                f"{reached.shape}"
            )
        count = int(ended.sum())
        self.episodes[self.stage] += count
        self._recent.extend(reached[ended].tolist())
        if (
            not self.finished
            and len(self._recent) == self.window
            and self.success_rate >= self.promote_at
        ):
            self.stage += 1
            self._recent.clear()
            return True
        return False

    def apply(self, env: Any) -> None:
        """Makes the next episodes of ``env`` (a maze env, a goal env or their native vector
        envs, wrapped or not, of a task with ``world="random"``) draw mazes of the current size.

        Raises:
            WrongTypeError: ``env`` is not one of those envs.
            InvalidArgumentError: ``env`` does not draw random mazes, or its observation space
                does not hold the positions of every stage's mazes (see the module).
        """
        target = _maze_env(env)
        world = target.options.world
        if world is not None:
            raise InvalidArgumentError(
                "expected an env of random mazes (world='random'); found the fixed world "
                f"{_shown(world.name)}"
            )
        if target.options.world_sampler is not None:
            raise InvalidArgumentError(
                "expected an env of random mazes (world='random'); found an env whose worlds "
                "come from a world sampler (world=a callable), which maze_size does not change: "
                "let the sampler draw the curriculum's size, generate_maze(*curriculum.size, ...)"
            )
        _check_stages_fit(env, target.options, self.sizes)
        target.options = dataclasses.replace(target.options, maze_size=self.size)

    def state(self) -> dict[str, Any]:
        """The stage, its size, its recent success rate and each stage's episodes, for a log."""
        return {
            "stage": self.stage,
            "maze_size": list(self.size),
            "success_rate": self.success_rate,
            "episodes": list(self.episodes),
        }


class MazeSizeCurriculumWrapper(gymnasium.vector.VectorWrapper):
    """A vector env whose maze size follows ``curriculum``: each step records the episodes that
    ended and, when the stage changes, the next episodes draw mazes of the new size.

    Args:
        env: A vector env of a random-maze task (the native one or ``SyncVectorEnv``).
        curriculum: The stages; its current size is applied at once.
    """

    def __init__(self, env: gymnasium.vector.VectorEnv, curriculum: MazeSizeCurriculum) -> None:
        super().__init__(env)
        self.curriculum = curriculum
        self._apply()

    def step(self, actions: Any) -> Any:
        """Steps the envs and records the episodes that ended."""
        observations, rewards, terminated, truncated, infos = self.env.step(actions)
        dones = np.logical_or(terminated, truncated)
        if dones.any() and self.curriculum.record(dones, infos["is_success"]):
            self._apply()
        return observations, rewards, terminated, truncated, infos

    def _apply(self) -> None:
        inner = self.env.unwrapped
        envs = getattr(inner, "envs", None)
        if envs is not None:  # SyncVectorEnv: each of its single envs
            for each in envs:
                self.curriculum.apply(each)
        else:
            self.curriculum.apply(inner)


def _checked_size(size: Any) -> tuple[int, int]:
    values = tuple(size) if isinstance(size, (tuple, list, np.ndarray)) else (size,)
    if (
        len(values) != 2
        or not all(isinstance(v, (int, np.integer)) and not isinstance(v, bool) for v in values)
        or min(values) < 2
        or int(values[0]) * int(values[1]) > MAX_ENV_CELLS
    ):
        raise InvalidArgumentError(
            f"expected each maze size to be (width, height) of at least 2 cells each and at most "
            f"{MAX_ENV_CELLS} cells in all, found {_shown(size)}"
        )
    return int(values[0]), int(values[1])


def _maze_env(env: Any) -> EPuckMazeEnv | EPuckMazeVectorEnv:
    """The maze env (or native vector env) whose options draw ``env``'s mazes."""
    target = getattr(env, "unwrapped", env)
    if isinstance(target, MazeGoalEnv):
        return target.maze
    if isinstance(target, MazeGoalVectorEnv):
        return target.mazes
    if not isinstance(target, (EPuckMazeEnv, EPuckMazeVectorEnv)):
        raise WrongTypeError(
            "expected a mazesim maze env, a goal env or their native vector env, found "
            f"{_a_type(target)}"
        )
    return target


def _check_stages_fit(env: Any, options: EnvOptions, sizes: Sequence[tuple[int, int]]) -> None:
    """Refuses stages whose mazes reach outside the positions ``env``'s space holds (the bounds
    each drawn world is checked against at its reset)."""
    held = _maze_env(env)._held_bounds
    if held is None:
        return
    for size in sizes:
        bounds = dataclasses.replace(options, maze_size=size).random_maze(0).bounds
        if _reaches_outside(bounds, held):
            largest = max(sizes, key=lambda s: s[0] * s[1])
            raise InvalidArgumentError(
                "expected every stage's mazes to lie within the positions the env's observation "
                f"space holds (x {held[0]:.3f} to {held[2]:.3f} m, y {held[1]:.3f} to "
                f"{held[3]:.3f} m, its maze_size {options.maze_size}); found the stage {size}, "
                f"whose mazes reach x {bounds[2]:.3f} m, y {bounds[3]:.3f} m: make the env with "
                f"maze_size={largest}, the curriculum's largest mazes"
            )
