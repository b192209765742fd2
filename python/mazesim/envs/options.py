"""The options of the maze environments, checked once and shared by the single and vector envs.

:meth:`EnvOptions.create` is the one list of the keyword arguments of
``gymnasium.make("mazesim/...")`` and ``gymnasium.make_vec(...)``, with their defaults and their
documentation; both environments pass their keywords straight to it.
"""

from __future__ import annotations

import dataclasses
import inspect
import numbers
import os
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Union

import numpy as np
from gymnasium.envs.registration import EnvSpec

import mazesim
from mazesim._core import RobotProfile, World, generate_maze
from mazesim.envs.navigation import (
    OBSERVATIONS,
    START_GOALS,
    StartAndGoal,
    draw_start_and_goal,
    start_and_goal_cells,
)
from mazesim.envs.reward import RewardWeights
from mazesim.errors import InvalidArgumentError, RegisteredName, _closest_name, _known_name, _shown

__all__ = [
    "ACTION_MODES",
    "DEFAULT_MAX_EPISODE_STEPS",
    "MAX_ENV_CELLS",
    "EnvOptions",
    "SampledWorld",
    "WorldOption",
    "WorldSampler",
    "draw_seed",
    "option_names",
]

#: The accepted values of ``action_mode``.
ACTION_MODES = ("continuous", "discrete")

#: The registered time limit: 3000 control steps, 96 s of simulated time at 32 ms a step, which
#: lets a robot at the report's cruise speed (0.064 m/s on the e-puck) drive 6 m, more than the
#: longest shortest path of a 5 x 5 maze of 0.25 m cells.
DEFAULT_MAX_EPISODE_STEPS = 3000

#: The most maze cells of an env's world (a 500 x 500 grid). The env keeps Python tables per cell
#: (the distance to the goal, the navigation features): an open 300 x 300 grid takes 5 s to make,
#: 6 s to reset and 150 MB; a 2,500 x 2,500 one, legal for the simulators, ran out of memory.
MAX_ENV_CELLS = 250_000

#: What a world sampler (the ``world`` option given as a callable) returns for each episode: a
#: World, a built-in world name or a path to a world file.
SampledWorld = Union[str, "os.PathLike[str]", World]
#: A world sampler: called at every reset with the env's RNG (a ``numpy.random.Generator``),
#: it returns the world of the next episode, drawing whatever it draws from that RNG.
WorldSampler = Callable[[np.random.Generator], SampledWorld]
#: What the ``world`` option accepts: a built-in name, a path, ``"random"``, a World, a World's
#: JSON form (:func:`world_as_json`) or a world sampler.
WorldOption = Union[str, "os.PathLike[str]", World, dict[str, str], WorldSampler]

#: The seed of the RNG a world sampler is called with once when the env is made, for a world of
#: the kind its episodes run in (the spaces' bounds, the frame rate); the episodes' RNGs are the
#: env's own.
SAMPLER_PROBE_SEED = 0

#: The x, y bounds in metres (min x, min y, max x, max y) of the positions an observation space
#: holds, or of a world.
_PositionBounds = tuple[float, float, float, float]

#: How far, in metres, a world may reach past the bounds a space holds (float32 rounding).
_BOUNDS_TOLERANCE = 1e-6


#: Keywords of a vector env that reach a single env when given to ``make_vec`` in sync or async
#: mode, where gymnasium takes them in ``vector_kwargs``.
_VECTOR_ENV_KEYWORDS = ("autoreset_mode", "copy", "observation_mode", "shared_memory", "context")
#: Keywords gymnasium.make takes itself (or passes to every env), suggested for a typo of one.
_MAKE_KEYWORDS = (
    "max_episode_steps",
    "render_mode",
    "disable_env_checker",
    "autoreset",
    "apply_api_compatibility",
)


def draw_seed(rng: np.random.Generator) -> int:
    """Draws the seed of the next episode (or of the next random maze) from an env's RNG."""
    return int(rng.integers(0, 2**63))


