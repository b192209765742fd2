"""Recording the navigator's episodes: what it saw, which sub-task ran, and why it turned.

A :class:`NavigatorRecorder` stands between :func:`mazesim.episodes.run_episodes` and a
navigator (the hierarchical policy or the flat baseline) and records the first few episodes of a
:class:`mazesim.episodes.EpisodeBatch`: at every step, before the navigator acts, the
frame it acts on (pose, the Sharp volts and ground reading, contact, the checkpoint event of the
last step), then what it did (the action code, the running sub-task, the Table 4.1 levels) and, at
a checkpoint, the higher level's decision: the barcode as read, the value of each sub-task and the
one chosen, and whether that was the highest (greedy) or an exploring choice. :meth:`after_step`
adds the last frame when an episode ends.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._sizes import whole_array
from mazesim.actions import ACTION_CODES
from mazesim.episodes import EpisodeBatch, NavigatorWrapper
from mazesim.errors import RegisteredName
from mazesim.learn.subtasks import SUBTASK_NAMES
from mazesim.replay.recorder import EpisodeRecorder, reading_scale
from mazesim.replay.run import RecordedRun

__all__ = ["NavigatorRecorder", "Recording"]


class NavigatorRecorder(NavigatorWrapper):
    """Records episodes ``0 .. episodes - 1`` of a navigation batch driven by ``navigator``.

    It is itself a navigator (``reset``, ``act``, ``record``), to hand to ``run_episodes`` in
    place of the one it watches.

    Args:
        nav: The batch the episodes run in.
        navigator: The navigator that drives it.
        episodes: How many of the first episodes to record.
    """

    def __init__(self, nav: EpisodeBatch, navigator: Any, episodes: int) -> None:
        self.nav = nav
        self.navigator = navigator
        self.episodes = episodes
        self.recorders: dict[int, EpisodeRecorder] = {}
        self.outcomes: dict[int, str] = {}

    def reset(self, envs: npt.ArrayLike, poses: npt.ArrayLike) -> None:
        """Starts robots afresh (see the watched navigator)."""
        self.navigator.reset(envs, poses)

    def _recording(self) -> list[tuple[int, EpisodeRecorder]]:
        """(env, recorder) of the robots now running an episode being recorded."""
        nav = self.nav
        running = []
        for env in np.flatnonzero((nav.episode >= 0) & (nav.episode < self.episodes)):
            episode = int(nav.episode[env])
            recorder = self.recorders.get(episode)
            if recorder is None:
                world = nav.worlds[int(nav.world_of_env[env])]
                recorder = EpisodeRecorder(world, nav.robot, episode)
                self.recorders[episode] = recorder
            if not recorder.finished:
                running.append((int(env), recorder))
        return running

    def _add_frame(self, env: int, recorder: EpisodeRecorder, event: int) -> None:
        nav = self.nav
        recorder.add_frame(
            nav.poses[env], nav.observations[env], bool(nav.colliding[env]), int(event)
        )

    def act(
        self, observations: npt.ArrayLike, poses: npt.ArrayLike, events: npt.ArrayLike
    ) -> npt.NDArray[np.int64]:
        """Records the frames, lets the navigator act, records what it did."""
        event_row = whole_array(events, "events")
        running = self._recording()
        for env, recorder in running:
            self._add_frame(env, recorder, int(event_row[env]))
        actions = np.asarray(self.navigator.act(observations, poses, events))
        record = self.navigator.record
        for env, recorder in running:
            recorder.set_action(
                code=ACTION_CODES[int(actions[env])],
                subtask=int(record.subtask[env]) if hasattr(self.navigator, "higher") else None,
                levels=record.levels[env],
            )
            chosen = int(record.chosen[env])
            if chosen >= 0 and hasattr(self.navigator, "higher"):
                world = int(self.navigator.world_of_env[env])
                recorder.add_choice(self.navigator.higher, world, int(event_row[env]), chosen)
        return actions

    def after_step(
        self, arrived: npt.NDArray[np.bool_], out_of_time: npt.NDArray[np.bool_]
    ) -> None:
        """Adds the last frame of the recorded episodes that ended on this step."""
        for env, recorder in self._recording():
            if arrived[env] or out_of_time[env]:
                self._add_frame(env, recorder, int(self.nav.events[env]))
                recorder.finished = True
                self.outcomes[recorder.number] = "goal reached" if arrived[env] else "out of time"

    def run(self, controller: RegisteredName, seed: int) -> RecordedRun:
        """The recorded episodes as a run (in the first world of the batch)."""
        nav = self.nav
        hierarchical = hasattr(self.navigator, "higher")
        return RecordedRun(
            world=nav.worlds[0],
            robot=nav.robot.name,
            controller=controller,
            seed=seed,
            control_step_ms=nav.control_step_ms,
            episodes=[
                self.recorders[number].episode(self.outcomes.get(number, "stopped"))
                for number in sorted(self.recorders)
            ],
            subtask_names=list(SUBTASK_NAMES) if hierarchical else [],
            reading_scale=reading_scale(nav.robot),
            own_profile=nav.robot,
        )


class Recording:
    """The ``recorder`` of an evaluation's :class:`~mazesim.learn.evaluate.EvaluationRecord`:
    builds a :class:`NavigatorRecorder` of the first ``episodes`` episodes.

    Args:
        episodes: How many of the first episodes to record.
    """

    def __init__(self, episodes: int) -> None:
        self.episodes = episodes

    def __call__(self, nav: EpisodeBatch, navigator: Any) -> NavigatorRecorder:
        """The recorder of ``nav``'s first episodes, driven by ``navigator``."""
        return NavigatorRecorder(nav, navigator, self.episodes)
