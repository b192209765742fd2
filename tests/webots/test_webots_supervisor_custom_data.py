"""A supervisor's write of another robot's ``customData`` field in a world of several robots
reaches that robot's controller, in its own process, as in Webots (#33)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from mazesim.webots.lockstep import run_world
from supervised_world import SWARM

pytestmark = pytest.mark.usefixtures("fresh_robot")


def test_a_supervisors_write_of_a_robots_custom_data_is_what_the_robot_reads(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A supervisor that gives orders through another robot's ``customData`` field
    (``getField("customData").setSFString``): the robot's ``getCustomData`` reads each after the
    world's next step, as in Webots, where the robot's controller runs in another process; the
    robot's own ``setCustomData`` stands until the next write."""
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    worker, orderer = run_world(str(SWARM / "worlds" / "orders.wbt"), seconds=2.0).robots
    assert [worker.exit_status, orderer.exit_status] == [0, 0], [worker.error, orderer.error]
    seen = json.loads((tmp_path / "worker.json").read_text())
    # Written after the supervisor's step 3, read after step 4; its own at 20; then 0 at 31.
    assert seen == ["0"] * 3 + ["4.0"] * 17 + ["mine"] * 10 + ["0.0"] * 10, seen
    assert worker.distance_m == pytest.approx(4.0 * 0.02 * 0.032 * 17, rel=0.15)