@dataclass(frozen=True)
class EnvOptions:
    """The checked options of an environment (see :class:`~mazesim.envs.EPuckMazeEnv`).

    Attributes:
        world: The fixed world, or None when every episode draws its world (a random maze, or
            the world of ``world_sampler``).
        maze_size: (width, height) in cells of the random mazes.
        robot: The robot profile.
        action_mode: ``"continuous"`` or ``"discrete"``.
        clip_actions: Whether continuous actions outside [-1, 1] are clipped (True) or raise.
        observation: ``"sensors"``, ``"goal"``, ``"explore"``, ``"guided"`` or ``"plan"``
            (:mod:`mazesim.envs.navigation`).
        start_goal: ``"world"`` (the world's) or ``"random"`` (random cells at every reset).
        noise: Whether the sensors are noisy.
        include_pose: Whether the observation ends with the pose (x, y, yaw).
        control_step_ms: The control step in ms, or None for the world's basic time step.
        reward: The reward weights.
        render_size: (width, height) of the rendered images in pixels.
        world_sampler: The callable that draws each episode's world from the env's RNG, or None.
    """

    world: World | None
    maze_size: tuple[int, int]
    robot: RobotProfile
    action_mode: str
    noise: bool
    include_pose: bool
    control_step_ms: float | None
    clip_actions: bool = True
    observation: str = "sensors"
    start_goal: str = "world"
    reward: RewardWeights = field(default_factory=RewardWeights)
    render_size: tuple[int, int] = (400, 400)
    world_sampler: WorldSampler | None = None

    @classmethod
    def create(
        cls,
        world: WorldOption = "seed-maze",
        robot: str | os.PathLike[str] = "e-puck",
        action_mode: RegisteredName = "continuous",
        clip_actions: bool = True,
        observation: RegisteredName = "sensors",
        start_goal: RegisteredName = "world",
        noise: bool = True,
        include_pose: bool = False,
        control_step_ms: float | None = None,
        maze_size: tuple[int, int] = (5, 5),
        goal_reward: float = 10.0,
        collision_penalty: float = 0.1,
        progress_reward: float = 10.0,
        render_size: int | tuple[int, int] = 400,
    ) -> EnvOptions:
        """Checks the keyword arguments of the environments and resolves the world and robot.

        Args:
            world: A built-in world name, a path to a world file, a ``World`` (or its JSON form,
                :func:`world_as_json`), ``"random"``
                for a fresh random maze at each reset (``maze_size`` cells, drawn from the env's
                RNG), or a callable, a distribution of worlds of your own: called at each reset
                with the env's RNG (``numpy.random.Generator``), it returns that episode's world
                (a ``World``, a built-in name or a path) and draws only from that RNG, so the
                same seed gives the same worlds. It is also called once when the env is made,
                with an RNG of seed 0, for a world of the kind the episodes run in (the spaces'
                bounds come from it).
            robot: The robot profile (``mazesim.robot_profile_names()``): ``"e-puck"``,
                ``"e-puck2"``, ``"e-puck-hardware"``, ``"seed"`` or ``"alphabot2"``, or the path
                of a profile ``.toml`` file (:meth:`mazesim.RobotProfile.load`).
            action_mode: ``"continuous"`` (left and right wheel speeds as fractions of the motor
                limit) or ``"discrete"`` (the report's 12 primitive actions).
            clip_actions: With True (the default), a continuous action outside [-1, 1] is
                clipped to it, as ``np.clip`` would, so a policy's 1.0001 drives at full speed;
                with False it raises :class:`~mazesim.errors.InvalidActionError`. A NaN or
                infinite action, a wrong shape or dtype and a discrete index out of range
                always raise.
            observation: ``"sensors"`` (the raw readings), ``"goal"`` (normalised readings, the
                goal's position in the robot's frame, the previous action), ``"explore"``
                (``"goal"`` and the map explored round the robot), ``"guided"`` (``"goal"`` and
                the next waypoint of the shortest path) or ``"plan"`` (``"explore"`` and the next
                waypoint of the shortest path through the maze as the robot knows it); see
                :mod:`mazesim.envs.navigation`.
            start_goal: ``"world"`` (the world's start and goal) or ``"random"`` (at every reset
                two distinct random cells of the maze, the start facing a random direction).
            noise: Whether the sensors are noisy (Webots' relative Gaussian noise).
            include_pose: Whether the observation ends with x, y (metres) and yaw (radians).
            control_step_ms: The control step in ms (a whole number of physics steps); None for
                the world's basic time step.
            maze_size: (width, height) in cells of the random mazes.
            goal_reward: Bonus on reaching the goal.
            collision_penalty: Penalty for every step spent touching a wall.
            progress_reward: Reward per metre of progress along the shortest path.
            render_size: Side of the rendered images in pixels, or (width, height).

        Raises:
            InvalidArgumentError: An option has a wrong type or value.
            UnknownNameError: The world or the robot profile does not exist, or an unknown
                action mode, observation or start.
            WorldFormatError: The world file is malformed.
        """
        _known_name(action_mode, "action_mode", ACTION_MODES)
        _known_name(observation, "observation", OBSERVATIONS)
        _known_name(start_goal, "start_goal", START_GOALS)
        flags = (("noise", noise), ("include_pose", include_pose), ("clip_actions", clip_actions))
        for name, flag in flags:
            if not isinstance(flag, (bool, np.bool_)):
                raise InvalidArgumentError(
                    f"expected {name} to be True or False, found {_shown(flag)}"
                )
        if control_step_ms is not None and not (
            isinstance(control_step_ms, numbers.Real) and control_step_ms > 0
        ):
            raise InvalidArgumentError(
                f"expected control_step_ms to be a positive number of ms or None, "
                f"found {_shown(control_step_ms)}"
            )
        sizes = _items(maze_size)
        if (
            len(sizes) != 2
            or not all(_is_count(n) and n >= 2 for n in sizes)
            or int(sizes[0]) * int(sizes[1]) > MAX_ENV_CELLS
        ):
            raise InvalidArgumentError(
                f"expected maze_size to be (width, height) of at least 2 cells each and at most "
                f"{MAX_ENV_CELLS} cells in all, found {_shown(maze_size)}"
            )
        sides = (render_size, render_size) if _is_count(render_size) else _items(render_size)
        if len(sides) != 2 or not all(_is_count(n) and 16 <= n <= 4096 for n in sides):
            raise InvalidArgumentError(
                f"expected render_size to be pixels (16 to 4096) or (width, height), "
                f"found {_shown(render_size)}"
            )
        sampler = world if callable(world) and not isinstance(world, World) else None
        resolved = None if _is_random(world) or sampler is not None else _resolve_world(world)
        if resolved is not None:
            _check_cells(resolved)
        if resolved is not None and start_goal == "random":
            start_and_goal_cells(resolved)  # refused now, not at the first reset
        return cls(
            world=resolved,
            maze_size=(int(sizes[0]), int(sizes[1])),
            robot=RobotProfile.load(robot),
            action_mode=action_mode,
            noise=bool(noise),
            include_pose=bool(include_pose),
            control_step_ms=None if control_step_ms is None else float(control_step_ms),
            clip_actions=bool(clip_actions),
            observation=observation,
            start_goal=start_goal,
            reward=RewardWeights(goal_reward, collision_penalty, progress_reward),
            render_size=(int(sides[0]), int(sides[1])),
            world_sampler=sampler,
        )

    @classmethod
    def from_keywords(cls, keywords: dict[str, Any]) -> EnvOptions:
        """:meth:`create` from an environment's keyword arguments; an unknown keyword raises
        InvalidArgumentError naming the options there are."""
        unknown = sorted(set(keywords) - set(option_names()))
        if unknown:
            vector = [key for key in unknown if key in _VECTOR_ENV_KEYWORDS]
            hint = (
                f" ({', '.join(vector)} belong to the vector env: with "
                'vectorization_mode="sync" or "async" pass them as vector_kwargs={...})'
                if vector
                else ""
            )
            # gymnasium's make takes these itself: a typo of one reaches the env.
            known = [*option_names(), *_MAKE_KEYWORDS]
            meant = [
                f"{_shown(closest)} for {_shown(key)}"
                for key in unknown
                if (closest := _closest_name(key, known)) is not None
            ]
            raise InvalidArgumentError(
                f"expected options among {', '.join(option_names())}; "
                f"found unknown {', '.join(map(repr, unknown))}{hint}"
                + (f"; did you mean {', '.join(meant)}?" if meant else "")
            )
        return cls.create(**keywords)

    def sample_world(self) -> World:
        """A world of the kind the episodes run in: the fixed world, a random maze (seed 0), or
        the world sampler's draw from an RNG of seed :data:`SAMPLER_PROBE_SEED`."""
        if self.world is not None:
            return self.world
        if self.world_sampler is not None:
            return self.sampled_world(np.random.default_rng(SAMPLER_PROBE_SEED))
        return self.random_maze(0)

    def sampled_world(self, rng: np.random.Generator) -> World:
        """The world sampler's world for ``rng``, checked as a fixed world is.

        Raises:
            InvalidArgumentError: The sampler returned something that is not a World, a name or
                a path, or a world the options cannot run (too many cells; without a cell maze
                when ``start_goal="random"``).
        """
        sampler = self.world_sampler
        assert sampler is not None
        drawn = sampler(rng)
        if not isinstance(drawn, (World, str, os.PathLike)) or _is_random(drawn):
            raise InvalidArgumentError(
                f"expected the world sampler {_callable_name(sampler)} to return a World, a "
                f"built-in world name or a path to a world file; found {_shown(drawn)}. It is "
                "called "
                "with the env's numpy.random.Generator at each reset: return e.g. "
                "mazesim.generate_maze(5, 5, seed=int(rng.integers(2**32)))"
            )
        world = _resolve_world(drawn)
        _check_cells(world)
        if self.start_goal == "random":
            start_and_goal_cells(world)
        return world

    def random_maze(self, seed: int) -> World:
        """The random maze of one episode, generated from ``seed`` (a single-corridor draw is
        kept, ``junction=False``, as when the documented RL results were measured)."""
        width, height = self.maze_size
        return generate_maze(width, height, seed=seed, junction=False)

    def next_world(
        self, rng: np.random.Generator, held: _PositionBounds | None = None
    ) -> tuple[World | None, StartAndGoal | None]:
        """The world of the next episode, a random maze or the world sampler's world drawn from
        ``rng`` (None to keep the fixed world: nothing is drawn for it), and its start and goal,
        drawn next if ``start_goal="random"`` (None for the world's own).

        Raises:
            InvalidArgumentError: As :meth:`sampled_world`, or ``held`` (the positions in metres
                the env's observation space holds; None when it observes none) does not hold
                the drawn world.
        """
        if self.world is not None:
            world = self.world
        elif self.world_sampler is not None:
            world = self.sampled_world(rng)
        else:
            world = self.random_maze(draw_seed(rng))
        if held is not None and self.world is None:
            self._check_world_held(world, held)
        drawn = draw_start_and_goal(world, rng) if self.start_goal == "random" else None
        return (None if self.world is not None else world), drawn

    def _check_world_held(self, world: World, held: _PositionBounds) -> None:
        """Refuses a drawn world reaching outside the positions the observation space holds."""
        bounds = world.bounds
        if not _reaches_outside(bounds, held):
            return
        source = (
            f"the world sampler {_callable_name(self.world_sampler)}'s draw with an RNG of seed "
            f"{SAMPLER_PROBE_SEED} when the env was made"
            if self.world_sampler is not None
            else "the random maze of the maze_size the env was made with"
        )
        remedy = (
            "draw mazes of one size, or let that first draw be of the largest mazes drawn"
            if self.world_sampler is not None
            else "make the env with a maze_size as large as any its episodes draw"
        )
        raise InvalidArgumentError(
            "expected each episode's world to lie within the positions in metres the env's "
            f"observation space holds (x {held[0]:.3f} to {held[2]:.3f} m, y {held[1]:.3f} to "
            f"{held[3]:.3f} m, from {source}); found {_shown(world.name)}, reaching x "
            f"{bounds[0]:.3f} to {bounds[2]:.3f} m, y {bounds[1]:.3f} to {bounds[3]:.3f} m: "
            f"{remedy}"
        )


