"""Plays its half-second beep on the e-puck's speaker and waits for it to end before playing
it again, as a controller that beeps at each checkpoint does; logs when the sound played."""

import json
import os

from controller import Robot, Speaker

robot = Robot()
time_step = int(robot.getBasicTimeStep())
speaker = robot.getDevice("speaker")
Speaker.playSound(speaker, speaker, "beep.wav", 1.0, 1.0, 0.0, False)
playing = []
while robot.step(time_step) != -1 and len(playing) < 30:
    playing.append(speaker.isSoundPlaying("beep.wav"))
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump({"playing": playing}, out)
