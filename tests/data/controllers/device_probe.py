"""Enables and reads every device of its robot for a few steps, calling each getter the
device's class has, and prints each exception a call raised (``PROBE-RAISED ...``): Webots'
device calls print their errors and return, so a world that a controller can run has none.

Test controller of the mutated-world runs (tests/webots/test_world_run_fuzz.py).
"""

import controller

robot = controller.Robot()
time_step = max(1, int(robot.getBasicTimeStep() or 32))
raised = []


def call(label, function, *args):
    try:
        return function(*args)
    except Exception as error:  # noqa: BLE001 - each one is a finding, printed below
        raised.append(f"{label}: {type(error).__name__}: {error}")
        return None


GETTERS = (
    "getValue", "getValues", "getImage", "getRangeImage", "getPointCloud",
    "getRecognitionObjects", "getQueueLength", "getRollPitchYaw", "getQuaternion", "getSpeed",
    "getLookupTable", "getType", "getModel", "getNodeType", "getMaxRange", "getNumberOfPoints",
    "getWidth", "getHeight", "getFov", "getSamplingPeriod", "getTargetPosition", "getVelocity",
    "getBrightness", "getChannel", "getRange", "getTargets", "getPresence",
)  # fmt: skip
count = call("getNumberOfDevices", robot.getNumberOfDevices) or 0
devices = [call(f"getDeviceByIndex({i})", robot.getDeviceByIndex, i) for i in range(count)]
devices = [device for device in devices if device is not None]
for device in devices:
    name = device.getName()
    if hasattr(device, "enable"):
        call(f"{name}.enable", device.enable, time_step)
    if hasattr(device, "recognitionEnable"):
        call(f"{name}.recognitionEnable", device.recognitionEnable, time_step)
    if isinstance(device, controller.Motor):
        call(f"{name}.setPosition", device.setPosition, float("inf"))
        call(f"{name}.setVelocity", device.setVelocity, 1.0)
for _ in range(4):
    if call("step", robot.step, time_step) in (None, -1):
        break
    for device in devices:
        for getter in GETTERS:
            if hasattr(device, getter):
                call(f"{device.getName()}.{getter}", getattr(device, getter))
        if isinstance(device, controller.Emitter):
            call(f"{device.getName()}.send", device.send, b"probe")
        if isinstance(device, controller.Receiver):
            while (call("getQueueLength", device.getQueueLength) or 0) > 0:
                call("getBytes", device.getBytes)
                call("nextPacket", device.nextPacket)
print(f"PROBE-DONE {len(devices)} devices")
for line in raised:
    print(f"PROBE-RAISED {line}")
