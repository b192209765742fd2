"""What the reset tests of both ROS bridges share: the wheel speeds a client sends, the poses
the in-process simulator gives for them, and the client's run around its two reset calls, as
Python source for the client's process. The client's own part defines ``pose_at(step)`` (the
first ``pose`` of that step's simulated time), ``send(left, right)`` (one ``motor`` command)
and ``reset(name)`` (a call of ``reset_simulation`` or ``reset_world``, returning once answered)."""

from __future__ import annotations

import numpy as np

import mazesim
from mazesim.ros import topics

STEPS = 12


def wheel_speeds() -> list[list[float]]:
    """The ``[left, right]`` of each command, in rad/s."""
    return np.random.default_rng(5).uniform(-6.0, 6.28, (STEPS, 2)).tolist()


def in_process_poses() -> list[list[float]]:
    """The ``pose`` the in-process simulator (seed-maze, e-puck, seed 0) has after each command."""
    simulator = mazesim.Simulator(mazesim.load_world("seed-maze"), robot="e-puck", seed=0)
    poses = []
    for left, right in wheel_speeds():
        simulator.step(left, right)
        poses.append(topics.pose_values(simulator))
    return poses


def client_run() -> str:
    """The client's run: 12 commands equal to the in-process run, ``reset_simulation``, the same
    12 again equal to the first, ``reset_world``, then at the start with the clock going on."""
    return f"""
speeds = {wheel_speeds()!r}
expected = {in_process_poses()!r}

def drive(first_step):
    out = []
    for index, (left, right) in enumerate(speeds):
        send(left, right)
        out.append(pose_at(first_step + index + 1))
    return out

start = pose_at(0)
first = drive(0)
assert first == expected, (first, expected)
assert first[-1][:2] != start[:2]
reset('reset_simulation')
assert pose_at(0) == start
again = drive(0)
assert again == first, (again, first)
print('reset_simulation: the run again, bit for bit')
reset('reset_world')
after = pose_at({STEPS})
assert after[:3] == start[:3], (after, start)
moved = drive({STEPS})
assert moved[-1][3] > after[3] and moved[-1][:2] != after[:2]
print('reset_world: at the start, the clock going on')
"""
