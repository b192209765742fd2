"""``mazesim/EPuckMaze-v0``: one robot in a maze, as a gymnasium environment."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, SupportsFloat

import gymnasium
import numpy as np
import numpy.typing as npt

from mazesim._core import Simulator, StepBounds, World
from mazesim._hot_paths import checks_own_arguments
from mazesim.envs.errors import EnvClosedError, ResetNeededError, check_options, check_seed
from mazesim.envs.navigation import (
    NavigationFeatures,
    StartAndGoal,
    distance_table,
    navigation_features,
)
from mazesim.envs.options import EnvOptions, draw_seed, json_world_spec
from mazesim.envs.spaces import ActionConverter, ObservationLayout, sensor_ranges
from mazesim.errors import (
    RegisteredName,
    WrongTypeError,
    _a_type,
    _known_name,
)
from mazesim.maze import PathDistanceTable
from mazesim.render.episode import EpisodeTrace
from mazesim.render.topdown import TopDownRenderer

__all__ = [
    "RENDER_MODES",
    "VECTOR_RENDER_MODES",
    "EPuckMazeEnv",
    "check_render_mode",
    "step_length_ms",
]


class _RenderModes(tuple[str, ...]):
    """The render modes of an env, as its ``metadata["render_modes"]``: asked whether it holds
    something that is neither a str nor None, it refuses it with a WrongTypeError naming the
    modes, since ``gymnasium.make(..., render_mode=42)`` asks so before the env is made (and
    would otherwise fail inside gymnasium on ``42.endswith``)."""

    __slots__ = ()

    def __contains__(self, value: object) -> bool:
        if value is None:
            return False
        if not isinstance(value, str):
            raise WrongTypeError(
                f"expected render_mode to be None or one of {', '.join(self)}; "
                f"found {_a_type(value)}"
            )
        return super().__contains__(value)


#: The render modes of the maze environment: a live window, or top-down RGB images.
RENDER_MODES = _RenderModes(("human", "rgb_array"))
#: The render modes of the vector environments (images only).
VECTOR_RENDER_MODES = _RenderModes(("rgb_array",))
#: What an env of ``render_mode="human"`` says once where no window can open (``{problem}``: the
#: reason): what becomes of its frames, how to get them, and that gymnasium's ``check_env``,
#: which makes an env of every declared render mode, needs nothing done.
HUMAN_MODE_HEADLESS_NOTICE = (
    'mazesim: render_mode="human" shows no window here: {problem}; its frames are drawn but not '
    'shown (render_mode="rgb_array" returns them as arrays). Nothing to do when gymnasium\'s '
    "check_env made this env: it tries every render mode"
)


def step_length_ms(options: EnvOptions, world: World) -> float:
    """The length of a control step in ms: the option, or the world's basic time step."""
    return (
        options.control_step_ms if options.control_step_ms is not None else world.basic_time_step_ms
    )


def check_render_mode(
    render_mode: RegisteredName | None, modes: Sequence[str] = RENDER_MODES
) -> None:
    """Raises UnknownNameError unless ``render_mode`` is None or one of ``modes``
    (WrongTypeError for one that is not a str)."""
    if render_mode is not None and render_mode not in modes:
        _known_name(render_mode, "render_mode", tuple(modes))


