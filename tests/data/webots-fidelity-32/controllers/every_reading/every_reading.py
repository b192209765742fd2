"""Enables every device the robot has and, before the first step, calls each getter that takes
no argument; writes, for each getter that answered a list of numbers, which of them are NaN, and
the getters that answered one number, NaN, as JSON into $SWARM_LOG (and the getters that
raised, by name)."""

import contextlib
import inspect
import io
import json
import math
import os

from controller import Robot
from controller.sensor import Sensor

robot = Robot()
time_step = int(robot.getBasicTimeStep())
devices = [robot.getDeviceByIndex(i) for i in range(robot.getNumberOfDevices())]
for device in devices:
    if isinstance(device, Sensor):
        device.enable(time_step)
lists = {}
nan_numbers = []
raised = {}
with contextlib.redirect_stderr(io.StringIO()):
    for device in devices:
        for name in dir(type(device)):
            if not name.startswith("get"):
                continue
            getter = getattr(device, name)
            wanted = inspect.signature(getter).parameters.values()
            if any(p.default is p.empty and p.kind is p.POSITIONAL_OR_KEYWORD for p in wanted):
                continue  # it takes an argument
            try:
                value = getter()
            except Exception as error:  # a getter the device's class does not answer
                raised[f"{device.getName()}.{name}"] = type(error).__name__
                continue
            if isinstance(value, list) and value and all(isinstance(v, float) for v in value):
                lists[f"{device.getName()}.{name}"] = [math.isnan(v) for v in value]
            elif isinstance(value, float) and math.isnan(value):
                nan_numbers.append(f"{device.getName()}.{name}")
lidar = robot.getDevice("lidar")
log = {"lists": lists, "nan_numbers": nan_numbers, "raised": raised}
log["lidar_frequencies"] = [lidar.getMinFrequency(), lidar.getMaxFrequency()]
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