def _reaches_outside(bounds: _PositionBounds, held: _PositionBounds) -> bool:
    """Whether a world of ``bounds`` reaches outside the positions ``held`` (both min x, min y,
    max x, max y in metres), beyond float32 rounding: the one check of every drawn world and of
    every maze-size curriculum stage."""
    return (
        bounds[0] < held[0] - _BOUNDS_TOLERANCE
        or bounds[1] < held[1] - _BOUNDS_TOLERANCE
        or bounds[2] > held[2] + _BOUNDS_TOLERANCE
        or bounds[3] > held[3] + _BOUNDS_TOLERANCE
    )


def _check_cells(world: World) -> None:
    """Refuses a world whose cell maze has more than :data:`MAX_ENV_CELLS` cells."""
    maze = world.cell_maze()
    if maze is None:
        return
    cells = int(maze["rows"]) * int(maze["cols"])  # type: ignore[call-overload]
    if cells > MAX_ENV_CELLS:
        raise InvalidArgumentError(
            f"expected a world of at most {MAX_ENV_CELLS} maze cells for a gymnasium env (its "
            f"distance tables take about 2 kB and 60 us a cell), found {maze['rows']} x "
            f"{maze['cols']} = {cells} in {_shown(world.name)}; the simulators (Simulator, "
            f"BatchSimulator) take larger worlds"
        )


