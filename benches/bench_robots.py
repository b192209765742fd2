"""Robot-steps per second of worlds of several robots against worlds of one, on the canonical
workload: a 5 x 5 maze of 0.25 m cells and 0.01 m walls (``generate_maze(seed=i, loops=0.1)``),
e-pucks with ps0-ps7 and gs0-gs2, a 32 ms control step, wheel speeds from the Braitenberg rule
(the batch's native ``run``, so no Python per step).

It compares ``--robots`` robots in each of ``--envs`` environments (placed in the four corner
cells of the maze) with ``--envs * --robots`` environments of one robot, taking the best of
``--repeats`` timed runs of ``--steps`` steps each, and prints robot-steps per second of both and
their ratio. ``docs/multi-robot.md`` quotes its figures.

    python benches/bench_robots.py [--envs 1024] [--robots 4] [--steps 200] [--repeats 5]
"""

from __future__ import annotations

import argparse
import re
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


def main() -> None:
    """Runs the comparison and prints it."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--envs", type=int, default=1024)
    parser.add_argument("--robots", type=int, default=4)
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    many = robot_steps_per_second(args.envs, args.robots, args.steps, args.repeats)
    single = robot_steps_per_second(args.envs * args.robots, 1, args.steps, args.repeats)
    print(f"{args.envs} envs x {args.robots} robots: {many:,.0f} robot-steps/s")
    print(f"{args.envs * args.robots} envs x 1 robot: {single:,.0f} robot-steps/s")
    print(f"ratio: {many / single:.0%}")


if __name__ == "__main__":
    main()
