"""Quick start: the e-puck in the built-in seed-maze, driven by the report's Alg. 1."""

import mazesim
from mazesim.controllers import AvoidCollision

world = mazesim.load_world("seed-maze")  # a built-in name, or a path to a .toml world file
sim = mazesim.Simulator(world, robot="e-puck", seed=0)  # same seed, same run, bit for bit
avoid = AvoidCollision()  # Alg. 1: a proximity reading above 80 turns the robot away

for _ in range(1000):  # 1,000 control steps of 32 ms: 32 s of simulated time
    left, right = avoid(sim.distance_sensors())  # ps0..ps7 -> wheel speeds in rad/s
    sim.step(left, right)

x, y, yaw = sim.pose
print(f"after {sim.time:.2f} s ({sim.steps} steps): x {x:.3f} m, y {y:.3f} m, yaw {yaw:.2f} rad")
print(f"collisions: {sim.collisions}, distance travelled: {sim.distance_travelled:.2f} m")
print("ps0..ps7 (raw):", " ".join(f"{value:.0f}" for value in sim.distance_sensors()))
print("gs0..gs2 (raw):", " ".join(f"{value:.0f}" for value in sim.ground_sensors()))