def option_names() -> list[str]:
    """The names of the environments' options, in the order of :meth:`EnvOptions.create`."""
    return list(inspect.signature(EnvOptions.create).parameters)


def _items(value: Any) -> tuple[Any, ...]:
    """The items of a (width, height) option given as a tuple, a list or a 1-d numpy array;
    ``(value,)`` for anything else (which the caller then refuses)."""
    if isinstance(value, (tuple, list)) or (isinstance(value, np.ndarray) and value.ndim == 1):
        return tuple(value)
    return (value,)


def _is_count(value: Any) -> bool:
    """Whether ``value`` is a whole number (a Python or numpy integer), not a bool."""
    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


def _is_random(world: WorldOption) -> bool:
    return isinstance(world, str) and world == "random"


def world_as_json(world: World) -> dict[str, str]:
    """The JSON form of a ``World`` that the ``world`` option accepts too: ``{"toml": its world
    file text, "source": its name}``."""
    return {"toml": world.to_toml(), "source": world.name}


def spec_with_json_world(spec: EnvSpec | None) -> EnvSpec | None:
    """``spec`` with a ``World`` given as ``world`` replaced by :func:`world_as_json`, so that
    ``spec.to_json()`` works and ``gymnasium.make(spec)`` makes the same env."""
    if spec is None or not isinstance(spec.kwargs.get("world"), World):
        return spec
    kwargs = {**spec.kwargs, "world": world_as_json(spec.kwargs["world"])}
    return dataclasses.replace(spec, kwargs=kwargs)


