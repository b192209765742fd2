"""Asks for devices the e-puck does not have and checks for None, as controllers shared
between robots do.

Test controller of mazesim's Webots interoperability (tests/test_webots_user_controllers.py).
"""

from controller import Robot

robot = Robot()
timestep = int(robot.getBasicTimeStep())
optional = {}
for name in ("gps", "lidar", "ds_left", "display", "inertial unit", "ps0", "camera"):
    device = robot.getDevice(name)
    if device is None:
        print(f"no {name}")
        continue
    optional[name] = device
    if hasattr(device, "enable"):
        device.enable(timestep)
print("found", sorted(optional))

left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
left.setPosition(float("inf"))
right.setPosition(float("inf"))
gps = optional.get("gps")
while robot.step(timestep) != -1:
    if gps is not None:
        print(gps.getValues())
    near = optional["ps0"].getValue() > 100
    left.setVelocity(-3.0 if near else 3.0)
    right.setVelocity(3.0)
