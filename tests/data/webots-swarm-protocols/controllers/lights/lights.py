"""As a "beacon" (first argument) sends a packet every step; else lights its LEDs in the
pattern of its number (second argument), draws on its turret's Display and tells the others
its pattern over the radio; notes what its LEDs and display read and what it heard."""

import json
import os
import sys

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
if sys.argv[1] == "beacon":
    emitter = robot.getDevice("emitter")
    while robot.step(time_step) != -1:
        emitter.send(b"here")
    raise SystemExit(0)
number = int(sys.argv[2])
leds = [robot.getDevice(f"led{i}") for i in range(10)]
pattern = [1 if (i + number) % 3 == 0 else 0 for i in range(10)]
for led, value in zip(leds, pattern):
    led.set(value)
display = robot.getDevice("display")
display.setColor(0xFF0000)
display.drawText(robot.getName(), 0, 0)
emitter, receiver = robot.getDevice("emitter"), robot.getDevice("receiver")
receiver.enable(time_step)
heard = {}
steps = 0
while robot.step(time_step) != -1:
    steps += 1
    emitter.send(json.dumps({"from": robot.getName(), "leds": [led.get() for led in leds]}))
    while receiver.getQueueLength() > 0:
        packet = receiver.getString()
        receiver.nextPacket()
        message = json.loads(packet)
        heard[message["from"]] = message["leds"]
    if steps == 5:
        break
log = {
    "leds": [led.get() for led in leds],
    "pattern": pattern,
    "display": [display.getWidth(), display.getHeight()],
    "heard": heard,
}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
