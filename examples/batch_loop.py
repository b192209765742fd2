"""Many robots at once: a numpy control loop over a BatchSimulator.

Each of N robots drives its own generated 5 x 5 maze with the report's avoid-collision rule
(Alg. 1), computed for all of them in one numpy call; a robot that touches a wall goes back to its
start. The batch writes into buffers allocated once, so the loop makes no Python object per robot.

Run it with ``python examples/batch_loop.py``; with ``MAZESIM_EXAMPLES_FAST=1`` it runs a smaller
batch for fewer steps (the tests do that).
"""

import os
import time

import numpy as np

import mazesim
from mazesim.controllers import AvoidCollision

FAST = os.environ.get("MAZESIM_EXAMPLES_FAST") == "1"
NUM_ENVS = 256 if FAST else 1024
STEPS = 1000 if FAST else 2000  # control steps of 32 ms

worlds = [mazesim.generate_maze(5, 5, seed=i, loops=0.1) for i in range(NUM_ENVS)]
batch = mazesim.BatchSimulator(worlds, robot="e-puck", seeds=0)  # env i gets seed 0 + i
n, width = batch.num_envs, batch.observation_width  # width 11: ps0-ps7, then gs0-gs2
observations = np.zeros((n, width), np.float32)
poses = np.zeros((n, 3), np.float32)  # x, y, yaw
colliding = np.zeros(n, bool)  # touched a wall in the last step
crossings = np.zeros(n, np.int32)  # +id / -id of a barcode crossed in the last step, else 0
batch.reset(observations, poses, colliding, crossings)

controller = AvoidCollision()
restarts = 0
barcodes_read = 0
started = time.perf_counter()
for _ in range(STEPS):
    actions = controller.batch(observations[:, : batch.distance_width])  # (n, 2) rad/s
    batch.step(actions, observations, poses, colliding, crossings)
    barcodes_read += int(np.count_nonzero(crossings))
    if colliding.any():
        to_restart = colliding.copy()  # the mask must not be one of the output buffers
        restarts += int(to_restart.sum())
        batch.reset(observations, poses, colliding, crossings, mask=to_restart)
elapsed = time.perf_counter() - started

print(f"{n} robots x {STEPS} steps in {elapsed:.2f} s ({n * STEPS / elapsed:,.0f} env-steps/s)")
print(f"restarts after a wall contact: {restarts}, barcode crossings: {barcodes_read}")
print(f"distance travelled per robot: {batch.distances_travelled().mean():.2f} m on average")
