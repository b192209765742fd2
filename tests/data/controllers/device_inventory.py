"""Lists the robot's devices by Webots' node type name, as device-inventory controllers do.

Test controller of mazesim's Webots interoperability (tests/test_webots_api.py): it looks each
device's type up among ``Node``'s attributes, which only works if no two constants share a
value.
"""

from controller import Node, Robot

robot = Robot()
constant_names = list(Node.__dict__.keys())
constant_values = list(Node.__dict__.values())
for index in range(robot.getNumberOfDevices()):
    device = robot.getDeviceByIndex(index)
    kind = constant_names[constant_values.index(device.getNodeType())]
    print(f"{device.getName()}: {kind}")
robot.step(int(robot.getBasicTimeStep()))
