"""Robot-steps per second of worlds of several robots against worlds of one, on the canonical
workload: a 5 x 5 maze of 0.25 m cells and 0.01 m walls (``generate_maze(seed=i, loops=0.1)``),
e-pucks with ps0-ps7 and gs0-gs2, a 32 ms control step, wheel speeds from the Braitenberg rule
(the batch's native ``run``, so no Python per step).

It compares ``--robots`` robots in each of ``--envs`` environments (placed in the four corner
cells of the maze) with ``--envs * --robots`` environments of one robot, taking the best of
``--repeats`` timed runs of ``--steps`` steps each, and prints robot-steps per second of both and
their ratio. ``docs/multi-robot.md`` quotes its figures.

    python benches/bench_robots.py [--envs 1024] [--robots 4] [--steps 200] [--repeats 5]

With ``--baseline-python PYTHON`` (the interpreter of another build of mazesim, say a checkout of
the main branch), it measures instead whether worlds of one robot got slower: the single-robot
workload of ``--envs * --robots`` environments runs ``--pairs`` times under each interpreter, in
alternation (each run in a fresh process, the order swapped every pair, so that a load that comes
and goes on the machine falls on both alike), and it prints both medians and the median of the
per-pair ratios.

    python benches/bench_robots.py --baseline-python ../main/.venv/bin/python [--pairs 7]

Timing on a shared machine scatters by several per cent; with ``--instructions`` it counts
instead (valgrind's callgrind, which the machine's load does not move): each build runs the
single-robot workload on one thread under callgrind once without steps and once with
``--steps`` steps, and the difference of the two totals over the robot-steps is that build's
instructions per robot-step. Both builds must end with the same poses (the same work); the
script exits with status 1 when this build needs more than ``--tolerance`` (a fraction) more
instructions per robot-step than the baseline.

    python benches/bench_robots.py --baseline-python OTHER/.venv/bin/python --instructions \
        [--envs 64 --robots 4 --steps 200 --tolerance 0.01]
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import mazesim
from mazesim import _core as core

CELL = 0.25


def world_of(seed: int, robots: int) -> mazesim.World:
    """Maze ``seed`` with ``robots`` robots at the centres of its corner cells (one: its start)."""
    maze = core.generate_maze(seed=seed, loops=0.1)
    if robots == 1:
        return maze
    text = re.sub(r"\[start\]\n(?:[a-z]+ = .*\n)+", "", maze.to_toml())
    corners = [(0, 0), (4, 4), (0, 4), (4, 0), (2, 2), (1, 3), (3, 1), (2, 0)]
    for k in range(robots):
        c, r = corners[k]
        text += (
            f'\n[[robots]]\nname = "epuck{k}"\nx = {(c + 0.5) * CELL}\n'
            f"y = {(r + 0.5) * CELL}\nyaw = 0.0\n"
        )
    return mazesim.World.from_toml(text)


def robot_steps_per_second(envs: int, robots: int, steps: int, repeats: int) -> float:
    """Best robot-steps per second of ``repeats`` runs of ``steps`` steps of ``envs`` envs."""
    worlds = [world_of(i, robots) for i in range(envs)]
    batch = mazesim.BatchSimulator(worlds, seeds=0)
    shape = (envs, robots) if robots > 1 else (envs,)
    obs = np.zeros((*shape, batch.observation_width), np.float32)
    poses = np.zeros((*shape, 3), np.float32)
    colliding = np.zeros(shape, bool)
    crossings = np.zeros(shape, np.int32)
    batch.reset(obs, poses, colliding, crossings)
    batch.run(20, "braitenberg", obs, poses, colliding, crossings)  # warm up
    best = 0.0
    for _ in range(repeats):
        start = time.perf_counter()
        batch.run(steps, "braitenberg", obs, poses, colliding, crossings)
        best = max(best, envs * robots * steps / (time.perf_counter() - start))
    return best


def single_robot_run(python: str, envs: int, steps: int, repeats: int) -> float:
    """Robot-steps per second of ``envs`` single-robot environments, measured by ``python`` (an
    interpreter with its own build of mazesim) in a fresh process running this script."""
    command = [python, __file__, "--single-only", "--envs", str(envs), "--robots", "1"]
    command += ["--steps", str(steps), "--repeats", str(repeats)]
    out = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    return float(out.split()[-1])


def single_robot_poses(envs: int, steps: int) -> str:
    """The poses after ``steps`` Braitenberg steps of ``envs`` single-robot environments on one
    thread (no warm-up: the workload callgrind counts), as a checksum line."""
    batch = mazesim.BatchSimulator([world_of(i, 1) for i in range(envs)], seeds=0, threads=1)
    obs = np.zeros((envs, batch.observation_width), np.float32)
    poses = np.zeros((envs, 3), np.float32)
    colliding = np.zeros(envs, bool)
    crossings = np.zeros(envs, np.int32)
    batch.reset(obs, poses, colliding, crossings)
    if steps:
        batch.run(steps, "braitenberg", obs, poses, colliding, crossings)
    return poses.tobytes().hex()


def counted_instructions(python: str, envs: int, steps: int) -> tuple[int, str]:
    """Callgrind's instruction total of ``python`` running ``steps`` single-robot steps of
    ``envs`` environments (set-up included), and the poses it ended with."""
    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, "callgrind.out")
        command = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", python]
        command += [__file__, "--poses-only", "--envs", str(envs), "--steps", str(steps)]
        env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
        poses = subprocess.run(command, check=True, capture_output=True, text=True, env=env)
        with open(out, encoding="utf-8") as file:
            totals = [line for line in file if line.startswith(("summary:", "totals:"))]
    return int(totals[0].split()[1]), poses.stdout.strip()


def instructions_per_robot_step(python: str, envs: int, steps: int) -> tuple[float, str]:
    """Instructions per robot-step of ``python``'s build: the count of ``steps`` steps less the
    count of none, over ``envs * steps``; and the poses of the run with steps."""
    without, _ = counted_instructions(python, envs, 0)
    with_steps, poses = counted_instructions(python, envs, steps)
    return (with_steps - without) / (envs * steps), poses


def counted(baseline: str, envs: int, steps: int, tolerance: float) -> int:
    """Instructions per robot-step of this build against ``baseline``'s; 1 when this build needs
    more than ``tolerance`` more, or when the two builds' runs end with different poses."""
    mine, my_poses = instructions_per_robot_step(sys.executable, envs, steps)
    theirs, their_poses = instructions_per_robot_step(baseline, envs, steps)
    print(f"{envs} envs x 1 robot, {steps} steps, one thread, instructions per robot-step:")
    print(f"this build: {mine:,.0f}")
    print(f"baseline:   {theirs:,.0f}")
    print(f"ratio (this / baseline): {mine / theirs:.3f}")
    if my_poses != their_poses:
        print("the two builds end with different poses: they did not do the same work")
        return 1
    if mine > theirs * (1.0 + tolerance):
        print(f"this build needs more than {tolerance:.1%} more instructions per robot-step")
        return 1
    return 0


