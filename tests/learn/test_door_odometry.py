"""The door sub-tasks' odometry as the core computes it (``mazesim_core::navigator::door``) must
give SubTaskTracker's phases and ends bit for bit. The core's tests replay the file
``crates/mazesim-core/tests/data/door_subtasks.txt``; this test checks that the file is what
the Python tracker does today. Rewrite it with ``python tests/learn/test_door_odometry.py``.

Each sequence is one robot's sub-task: a line ``subtask x y yaw`` (the pose bits as float32
integers) and then one line per step ``x y yaw phase end heading_change`` (``end``: 0 running,
1 done, 2 gave up; ``heading_change`` as float64 bits), up to and including its end.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

from mazesim.learn.subtasks import MAX_DOOR_STEPS, TARGET_TURN
from navigator_oracle import SubTaskTracker

FIXTURE = Path(__file__).resolve().parents[2] / "crates/mazesim-core/tests/data/door_subtasks.txt"
SEQUENCES = 60


def _pose_bits(pose: np.ndarray) -> str:
    return " ".join(str(int(v)) for v in pose.astype(np.float32).view(np.uint32))


def door_sequences() -> str:
    """The fixture's text: the tracker following many robots side by side, each turning and
    driving with its own noise until its sub-task ends (or for ``MAX_DOOR_STEPS`` steps)."""
    rng = np.random.default_rng(18)
    n = SEQUENCES
    subtasks = rng.choice(4, n, p=[0.04, 0.32, 0.32, 0.32])
    poses = np.zeros((n, 3), dtype=np.float32)
    poses[:, :2] = rng.uniform(0.0, 1.25, (n, 2))
    poses[:, 2] = rng.uniform(-math.pi, math.pi, n)
    # Turning rates towards each sub-task's aim (some overshoot, some turn the wrong way).
    aim = np.asarray(TARGET_TURN)[subtasks] + rng.normal(0.0, 0.4, n)
    rate = rng.uniform(0.02, 0.12, n)
    tracker = SubTaskTracker(n)
    tracker.begin(np.ones(n, dtype=bool), subtasks, poses)
    lines: list[list[str]] = [[f"{subtasks[i]} {_pose_bits(poses[i])}"] for i in range(n)]
    running = np.ones(n, dtype=bool)
    turned = np.zeros(n)
    for _ in range(MAX_DOOR_STEPS):
        step = np.clip(aim - turned, -rate, rate) + rng.normal(0.0, 0.01, n)
        turned += step
        yaw = poses[:, 2].astype(np.float64) + step
        poses[:, 2] = ((yaw + math.pi) % (2.0 * math.pi) - math.pi).astype(np.float32)
        speed = rng.uniform(0.0, 0.012, n)
        poses[:, 0] += (speed * np.cos(poses[:, 2])).astype(np.float32)
        poses[:, 1] += (speed * np.sin(poses[:, 2])).astype(np.float32)
        done, gave_up = tracker.update(poses)
        end = np.where(gave_up, 2, np.where(done, 1, 0))
        change = tracker.heading_change.view(np.uint64)
        for i in np.flatnonzero(running):
            lines[i].append(f"{_pose_bits(poses[i])} {tracker.phase[i]} {end[i]} {change[i]}")
        running &= end == 0
    return "".join("\n".join(sequence) + "\n\n" for sequence in lines)


def test_the_core_replays_what_the_tracker_does() -> None:
    text = door_sequences()
    ends = [line.split()[4] for line in text.splitlines() if len(line.split()) == 6]
    # The sequences reach every kind of end, so the core's replay checks each.
    assert {"0", "1", "2"} <= set(ends), set(ends)
    assert FIXTURE.read_text() == text, f"{FIXTURE} is stale: run this file to rewrite it"


if __name__ == "__main__":
    FIXTURE.write_text(door_sequences())
    sys.exit(0)
