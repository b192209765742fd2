"""A supervisor that finds its robot and a target among the root's children and puts the robot
back at its start every 50 steps through its translation and rotation fields.

Test controller of mazesim's Webots interoperability (tests/test_webots_user_controllers.py),
for the world ``worlds/supervised_arena.wbt``.
"""

import math

from controller import Supervisor

RESET_EVERY = 50

supervisor = Supervisor()
timestep = int(supervisor.getBasicTimeStep())
root_children = supervisor.getRoot().getField("children")
robot_node = target_node = None
for i in range(root_children.getCount()):
    node = root_children.getMFNode(i)
    if node.getDef() == "EPUCK":
        robot_node = node
    elif node.getDef() == "TARGET":
        target_node = node
if robot_node is None or target_node is None:
    raise RuntimeError("EPUCK or TARGET not found among the root's children")
last = root_children.getMFNode(-1)
print(f"last child {last.getTypeName()} {last.getDef()}")

translation_field = robot_node.getField("translation")
rotation_field = robot_node.getField("rotation")
start_translation = translation_field.getSFVec3f()
start_rotation = rotation_field.getSFRotation()
target = target_node.getPosition()

left = supervisor.getDevice("left wheel motor")
right = supervisor.getDevice("right wheel motor")
left.setPosition(float("inf"))
right.setPosition(float("inf"))
left.setVelocity(5.0)
right.setVelocity(4.0)

steps = resets = 0
worst_reset_error = 0.0
while supervisor.step(timestep) != -1:
    steps += 1
    if steps % RESET_EVERY == 0:
        translation_field.setSFVec3f(start_translation)
        rotation_field.setSFRotation(start_rotation)
        robot_node.resetPhysics()
        supervisor.step(timestep)
        steps += 1
        x, y, _ = robot_node.getPosition()
        error = math.hypot(x - start_translation[0], y - start_translation[1])
        worst_reset_error = max(worst_reset_error, error)
        resets += 1
x, y, _ = robot_node.getPosition()
distance_to_target = math.hypot(x - target[0], y - target[1])
print(f"resets {resets} worst {worst_reset_error:.4f} target {distance_to_target:.3f}")
