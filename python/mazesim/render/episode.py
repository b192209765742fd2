"""What a frame of a maze env shows beside the world and the robot: the trail since the reset and
the overlay of time, step, last reward, the episode's return and the last event.

One :class:`EpisodeTrace` per environment, kept by the single env and (when it renders) by every
environment of the native vector env, so both draw their frames the same way
(:meth:`EpisodeTrace.frame`), with :class:`~mazesim.render.topdown.TopDownRenderer`.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from mazesim.render.topdown import TopDownRenderer

__all__ = ["EpisodeTrace"]


class EpisodeTrace:
    """The trail, rewards and last event of one environment's episode.

    Args:
        x: Where the episode starts (metres).
        y: Where the episode starts (metres).
    """

    def __init__(self, x: float = 0.0, y: float = 0.0) -> None:
        self.trail: list[tuple[float, float]] = []
        self.last_reward = 0.0
        self.episode_return = 0.0
        self.last_event = "none"
        self.restart(x, y)

    def restart(self, x: float, y: float) -> None:
        """Starts a new episode at (x, y): the trail holds that point alone."""
        self.trail = [(x, y)]
        self.last_reward = self.episode_return = 0.0
        self.last_event = "none"

    def note(
        self,
        x: float,
        y: float,
        reward: float,
        reached: bool,
        crossing: int,
        colliding: bool,
        step: int,
    ) -> None:
        """Counts a step that ended at (x, y) with ``reward``: whether it reached the goal, the
        signed checkpoint it crossed (0: none), whether the robot touches a wall, and the step's
        number in the episode."""
        self.trail.append((x, y))
        self.last_reward = reward
        self.episode_return += reward
        if reached:
            self.last_event = f"goal reached at step {step}"
        elif crossing != 0:
            direction = "arrival" if crossing > 0 else "departure"
            self.last_event = f"checkpoint {abs(crossing)} ({direction}) at step {step}"
        elif colliding:
            self.last_event = f"touching a wall at step {step}"

    def frame(
        self,
        renderer: TopDownRenderer,
        pose: tuple[float, float, float],
        colliding: bool,
        time_s: float,
        step: int,
    ) -> npt.NDArray[np.uint8]:
        """The frame of the robot at ``pose`` with the trail and the overlay, ``time_s`` seconds
        and ``step`` steps into the episode."""
        overlay = [
            f"t {time_s:6.2f} s   step {step}",
            f"reward {self.last_reward:+.3f}   return {self.episode_return:+.2f}",
            f"last event: {self.last_event}",
        ]
        return renderer.frame(pose, colliding, trail=self.trail, overlay=overlay)