class EPuckMazeEnv(gymnasium.Env[npt.NDArray[np.float32], Any]):
    """A robot (the e-puck by default) that must drive to the goal of a maze.

    Every step runs one control step of the simulator (the world's basic time step, 32 ms in the
    built-in worlds) with the wheel speeds of the action, then reads the sensors.

    Observation: the sensor readings as a float32 vector, distance sensors then ground sensors
    (for the e-puck: ps0-ps7 raw counts, gs0-gs2 raw), with the pose appended when
    ``include_pose`` is set; see :mod:`mazesim.envs.spaces` for each index and the bounds. With
    ``observation="goal"``, ``"explore"``, ``"guided"`` or ``"plan"``: normalised readings, the
    goal (and the explored map, the next waypoint) in the robot's frame and the previous action
    (:mod:`mazesim.envs.navigation`).

    Action: ``"continuous"``, ``Box(-1, 1, (2,), float32)``, the left and right wheel speeds as
    fractions of the motor limit; or ``"discrete"``, ``Discrete(12)``, the report's primitive
    actions of :mod:`mazesim.actions` (``00`` forward, ``11``-``44`` right turns, ...).
    Continuous actions outside [-1, 1] are clipped (``clip_actions=True``, the default).

    Reward: ``progress * (metres gained along the shortest path to the goal)
    - collision * (1 while touching a wall) + goal * (1 on reaching the goal)``, by default with
    progress 10, collision 0.1 and goal 10; see :mod:`mazesim.envs.reward`.

    Episode end: terminated when the robot's centre enters the goal disc; truncated by the time
    limit (``max_episode_steps`` of the registration, 3000 steps, applied by ``gymnasium.make``).

    Info (after reset and after every step): ``pose`` (float32 x, y, yaw), ``collisions`` (bumps
    since the reset), ``colliding`` (touching a wall now), ``distance_to_goal`` (the shortest-path
    distance in metres), ``is_success`` (True on the step that reaches the goal) and, only on a
    step that crossed a barcode checkpoint, ``checkpoint``: its id, positive when crossed along
    the barcode's direction (arriving), negative when departing.

    Seeding: ``reset(seed=s)`` seeds the env's RNG; each episode draws its simulator seed (and its
    maze, with ``world="random"``) from that RNG, so the same seed and actions replay the same
    episodes bit for bit.

    Args:
        render_mode: None, ``"rgb_array"`` (a top-down image with the trail and an overlay of
            time, step, reward and the last event, see :mod:`mazesim.render.topdown`), or
            ``"human"`` (that image in a window that updates every step).
        **options: The options of :meth:`mazesim.envs.options.EnvOptions.create`, the one list
            of them: ``world``, ``robot``, ``action_mode``, ``clip_actions``, ``observation``,
            ``start_goal``, ``noise``, ``include_pose``, ``control_step_ms``, ``maze_size``,
            ``goal_reward``, ``collision_penalty``, ``progress_reward``, ``render_size``.

    Raises:
        InvalidArgumentError: An option has a wrong type or value.
        UnknownNameError: The world or robot profile does not exist.
    """

    metadata: dict[str, Any] = {"render_modes": RENDER_MODES, "render_fps": 31.25}

    def __init__(self, render_mode: RegisteredName | None = None, **options: Any) -> None:
        check_render_mode(render_mode)
        self._closed = False
        self.render_mode = render_mode
        self.options = EnvOptions.from_keywords(options)
        self.world = self.options.sample_world()
        self.metadata = {
            **type(self).metadata,
            "render_fps": 1000.0 / step_length_ms(self.options, self.world),
        }
        self._layout = ObservationLayout(self.options.robot, self.world, self.options.include_pose)
        self._actions = ActionConverter(
            self.options.action_mode, self.options.robot.max_wheel_speed, self.options.clip_actions
        )
        table = PathDistanceTable.of_world(self.world)
        self._features = navigation_features(
            self.options.observation,
            1,
            self.options.robot,
            self.world,
            table,
            self.options.include_pose,
        )
        # The features whose core computes each step's goal distance, in the same call as the
        # step: the observation's own, or (for the raw readings) the goal's alone.
        self._observes = self._features is not None
        task = self._features or navigation_features(
            "goal", 1, self.options.robot, self.world, table
        )
        assert task is not None  # the "goal" kind has features
        self._task: NavigationFeatures = task
        self._max_speed = float(self._actions.max_speed)
        weights = self.options.reward
        self._weights = (weights.progress, weights.collision, weights.goal)
        features = self._features
        self.observation_space = self._layout.space if features is None else features.space
        # The positions in metres the observation space holds (the pose of the raw readings; a
        # goal env narrows them to its goals'): each drawn world must lie within them.
        self._held_bounds = self._layout.position_bounds if features is None else None
        self.action_space = self._actions.space
        width = self._layout.sensor_width
        self._low = np.ascontiguousarray(self._layout.low[:width])
        self._high = np.ascontiguousarray(self._layout.high[:width])
        self._bounds = StepBounds(self._low, self._high, self._max_speed)
        self._drawn: StartAndGoal | None = None
        self._distance = 0.0
        self._simulator: Simulator | None = None
        self._renderer: TopDownRenderer | None = None
        self._live: Any = None
        self._trace = EpisodeTrace()

    @property
    def observation_names(self) -> list[str]:
        """What each index of the observation holds (sensor names, then x, y, yaw, or the
        navigation features)."""
        return list(self._layout.names if self._features is None else self._features.names)

    #: The spec ``gymnasium.make`` recorded, a ``World`` given as ``world`` in its JSON form
    #: (:func:`~mazesim.envs.options.world_as_json`) so that ``spec.to_json()`` works.
    spec = json_world_spec()

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[npt.NDArray[np.float32], dict[str, Any]]:
        """Starts a new episode; ``options`` (a dict) are accepted and unused.

        Raises:
            InvalidArgumentError: ``seed`` is not None or an int in ``0..=2**64-1``, or
                ``options`` is not None or a dict.
            EnvClosedError: The env is closed.
        """
        self._check_open()
        check_options(options)
        super().reset(seed=check_seed(seed))
        world, drawn = self.options.next_world(self.np_random, self._held_bounds)
        episode_seed = draw_seed(self.np_random)
        simulator = self._simulator
        fresh = world is not None or simulator is None
        if fresh:
            self.world = world if world is not None else self.world
            simulator = self._simulator = Simulator(
                self.world,
                robot=self.options.robot,
                seed=episode_seed,
                noise=self.options.noise,
                control_step_ms=self.options.control_step_ms,
            )
        assert simulator is not None
        if drawn is not None:
            simulator.set_start(*drawn.start)
            simulator.set_goal(*drawn.goal)
        if drawn is not None or not fresh:
            simulator.reset(seed=episode_seed)
        if fresh or drawn is not None:
            table = distance_table(self.world, None if drawn is None else drawn.goal)
            self._task.set(0, self.world, table)  # the goal distance too
            self._renderer = None
        self._drawn = drawn
        readings = np.concatenate((simulator.distance_sensors(), simulator.ground_sensors()))
        pose = np.array(simulator.pose, dtype=np.float32)
        x, y, yaw = pose.tolist()
        self._task.restart(0)
        features, self._distance, _ = self._task.observe_one(
            readings, pose, 0.0, 0.0, self._max_speed
        )
        observation = features if self._observes else self._layout.assemble_one(readings, pose)
        self._trace.restart(x, y)
        if self.render_mode == "human":
            self.render()
        info = {
            "pose": pose,
            "collisions": simulator.collisions,
            "colliding": simulator.colliding,
            "distance_to_goal": self._distance,
            "is_success": False,
        }
        return observation, info

    @checks_own_arguments
    def step(
        self, action: Any
    ) -> tuple[npt.NDArray[np.float32], SupportsFloat, bool, bool, dict[str, Any]]:
        """Runs one control step with ``action``.

        Raises:
            InvalidActionError: The action has a wrong shape or dtype, is NaN or infinite, or is
                outside the space (a continuous one only with ``clip_actions=False``).
            ResetNeededError: :meth:`reset` has not been called since the env was made.
            EnvClosedError: The env is closed.
        """
        simulator = self._simulator
        if simulator is None or self._closed:
            self._check_open()
            raise ResetNeededError("call reset() before step()")
        left, right = self._actions.single(action)
        # The step, the observation (the task's, or the clamped readings), the distance to the
        # goal and whether it is reached, in one call into the core.
        observation, pose, colliding, crossing, collisions, distance, reached = simulator.step_task(
            self._task.core, self._bounds, left, right, self._observes
        )
        if not self._observes and self._layout.include_pose:
            observation = self._layout.assemble_one(observation, pose)
        progress, collision, goal = self._weights
        reward = (
            progress * (self._distance - distance)
            - collision * float(colliding)
            + goal * float(reached)
        )
        self._distance = distance
        info = {
            "pose": pose,
            "collisions": collisions,
            "colliding": colliding,
            "distance_to_goal": distance,
            "is_success": reached,
        }
        if crossing != 0:
            info["checkpoint"] = crossing
        if self.render_mode is not None:
            self._trace.note(
                float(pose[0]),
                float(pose[1]),
                reward,
                reached,
                crossing,
                colliding,
                simulator.steps,
            )
            if self.render_mode == "human":
                self.render()
        return observation, reward, reached, False, info

    @property
    def goal_disc(self) -> tuple[float, float, float] | None:
        """x, y and radius (metres) of this episode's goal disc, or None in a world without a
        goal."""
        drawn = getattr(self, "_drawn", None)
        return drawn.goal if drawn is not None else self.world.goal

    def render(self) -> npt.NDArray[np.uint8] | None:
        """A top-down (height, width, 3) uint8 image with ``render_mode="rgb_array"``; with
        ``"human"``, the same image shown in a window (:class:`mazesim.render.live.LiveView`,
        which carries on headless where there is no display) and None.

        The image shows the start pose and the goal, the robot's trail since the reset, and the
        time, step, last reward (and the episode's return) and last event at the top left.
        """
        self._check_open()
        if self.render_mode is None:
            gymnasium.logger.warn(
                'render() needs a render mode: make the env with render_mode="rgb_array"'
            )
            return None
        frame = self._frame()
        if self.render_mode == "human":
            from mazesim.render.live import shown_in

            fps = float(self.metadata["render_fps"])
            title = f"mazesim: {self.world.name}"
            self._live = shown_in(self._live, frame, title, fps, HUMAN_MODE_HEADLESS_NOTICE)
            return None
        return frame

    def _frame(self) -> npt.NDArray[np.uint8]:
        if self._renderer is None:
            drawn = self._drawn
            self._renderer = TopDownRenderer(
                self.world,
                self.options.robot,
                self.options.render_size,
                sensor_ranges(self.options.robot).ray_length,
                start=None if drawn is None else drawn.start,
                goal=None if drawn is None else drawn.goal,
            )
        if self._simulator is None:
            return self._renderer.frame(self.world.start)
        simulator = self._simulator
        return self._trace.frame(
            self._renderer, simulator.pose, simulator.colliding, simulator.time, simulator.steps
        )

    def __getstate__(self) -> dict[str, Any]:
        """What pickling and deep-copying keep: everything but the window and the renderer (made
        again when needed); the simulator pickles with its whole state, so a copy goes on
        exactly as the original."""
        state = self.__dict__.copy()
        state["_live"] = None
        state["_renderer"] = None
        return state

    def _check_open(self) -> None:
        if self._closed:
            raise EnvClosedError("the env is closed: make a new one")

    def close(self) -> None:
        """Releases the simulator and the renderer; safe to call more than once. A closed env
        raises :class:`~mazesim.envs.errors.EnvClosedError` from then on, as the vector env
        does."""
        self._closed = True
        self._simulator = None
        self._renderer = None
        if self._live is not None:
            self._live.close()
            self._live = None
