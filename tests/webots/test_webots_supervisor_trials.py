"""A supervisor runs trial after trial with ``simulationReset``, as Webots applies it: at the end
of the next step, the motors back at the world file's position control, the noise streams from
their seeds; ``simulationSetMode(PAUSE)`` stops the run, with ``step(0)`` still answered (#33)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from mazesim.webots import controller
from mazesim.webots import simulation as simulations
from mazesim.webots.lockstep import run_world
from supervised_world import drive, supervisor_of

SWARM = Path(__file__).resolve().parent.parent / "data" / "webots-swarm"
STEP_S = 0.032

pytestmark = pytest.mark.usefixtures("fresh_robot")


def test_a_world_run_resets_at_the_end_of_the_next_step_and_replays_its_first_trial(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    run = run_world(str(SWARM / "worlds" / "trial_reset.wbt"), seconds=5.0, seed=3)
    assert [r.exit_status for r in run.robots] == [0]
    seen = json.loads((tmp_path / "trial_reset.json").read_text())
    assert seen["driven"][0] > 0.02
    # Nothing changes until the next step, at whose end the world is reset: the clock reads 0.
    assert seen["after_call"]["time"] == pytest.approx(25 * STEP_S)
    assert seen["after_call"]["translation"] == pytest.approx(seen["driven"])
    assert seen["after_step"]["time"] == 0.0
    assert seen["after_step"]["position"] == pytest.approx([0.0, 0.0, 0.0], abs=1e-6)
    assert seen["after_step"]["translation"] == pytest.approx([0.0, 0.0, 0.0], abs=1e-6)
    # The controller library still reads what the controller set last...
    assert seen["after_step"]["target"] == math.inf
    # ...while the motors are back in position control at the wheels' reset angle: still.
    assert seen["held"] == pytest.approx([0.0, 0.0, 0.0], abs=1e-6)
    # The noise streams start again from their seeds: the second trial reads as the first.
    assert seen["second_trial"] == seen["first_trial"]
    assert len({tuple(r) for r in seen["first_trial"]}) > 1, "the readings are noisy"
    assert seen["driven_again"] == pytest.approx(seen["driven"], abs=1e-9)


def test_a_reset_waits_for_the_next_step_in_a_run_of_one_robot(tmp_path: Path) -> None:
    supervisor = supervisor_of(tmp_path, noise=True, seed=5)
    drive(supervisor, 6.0, 10)
    moved = simulations.current().simulator.pose
    supervisor.simulationReset()
    assert simulations.current().simulator.pose == moved
    assert supervisor.getTime() == pytest.approx(10 * STEP_S)
    supervisor.step(32)
    assert simulations.current().simulator.pose == pytest.approx((0.0, 0.0, 0.0), abs=1e-6)
    assert supervisor.getTime() == 0.0
    left = supervisor.getDevice("left wheel motor")
    assert left.getVelocity() == 6.0, "what the controller set last"
    for _ in range(5):
        supervisor.step(32)
    assert simulations.current().simulator.pose == pytest.approx((0.0, 0.0, 0.0), abs=1e-6)


def test_pausing_answers_step_zero_and_ends_the_run_at_the_next_step(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    supervisor = supervisor_of(tmp_path)
    drive(supervisor, 6.0, 3)
    supervisor.simulationSetMode(controller.Supervisor.SIMULATION_MODE_PAUSE)
    assert supervisor.simulationGetMode() == controller.Supervisor.SIMULATION_MODE_PAUSE
    pose = simulations.current().simulator.pose
    assert supervisor.step(0) == 0
    assert simulations.current().simulator.pose == pose
    assert supervisor.getTime() == pytest.approx(3 * STEP_S)
    assert supervisor.step(32) == -1
    assert "paused the simulation" in capsys.readouterr().err
    assert simulations.current().quit_status == 0
    assert supervisor.getTime() == pytest.approx(3 * STEP_S)


def test_resuming_before_the_next_step_goes_on(tmp_path: Path) -> None:
    supervisor = supervisor_of(tmp_path)
    supervisor.simulationSetMode(controller.Supervisor.SIMULATION_MODE_PAUSE)
    supervisor.simulationSetMode(controller.Supervisor.SIMULATION_MODE_FAST)
    assert supervisor.step(32) == 0
    assert supervisor.getTime() == pytest.approx(STEP_S)
