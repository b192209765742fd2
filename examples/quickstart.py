"""Quick start: the report's avoid-collision rule (Alg. 1) drives the e-puck in seed-maze."""

import mazesim
from mazesim.controllers import AvoidCollision

world = mazesim.load_world("seed-maze")  # a built-in name, or a path to a .toml or .wbt file
sim = mazesim.Simulator(world, robot="e-puck", seed=0)
controller = AvoidCollision()  # Alg. 1: threshold 80, MAX_SPEED 6.28 rad/s

for _ in range(1000):  # 1,000 control steps of 32 ms: 32 simulated seconds
    left, right = controller(sim.distance_sensors())  # ps0..ps7, raw e-puck counts
    sim.step(left, right)  # wheel speeds in rad/s

x, y, yaw = sim.pose
print(f"after {sim.time:.2f} s: x = {x:.3f} m, y = {y:.3f} m, yaw = {yaw:.2f} rad")
print(f"collisions: {sim.collisions}, travelled {sim.distance_travelled:.2f} m")
print("ps0..ps7:", sim.distance_sensors().round(1))
print("gs0..gs2:", sim.ground_sensors().round(1))  # about 300 on black, 856 on white
