"""A recorded run from the bag of ``mazesim ros demo``, for its ``--html``, ``--video`` and
``--record`` options.

The frames are the bridge's ``/pose`` messages in the order recorded, with the ``/sensors``
message of the same step and the wheel speeds of ``/motor`` (avoid-collision) or the action code
of ``/action`` (the perform-learning node). For the hierarchical policy, the ``/sensor_data``
messages (six distances in cm and the checkpoint event) are fed once more to the navigator the
node runs (:class:`mazesim.learn.policy.DeadReckoningNavigator`, deterministic), which gives the
running sub-task, the Table 4.1 levels and each decision with the higher level's values: the
same choices the node made, since it saw the same messages.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mazesim._core import RobotProfile, World
from mazesim._paths import open_input
from mazesim.errors import MissingDependencyError
from mazesim.learn.subtasks import SUBTASK_NAMES
from mazesim.replay.recorder import EpisodeRecorder, reading_scale
from mazesim.replay.run import RecordedRun

__all__ = ["read_topics", "run_from_bag"]


def read_topics(bag_path: str, topics: tuple[str, ...]) -> dict[str, list[Any]]:
    """The ``data`` of every message of each topic, in the order recorded."""
    try:
        import rosbag
    except ImportError as error:
        raise MissingDependencyError(
            f"reading a bag needs ROS 1's rosbag package ({error}); on Debian 'make ros-deps'"
        ) from error
    messages: dict[str, list[Any]] = {topic: [] for topic in topics}
    # Opened by mazesim (a regular file only, a path that is a path), then read by rosbag.
    with open_input(bag_path, "the bag") as file, rosbag.Bag(file) as bag:
        for topic, message, _ in bag.read_messages(topics=list(topics)):
            data = message.data
            messages[topic].append(data if isinstance(data, str) else list(data))
    return messages


def run_from_bag(
    bag_path: str,
    world: World,
    profile: RobotProfile,
    controller: str,
    seed: int,
    control_step_ms: float,
) -> RecordedRun:
    """The run a ``ros demo`` bag holds (see the module), of a robot with ``profile``: the
    profile the bridge drove, which the run keeps as a run of the simulator does (a profile
    file's robot replays with its own profile, as run format 1.3 holds it)."""
    hierarchical = controller == "hrl"
    topics = ("/pose", "/sensors", "/sensor_data", "/action") if hierarchical else (
        "/pose", "/sensors", "/motor",
    )  # fmt: skip
    messages = read_topics(bag_path, topics)
    recorder = EpisodeRecorder(world, profile)
    frames = min(len(messages["/pose"]), len(messages["/sensors"]))
    if hierarchical:
        frames = min(frames, len(messages["/sensor_data"]))
    navigator = _navigator(control_step_ms) if hierarchical else None
    for frame in range(frames):
        pose = messages["/pose"][frame]
        event = int(messages["/sensor_data"][frame][-1]) if hierarchical else 0
        recorder.add_frame(pose[:3], messages["/sensors"][frame], False, event)
        if navigator is not None:
            _replay_decision(navigator, recorder, messages["/sensor_data"][frame], event)
        elif frame < len(messages["/motor"]):
            left, right = messages["/motor"][frame][:2]
            recorder.set_action(wheel_speeds=(float(left), float(right)))
    goal = world.goal
    outcome = "stopped"
    if goal is not None and recorder.poses:
        x, y, _ = recorder.poses[-1]
        if np.hypot(x - goal[0], y - goal[1]) <= goal[2]:
            outcome = "goal reached"
    return RecordedRun(
        world=world,
        robot=profile.name,
        controller=f"{controller} over ROS",
        seed=seed,
        control_step_ms=control_step_ms,
        episodes=[recorder.episode(outcome)],
        subtask_names=list(SUBTASK_NAMES) if hierarchical else [],
        reading_scale=reading_scale(profile),
        own_profile=profile,
    )


def _navigator(control_step_ms: float) -> Any:
    from mazesim.learn.higher import HigherLevel
    from mazesim.learn.policy import DeadReckoningNavigator
    from mazesim.learn.tables import load_policy

    policy = load_policy()
    assert policy.lower_q is not None and policy.higher_q is not None
    higher = HigherLevel([policy.checkpoint_ids], q=policy.higher_q[None])
    return DeadReckoningNavigator(
        policy.lower_q, higher, control_step_ms, hold_heading=policy.hold_heading
    )


def _replay_decision(
    navigator: Any, recorder: EpisodeRecorder, sensor_data: list[float], event: int
) -> None:
    """Feeds one ``sensor_data`` message to the navigator and records what it did and chose."""
    code = navigator.act(np.asarray(sensor_data[:6], dtype=np.float64), event)
    record = navigator.policy.record
    recorder.set_action(code=code, subtask=int(record.subtask[0]), levels=record.levels[0])
    chosen = int(record.chosen[0])
    if chosen >= 0:
        recorder.add_choice(navigator.policy.higher, 0, event, chosen)
