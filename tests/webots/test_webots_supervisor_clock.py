"""A supervisor's ``simulationReset`` restarts what Webots restarts, at the end of the next step:
every robot's clock (``getTime``) and wheel position sensors count from the reset, its motors
are back in position control and the Emitter and Receiver queues are emptied, while the run's
summary and time limit count the whole run (#33)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from mazesim.webots import controller
from mazesim.webots import simulation as simulations
from mazesim.webots.lockstep import run_world
from native_controllers import NEEDS_COMPILERS, write_source
from supervised_world import drive, supervisor_of

SWARM = Path(__file__).resolve().parent.parent / "data" / "webots-swarm"
STEP_S = 0.032

pytestmark = pytest.mark.usefixtures("fresh_robot")


def wheel_sensors(supervisor: controller.Supervisor) -> list[controller.PositionSensor]:
    """The e-puck's wheel position sensors, enabled at every step."""
    sensors = [supervisor.getDevice(f"{side} wheel sensor") for side in ("left", "right")]
    for sensor in sensors:
        sensor.enable(32)
    return sensors


def test_after_a_reset_the_clock_and_the_wheel_sensors_read_as_in_a_fresh_run(
    tmp_path: Path,
) -> None:
    supervisor = supervisor_of(tmp_path)
    sensors = wheel_sensors(supervisor)
    drive(supervisor, 6.0, 40)
    assert supervisor.getTime() == pytest.approx(40 * STEP_S)
    assert sensors[0].getValue() > 1.0
    supervisor.simulationReset()
    assert supervisor.getTime() == pytest.approx(40 * STEP_S), "not before the next step"
    assert supervisor.step(32) == 0
    assert supervisor.getTime() == 0.0
    drive(supervisor, 6.0, 10)
    after_reset = (supervisor.getTime(), [sensor.getValue() for sensor in sensors])
    run = simulations.current()
    assert run.time == pytest.approx(51 * STEP_S), "the run's own count goes on"
    assert run.steps == 51
    simulations.release()
    fresh = supervisor_of(tmp_path)
    fresh_sensors = wheel_sensors(fresh)
    drive(fresh, 6.0, 10)
    assert after_reset[0] == pytest.approx(fresh.getTime(), abs=1e-12)
    # To the wheel sensors' resolution (2 pi / 1000 rad).
    assert after_reset[1] == pytest.approx([s.getValue() for s in fresh_sensors], abs=0.00629)


def test_every_robot_of_a_world_run_counts_from_the_reset_and_loses_its_packets(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    run = run_world(str(SWARM / "worlds" / "clock.wbt"), seconds=3.0)
    assert [r.exit_status for r in run.robots] == [0, 0]
    keeper = json.loads((tmp_path / "clock_keeper.json").read_text())
    assert keeper["before_reset"] == pytest.approx(30 * STEP_S)
    assert keeper["at_reset"] == pytest.approx(30 * STEP_S), "applied at the next step's end"
    assert keeper["step_after_reset"] == 0.0
    assert keeper["end"] == pytest.approx(9 * STEP_S)
    listener = json.loads((tmp_path / "listener.json").read_text())
    # Every robot learns of the reset with the answer of the same step, its 31st.
    assert listener["time"][29] == pytest.approx(30 * STEP_S)
    assert listener["time"][30:] == pytest.approx([k * STEP_S for k in range(10)])
    assert listener["queue"][29] == 20, "the keeper's packets, never read"
    assert listener["queue"][30:] == [0] * 10, "the reset emptied the queue"
    assert listener["wheel"][29] > 20 * 4.0 * STEP_S
    # Its motors are back in position control at the reset's wheel angles: the wheels hold
    # still, as in Webots, until the controller sets them again (this one never does).
    assert listener["wheel"][30:] == pytest.approx([0.0] * 10, abs=1e-9)
    # The run's summary counts the whole run.
    assert run.steps >= 40 and run.simulated_seconds == pytest.approx(run.steps * STEP_S)


#: A C controller that records its clock and left wheel sensor after each of its 40 steps.
C_TIMER = r"""#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <webots/motor.h>
#include <webots/position_sensor.h>
#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  int step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag wheel = wb_robot_get_device("left wheel sensor");
  wb_position_sensor_enable(wheel, step);
  WbDeviceTag motors[2] = {wb_robot_get_device("left wheel motor"),
                           wb_robot_get_device("right wheel motor")};
  for (int i = 0; i < 2; i++) {
    wb_motor_set_position(motors[i], INFINITY);
    wb_motor_set_velocity(motors[i], 4.0);
  }
  char path[4096];
  snprintf(path, sizeof path, "%s/c_timer.json", getenv("SWARM_LOG"));
  FILE *log = fopen(path, "w");
  fprintf(log, "[");
  for (int steps = 0; steps < 40 && wb_robot_step(step) != -1; steps++)
    fprintf(log, "%s[%.17g, %.17g]", steps ? ", " : "", wb_robot_get_time(),
            wb_position_sensor_get_value(wheel));
  fprintf(log, "]\n");
  fclose(log);
  wb_robot_cleanup();
  return 0;
}
"""


@NEEDS_COMPILERS
@pytest.mark.usefixtures("own_cache")
def test_a_c_controller_reads_its_clock_and_wheel_from_the_reset(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    timer = write_source(tmp_path, "c_timer", C_TIMER)
    run = run_world(
        str(SWARM / "worlds" / "clock.wbt"), seconds=3.0, controllers={"listener": str(timer)}
    )
    assert [r.exit_status for r in run.robots] == [0, 0]
    read = json.loads((tmp_path / "c_timer.json").read_text())
    times, wheel = [t for t, _ in read], [w for _, w in read]
    assert times[29] == pytest.approx(30 * STEP_S)
    assert times[30:] == pytest.approx([k * STEP_S for k in range(10)])
    assert wheel[29] > 20 * 4.0 * STEP_S
    assert wheel[30:] == pytest.approx([0.0] * 10, abs=1e-9), "position control holds them"
