"""A supervisor moves its own robot, reads it back, and quits the simulation with status 3.

Test controller of mazesim's Webots interoperability (tests/test_webots_controllers.py).
"""

from controller import Supervisor

supervisor = Supervisor()
timestep = int(supervisor.getBasicTimeStep())
robot_node = supervisor.getFromDef("EPUCK")
if robot_node is None:
    robot_node = supervisor.getSelf()
translation = robot_node.getField("translation")
rotation = robot_node.getField("rotation")
print("start", translation.getSFVec3f(), rotation.getSFRotation())

translation.setSFVec3f([0.2, -0.1, 0.0])
rotation.setSFRotation([0, 0, 1, 1.5708])
supervisor.step(timestep)
print("moved", [round(v, 3) for v in robot_node.getPosition()])

left = supervisor.getDevice("left wheel motor")
right = supervisor.getDevice("right wheel motor")
left.setPosition(float("inf"))
right.setPosition(float("inf"))
left.setVelocity(3.0)
right.setVelocity(3.0)
while supervisor.step(timestep) != -1:
    if supervisor.getTime() > 1.0:
        print("velocity", [round(v, 3) for v in robot_node.getVelocity()])
        supervisor.simulationQuit(3)
