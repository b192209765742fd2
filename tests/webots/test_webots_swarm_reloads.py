"""A supervisor's ``worldReload`` in a run of the whole world, checked against what Webots
documents (reference manual, Supervisor, ``wb_supervisor_world_reload``: the supervisor process
and all the robot processes are terminated and restarted): every controller ends and starts
again, on a clock back at 0, in the world as its file has it (#33, #32)."""

from __future__ import annotations

from pathlib import Path

import pytest

from swarm_project import run_project

PROJECT = Path(__file__).resolve().parent.parent / "data" / "webots-swarm-reloads"


pytestmark = pytest.mark.usefixtures("own_cache")


def _lines(logs: Path, name: str) -> list[list[str]]:
    return [line.split(" ", 2) for line in (logs / f"{name}.log").read_text().splitlines()]


def test_a_world_reload_restarts_every_controller_on_a_clock_back_at_0(
    tmp_path: Path,
) -> None:
    """The supervisor reloads the world at its 30th step (0.96 s): each of the three
    controllers, the supervisor's too, sees its 31st step return -1 and starts again at time 0,
    its first step ending at 0.032 s; the e-puck whose customData the supervisor wrote reads the
    file's value again, and both e-pucks, back at their starts, drive again because their
    controllers set their motors again (before, the reload was a reset: the controllers went
    on, their motors back at position control, and the e-pucks stood still)."""
    logs = tmp_path / "logs"
    done, _ = run_project(PROJECT, "reload", logs, 2.0)
    for name in ("m0", "m1"):
        lines = _lines(logs, name)
        assert [line[:2] for line in lines] == [
            ["start", "0.000"],
            ["first", "0.032"],
            ["end", "0.960"],
            ["start", "0.000"],
            ["first", "0.032"],
            ["end", "1.056"],
        ]
        assert lines[2][2] == "30" and lines[5][2] == "33"
    assert _lines(logs, "m0")[3][2] == "'from the file'"
    supervisor = _lines(logs, "reloader")
    assert supervisor == [
        ["start", "0.000"],
        ["reload", "0.960", "'written'"],
        ["end", "0.960", "30"],
        ["start", "0.000"],
        ["end", "1.056", "33"],
    ]
    assert [r.restarts_s for r in done.robots] == [[pytest.approx(0.96)]] * 3
    assert all(r.exit_status == 0 for r in done.robots)
    # Back at their starts at the reload, the e-pucks drove 33 steps of 3 rad/s on.
    m0, m1 = done.robots[0], done.robots[1]
    assert m0.final_pose[0] == pytest.approx(-0.3 + 33 * 0.032 * 3.0 * 0.02, abs=2e-3)
    assert m1.final_pose[0] == pytest.approx(0.3 - 33 * 0.032 * 3.0 * 0.02, abs=2e-3)