def paired(baseline: str, envs: int, steps: int, repeats: int, pairs: int) -> None:
    """Single-robot robot-steps per second of this build against ``baseline``'s, in alternation."""
    mine, theirs, ratios = [], [], []
    for k in range(pairs):
        order = [(sys.executable, mine), (baseline, theirs)]
        for python, into in order if k % 2 == 0 else order[::-1]:
            into.append(single_robot_run(python, envs, steps, repeats))
        ratios.append(mine[-1] / theirs[-1])
        print(f"pair {k + 1}: this build {mine[-1]:,.0f}, baseline {theirs[-1]:,.0f}", flush=True)
    print(f"{envs} envs x 1 robot, median of {pairs} runs each:")
    print(f"this build: {statistics.median(mine):,.0f} robot-steps/s")
    print(f"baseline:   {statistics.median(theirs):,.0f} robot-steps/s")
    print(f"median ratio (this / baseline): {statistics.median(ratios):.3f}")


def main() -> None:
    """Runs the comparison and prints it."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--envs", type=int, default=1024)
    parser.add_argument("--robots", type=int, default=4)
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--baseline-python", help="another build's interpreter: paired A/B runs")
    parser.add_argument("--pairs", type=int, default=7)
    parser.add_argument(
        "--instructions",
        action="store_true",
        help="with --baseline-python: count instructions per robot-step under callgrind",
    )
    parser.add_argument(
        "--tolerance", type=float, default=0.01, help="with --instructions: allowed excess"
    )
    parser.add_argument("--single-only", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--poses-only", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.poses_only:
        print(single_robot_poses(args.envs, args.steps))
        return
    if args.baseline_python and args.instructions:
        envs = args.envs * args.robots
        sys.exit(counted(args.baseline_python, envs, args.steps, args.tolerance))
    if args.single_only:
        print(robot_steps_per_second(args.envs, 1, args.steps, args.repeats))
        return
    if args.baseline_python:
        envs = args.envs * args.robots
        paired(args.baseline_python, envs, args.steps, args.repeats, args.pairs)
        return
    many = robot_steps_per_second(args.envs, args.robots, args.steps, args.repeats)
    single = robot_steps_per_second(args.envs * args.robots, 1, args.steps, args.repeats)
    print(f"{args.envs} envs x {args.robots} robots: {many:,.0f} robot-steps/s")
    print(f"{args.envs * args.robots} envs x 1 robot: {single:,.0f} robot-steps/s")
    print(f"ratio: {many / single:.0%}")


if __name__ == "__main__":
    main()
