"""Hand-written baseline agents for the unseen-maze tasks: a wall follower and a frontier explorer.

Both act on the observation of ``mazesim/UnseenMazeExplore-v0`` (the ``"explore"`` observation), as
``agent.act(observation) -> action``, continuous wheel speeds in [-1, 1]. They read nothing else:
the open sides of the robot's own cell (``open_ahead`` ... ``open_right``), the goal's direction
and their previous action, from which they keep their own odometry (:class:`CellAgent`); or, made
with ``include_pose=True``, the pose instead of the odometry. Neither ever sees a wall of a cell
the robot has not been in.

Each moves from cell centre to cell centre: on reaching the centre of the cell it was heading
for it picks a neighbour whose side is open and drives there (turn towards the cell's centre,
drive when it is ahead). They differ in the choice:

- :class:`WallFollower`: the left-hand rule of maze solving: turn left if that side is open,
  else go straight, else right, else back. In a maze without loops (every maze of the unseen-maze
  tasks: the generator's default) it walks round the walls through every cell, the goal's among
  them, taking each passage at most once each way; it ignores the goal's direction.
- :class:`FrontierExplorer`: frontier-based exploration (Yamauchi, 1997) on a map of cells it
  builds from its observations: the sides of every cell it has been in. When the goal's cell
  (known from the goal's direction and the pose) is joined to the robot's through that map, or is
  the cell across an open side of a cell it has been in, it goes there by the shortest known
  path; otherwise it goes to the nearest frontier (a cell it has not been in, across an open side
  of one it has), the frontier nearest the goal among equally near ones.

:func:`evaluate` runs an agent (or uniformly random actions) on the held-out episodes of
``examples/ppo_sb3.py`` and gives the success rate and the mean length of the episodes.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np
import numpy.typing as npt

from mazesim._sizes import number_array
from mazesim.errors import InvalidArgumentError, RegisteredName, _known_name, _shown

__all__ = [
    "BaselineResult",
    "CellAgent",
    "EpisodeAgent",
    "PredictingModel",
    "FrontierExplorer",
    "WallFollower",
    "evaluate",
]

#: A cell as (column, row), row 0 at the bottom (y up), as the pose's x and y.
Cell = tuple[int, int]
#: The (column, row) step across each side, indexed by direction: east, north, west, south.
_STEPS: tuple[Cell, ...] = ((1, 0), (0, 1), (-1, 0), (0, -1))
#: The observation's sides, relative to the robot: ahead, left, behind, right (counter-clockwise).
_SIDES = ("open_ahead", "open_left", "open_behind", "open_right")
#: The observation names the agents always read.
_NEEDED = ("goal_forward", "goal_left", *_SIDES)
#: The pose's names (``include_pose=True``); without them the agent keeps its own odometry.
_POSE = ("x", "y", "heading_cos", "heading_sin")
#: The previous action's names, which the odometry integrates.
_PREVIOUS = ("previous_left", "previous_right")
#: A cell's centre counts as reached within this fraction of a cell.
_ARRIVED = 0.15
#: The largest heading error (radians) at which the robot drives forward; beyond it, it turns.
_AHEAD = 0.5
#: Forward speed (fraction of the motor limit) when the target is ahead.
_DRIVE = 0.8
#: Wheel speeds (fractions) of the slow spin that finds the maze's axes without the pose.
_SPIN = 0.05
#: The e-puck's turn (radians) per control step of 128 ms per unit of (right - left) wheel speed
#: fraction: wheel radius 0.02 m x 6.28 rad/s / wheel distance 0.05685 m x 0.128 s.
EPUCK_TURN_PER_STEP = 0.02 * 6.28 / 0.05685 * 0.128


class CellAgent:
    """An agent that drives from cell centre to cell centre, choosing each next cell from what it
    has observed (:meth:`choose`, the rule of a subclass).

    With the pose in the observation (``include_pose=True``) it reads its cell and heading there.
    Without it (``UnseenMazeExplore-v0`` as registered) it keeps its own odometry, as a robot would:
    its heading turned since the start, from its previous actions (exact while it touches no wall);
    its position relative to the goal, from the goal's direction rotated by that heading (the goal
    is at a cell's centre, so the cells are those of the maze round it); and, first, the maze's
    axes: it spins slowly on the spot until the open sides it observes move round by one, which
    happens when its heading crosses a diagonal of its cell (a start cell open on all four sides, or
    on none, shows no such change: the agent then takes its start heading as an axis).

    Args:
        observation_names: The env's ``observation_names`` (``env.unwrapped.observation_names``):
            the agent finds its values by name.
        maze_size: The maze's columns and rows (5 x 5 for the unseen-maze tasks).
        turn_per_step: Radians turned in one control step per unit of right minus left wheel
            speed fraction (the e-puck's at 128 ms by default); used without the pose only.

    Raises:
        InvalidArgumentError: A value the agent reads is not in the observation (make the task
            with ``observation="explore"``).
    """

    def __init__(
        self,
        observation_names: Sequence[str],
        maze_size: tuple[int, int] = (5, 5),
        turn_per_step: float = EPUCK_TURN_PER_STEP,
    ):
        names = list(observation_names)
        self.uses_pose = all(name in names for name in _POSE)
        needed = (*_NEEDED, *(_POSE if self.uses_pose else _PREVIOUS))
        missing = [name for name in needed if name not in names]
        if missing:
            raise InvalidArgumentError(
                f"a baseline agent reads {', '.join(needed)} from the observation; missing: "
                f"{', '.join(missing)} (make the task with observation='explore')"
            )
        self._index = {name: names.index(name) for name in needed}
        self._width = len(names)
        self.columns, self.rows = (int(size) for size in maze_size)
        self.turn_per_step = float(turn_per_step)
        self.reset()

    def reset(self) -> None:
        """Forgets the episode: call it before the first action of each episode."""
        self._target: Cell | None = None
        #: The open sides (by direction: east, north, west, south) of each cell the robot has
        #: been in, as its observations gave them.
        self.known: dict[Cell, tuple[bool, bool, bool, bool]] = {}
        self._heading_of_travel: int | None = None
        #: Without the pose: the heading turned since the start, the previous step's, the
        #: offset of the maze's axes from the start heading once found, the first side pattern.
        self._turned = 0.0
        self._turned_before = 0.0
        self._axes: float | None = None
        self._first_pattern: tuple[bool, ...] | None = None

    def act(self, observation: npt.ArrayLike) -> npt.NDArray[np.float32]:
        """The wheel speeds (left, right, fractions of the motor limit) for ``observation``."""
        values = number_array(observation, "observation", checked_after=True)
        if values.shape != (self._width,) or not np.isfinite(values).all():
            found = f"shape {values.shape}" if values.shape != (self._width,) else "NaN or infinity"
            raise InvalidArgumentError(
                f"expected observation to be {self._width} finite numbers (one per name of "
                f"observation_names), found {found}"
            )
        sides = tuple(bool(values[self._index[side]] > 0.5) for side in _SIDES)
        if self.uses_pose:
            x, y, yaw, goal = self._pose(values)
        else:
            located = self._odometry(values, sides)
            if located is None:
                return np.array([-_SPIN, _SPIN], dtype=np.float32)
            x, y, yaw, goal = located
        here = (round(x), round(y))
        near = math.hypot(x - here[0], y - here[1]) < _ARRIVED
        if self._target is None or (here == self._target and near):
            facing = round(yaw / (math.pi / 2)) % 4
            opened = tuple(sides[(direction - facing) % 4] for direction in range(4))
            self.known[here] = (opened[0], opened[1], opened[2], opened[3])
            travel = facing if self._heading_of_travel is None else self._heading_of_travel
            direction = self.choose(here, travel, goal)
            self._heading_of_travel = direction
            step = _STEPS[direction]
            self._target = (here[0] + step[0], here[1] + step[1])
        return self._drive_to(self._target, x, y, yaw)

    def choose(self, here: Cell, travel: int, goal: Cell) -> int:
        """The direction (0 east, 1 north, 2 west, 3 south) of the next cell, through an open side
        of ``here`` (``self.known[here]``); ``travel`` is the direction of the last move."""
        raise NotImplementedError

    def _pose(self, values: npt.NDArray[np.float64]) -> tuple[float, float, float, Cell]:
        """x, y in cells (cell centres at whole numbers), the heading, and the goal's cell, from
        the observed pose and the goal's direction."""
        yaw = math.atan2(values[self._index["heading_sin"]], values[self._index["heading_cos"]])
        x = values[self._index["x"]] * self.columns - 0.5
        y = values[self._index["y"]] * self.rows - 0.5
        east, north = self._to_goal(values, yaw)
        return x, y, yaw, (round(x + east), round(y + north))

    def _odometry(
        self, values: npt.NDArray[np.float64], sides: tuple[bool, ...]
    ) -> tuple[float, float, float, Cell] | None:
        """x, y in cells relative to the goal's cell and the heading, both in the frame of the
        maze's axes found by the first spin, and the goal's cell (0, 0); None while spinning."""
        left, right = values[self._index["previous_left"]], values[self._index["previous_right"]]
        self._turned_before = self._turned
        self._turned += self.turn_per_step * (right - left)
        if self._axes is None:
            pattern = sides
            if self._first_pattern is None:
                self._first_pattern = pattern
            elif pattern != self._first_pattern:
                # The heading crossed a diagonal (45 degrees off an axis) between the two steps.
                self._axes = math.pi / 4 - (self._turned + self._turned_before) / 2
            elif self._turned >= math.tau:
                self._axes = 0.0  # a symmetric start cell: no axis to find
            if self._axes is None:
                return None
        yaw = self._turned + self._axes
        east, north = self._to_goal(values, yaw)
        return -east, -north, yaw, (0, 0)

    def _to_goal(self, values: npt.NDArray[np.float64], yaw: float) -> tuple[float, float]:
        """The goal's offset from the robot in cells along the axes (east, north) of a frame in
        which the robot's heading is ``yaw``."""
        forward, left = values[self._index["goal_forward"]], values[self._index["goal_left"]]
        side = max(self.columns, self.rows)
        east = (math.cos(yaw) * forward - math.sin(yaw) * left) * side
        north = (math.sin(yaw) * forward + math.cos(yaw) * left) * side
        return east, north

    def _drive_to(self, cell: Cell, x: float, y: float, yaw: float) -> npt.NDArray[np.float32]:
        """Turn towards ``cell``'s centre, drive when it is ahead."""
        error = math.remainder(math.atan2(cell[1] - y, cell[0] - x) - yaw, math.tau)
        drive = 0.0 if abs(error) > _AHEAD else _DRIVE
        return np.clip([drive - error, drive + error], -1.0, 1.0).astype(np.float32)


class WallFollower(CellAgent):
    """The left-hand rule over the cells: left if open, else straight, else right, else back."""

    def choose(self, here: Cell, travel: int, goal: Cell) -> int:
        opened = self.known[here]
        for turn in (1, 0, 3, 2):  # left, straight, right, back
            direction = (travel + turn) % 4
            if opened[direction]:
                return direction
        return (travel + 2) % 4  # walled in on every side: nothing to do but turn


class FrontierExplorer(CellAgent):
    """Goes to the goal's cell once its map joins it to the robot, else to the nearest frontier
    cell (the one nearest the goal among equally near ones)."""

    def choose(self, here: Cell, travel: int, goal: Cell) -> int:
        first_steps = self._first_steps(here)
        if goal in first_steps:
            return first_steps[goal][1]
        frontier = [cell for cell in first_steps if cell not in self.known]
        if not frontier:
            return travel  # nothing left to explore: the map holds no way on
        best = min(
            frontier,
            key=lambda cell: (
                first_steps[cell][0],
                abs(cell[0] - goal[0]) + abs(cell[1] - goal[1]),
                cell,
            ),
        )
        return first_steps[best][1]

    def _first_steps(self, here: Cell) -> dict[Cell, tuple[int, int]]:
        """Every cell reachable through the open sides of cells the robot has been in (the
        frontier included), with its distance in cells and the direction of the first step."""
        found: dict[Cell, tuple[int, int]] = {here: (0, -1)}
        queue = deque([here])
        while queue:
            cell = queue.popleft()
            if cell not in self.known:
                continue  # a frontier cell: its sides are not known
            distance, first = found[cell]
            for direction, is_open in enumerate(self.known[cell]):
                step = _STEPS[direction]
                across = (cell[0] + step[0], cell[1] + step[1])
                if is_open and across not in found:
                    found[across] = (distance + 1, direction if first < 0 else first)
                    queue.append(across)
        return found


@dataclass(frozen=True)
class BaselineResult:
    """What :func:`evaluate` measured.

    Attributes:
        episodes: The number of episodes (one per held-out environment).
        success: The fraction of them that reached the goal.
        mean_length: The mean length (control steps) of all episodes, the failed ones at the limit.
        mean_success_length: The mean length of the episodes that reached the goal (NaN if none).
    """

    episodes: int
    success: float
    mean_length: float
    mean_success_length: float


class EpisodeAgent(Protocol):
    """What :func:`evaluate` drives each episode with: a hand rule of this module, or a policy of
    your own (``act`` returns the action for one env's observation)."""

    def act(self, observation: npt.NDArray[np.float32]) -> Any:
        """The action for ``observation``."""


class PredictingModel(Protocol):
    """A model with Stable-Baselines3's ``predict(observation, deterministic=...)``, which
    returns the action and a recurrent state."""

    def predict(self, observation: Any, *args: Any, **kwargs: Any) -> Any:
        """The action for ``observation``, and the model's recurrent state."""


class _FunctionAgent:
    """A function ``observation -> action`` as an agent."""

    def __init__(self, function: Callable[[Any], Any]) -> None:
        self.function = function

    def act(self, observation: npt.NDArray[np.float32]) -> Any:
        """The function's action for ``observation``, refused if it is a pair such as
        Stable-Baselines3's ``predict`` returns."""
        action = self.function(observation)
        if isinstance(action, tuple) and len(action) == 2:
            raise InvalidArgumentError(
                f"evaluate: expected the agent function to return an action, found a pair "
                f"{_shown(action)}, as Stable-Baselines3's predict returns (action, state): "
                f"pass the model itself (evaluate(task, model)), which is driven with "
                f"model.predict(observation, deterministic=True)[0]"
            )
        return action


class _ModelAgent:
    """A Stable-Baselines3 model as an agent, acting deterministically."""

    def __init__(self, model: PredictingModel) -> None:
        self.model = model

    def act(self, observation: npt.NDArray[np.float32]) -> Any:
        """The model's deterministic action for ``observation``."""
        return self.model.predict(observation, deterministic=True)[0]


_AGENT_FORMS = (
    "a function observation -> action; an object with act(observation) -> action; a "
    "Stable-Baselines3 model (its predict, deterministic); or a class or function called as "
    "agent(observation_names, maze_size) that makes one such object per episode"
)


def _required_positional(function: Callable[..., Any]) -> int | None:
    """How many positional arguments ``function`` needs (None when unknown or any number)."""
    import inspect

    try:
        parameters = inspect.signature(function).parameters.values()
    except (TypeError, ValueError):
        return None
    if any(p.kind is p.VAR_POSITIONAL for p in parameters):
        return None
    positional = (inspect.Parameter.POSITIONAL_ONLY, inspect.Parameter.POSITIONAL_OR_KEYWORD)
    return sum(1 for p in parameters if p.kind in positional and p.default is p.empty)


def _episode_agents(
    agent: object, names: Sequence[str], size: tuple[int, int], episodes: int
) -> list[EpisodeAgent]:
    """The agents driving ``episodes`` episodes, from any form :func:`evaluate` takes (see
    there), or an :class:`~mazesim.errors.InvalidArgumentError` naming the forms."""
    if not isinstance(agent, type):
        if callable(getattr(agent, "act", None)):
            return [agent] * episodes  # type: ignore[list-item]
        if callable(getattr(agent, "predict", None)):
            return [_ModelAgent(agent)] * episodes  # type: ignore[arg-type]
        owner = getattr(agent, "__self__", None)
        if getattr(agent, "__name__", "") == "predict" and callable(
            getattr(owner, "predict", None)
        ):
            return [_ModelAgent(owner)] * episodes  # type: ignore[arg-type]
    if not callable(agent):
        raise InvalidArgumentError(
            f"evaluate: expected as the agent {_AGENT_FORMS}; found {_shown(agent)}"
        )
    needed = _required_positional(agent)
    if isinstance(agent, type):  # a class is made once per episode
        if needed == 0:
            return [agent() for _ in range(episodes)]
    elif needed == 1:
        return [_FunctionAgent(agent)] * episodes
    elif needed not in (None, 2):
        raise InvalidArgumentError(
            f"evaluate: expected as the agent {_AGENT_FORMS}; found {_shown(agent)}, which needs "
            f"{needed} arguments"
        )
    made = [agent(names, size) for _ in range(episodes)]
    if not callable(getattr(made[0], "act", None)):
        raise InvalidArgumentError(
            f"evaluate: expected agent(observation_names, maze_size) to make an object with "
            f"act(observation) -> action, found {_shown(made[0])}"
        )
    return made


def evaluate(
    task: RegisteredName,
    agent: Callable[..., Any] | EpisodeAgent | PredictingModel | None,
    episodes: int = 100,
    seed: int = 10**6,
    include_pose: bool = False,
    maze_size: tuple[int, int] | None = None,
    **options: Any,
) -> BaselineResult:
    """Runs one episode in each of ``episodes`` environments of ``task`` seeded ``seed``,
    ``seed + 1``, ... (``examples/ppo_sb3.py``'s held-out episodes for ``seed = 10**6 + its
    seed``), each driven by its own ``agent(observation_names, maze_size)`` (any object with an
    ``act(observation)`` method: a policy of your own too),
    or by uniformly random actions (the action space seeded with ``seed``) if ``agent`` is None;
    with ``include_pose`` the observations hold the pose (the episodes are the same); with
    ``maze_size`` the random mazes have that many cells (the task's own, 5 x 5, without).
    ``options`` are further options of the task (:class:`~mazesim.envs.options.EnvOptions`),
    such as ``world=`` a world sampler that draws held-out mazes of your own.
    """
    import gymnasium

    if not isinstance(episodes, (int, np.integer)) or isinstance(episodes, bool) or episodes < 1:
        raise InvalidArgumentError(
            f"expected episodes to be a whole number of at least 1 (one held-out environment "
            f"each), found {_shown(episodes)}"
        )
    if not isinstance(task, str) or task not in gymnasium.registry:
        from mazesim.envs.tasks import task_ids

        _known_name(task, "evaluate's task", task_ids())
    size = (5, 5) if maze_size is None else (int(maze_size[0]), int(maze_size[1]))
    envs = gymnasium.make_vec(
        task, num_envs=episodes, include_pose=include_pose, maze_size=size, **options
    )
    try:
        observations, _ = envs.reset(seed=seed)
        names = _observation_names(envs)
        agents = _episode_agents(agent, names, size, episodes) if agent is not None else []
        envs.action_space.seed(seed)
        steps = np.zeros(episodes, dtype=np.int64)
        success = np.zeros(episodes, dtype=bool)
        finished = np.zeros(episodes, dtype=bool)
        while not finished.all():
            if agents:
                actions = np.stack([each.act(obs) for each, obs in zip(agents, observations)])
            else:
                actions = envs.action_space.sample()
            observations, _, terminated, truncated, infos = envs.step(actions)
            steps += ~finished
            ended = (terminated | truncated) & ~finished
            success |= ended & infos["is_success"]
            finished |= ended
    finally:
        envs.close()
    lengths = steps[success]
    return BaselineResult(
        episodes,
        float(success.mean()),
        float(steps.mean()),
        float(lengths.mean()) if lengths.size else math.nan,
    )


def _observation_names(envs: object) -> list[str]:
    names = getattr(getattr(envs, "unwrapped", envs), "observation_names", None)
    if names is None:
        raise InvalidArgumentError("the vector env does not name its observation's values")
    return list(names)
