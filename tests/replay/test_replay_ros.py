"""``mazesim ros demo --record/--html``: the run read back from the bag, with the decisions."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from mazesim.learn.subtasks import SUBTASK_NAMES
from mazesim.replay import load_run
from ros_support import needs_ros


@needs_ros
def test_ros_demo_records_the_run_and_the_navigator_decisions(tmp_path: Path) -> None:
    out = tmp_path / "demo"
    command = [sys.executable, "-m", "mazesim", "ros", "demo", "--out", str(out)]
    command += ["--record", str(tmp_path / "run.json"), "--html", str(tmp_path / "replay.html")]
    result = subprocess.run(command, capture_output=True, text=True, timeout=200, check=False)
    assert result.returncode == 0, result.stderr
    assert f"wrote              {tmp_path / 'replay.html'}" in result.stdout
    poses = int(re.search(r"\((\d+) pose messages\)", result.stdout).group(1))  # type: ignore[union-attr]
    run = load_run(tmp_path / "run.json")
    episode = run.episodes[0]
    assert run.controller == "hrl over ROS" and run.control_step_ms == pytest.approx(32.0)
    assert episode.frames == poses and episode.outcome == "goal reached"
    assert episode.readings.shape == (poses, 7)  # six Sharp volts and the ground sensor
    assert episode.decisions, "the navigator chose nothing on its way to the goal"
    for decision in episode.decisions:
        event = decision.checkpoint if decision.arrival else -decision.checkpoint
        assert episode.events[decision.frame] == event
        assert decision.greedy and decision.chosen == int(np.argmax(decision.q_values))
        assert episode.subtasks is not None
        assert (
            SUBTASK_NAMES[int(episode.subtasks[decision.frame])] == SUBTASK_NAMES[decision.chosen]
        )