def json_world_spec() -> Any:
    """An env's ``spec`` property: it stores what ``gymnasium.make`` records through
    :func:`spec_with_json_world`."""

    def get(env: Any) -> EnvSpec | None:
        spec: EnvSpec | None = env.__dict__.get("_spec")
        return spec

    def put(env: Any, spec: EnvSpec | None) -> None:
        env.__dict__["_spec"] = spec_with_json_world(spec)

    return property(get, put, doc="The env's spec, its world in JSON form (world_as_json).")


def _callable_name(sampler: Any) -> str:
    """The name of a world sampler for a message: its qualified name, or its repr."""
    name = getattr(sampler, "__qualname__", None)
    return repr(name) if isinstance(name, str) else repr(sampler)


def _resolve_world(world: WorldOption) -> World:
    if isinstance(world, World):
        return world
    if isinstance(world, dict) and set(world) == {"toml", "source"}:
        return World.from_toml(str(world["toml"]), str(world["source"]))
    if not isinstance(world, (str, os.PathLike)):
        raise InvalidArgumentError(
            f'expected world to be a built-in world name, a path, "random", a World, '
            f'{{"toml": ..., "source": ...}} or a callable; '
            f'found {_shown(world)}. An env runs one world, or with "random" a new generated '
            "maze of "
            "maze_size cells at each reset; for mazes of your own choosing give a callable "
            "that draws each episode's world from the env's RNG: world=lambda rng: "
            "worlds[rng.integers(len(worlds))]"
        )
    return mazesim.load_world(world)
