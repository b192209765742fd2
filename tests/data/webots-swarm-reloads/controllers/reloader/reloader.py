"""A supervisor that writes m0's customData at its 10th step, then reloads the world at
its 30th step, once (a file in the log folder says it did); it logs its starts and ends."""

import os

from controller import Supervisor

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
logs = os.environ.get("SWARM_LOG", ".")
done = os.path.join(logs, "reloaded")


def note(line: str) -> None:
    with open(os.path.join(logs, "reloader.log"), "a") as out:
        out.write(line + "\n")


note(f"start {supervisor.getTime():.3f}")
m0 = supervisor.getFromDef("M0")
steps = 0
while supervisor.step(time_step) != -1:
    steps += 1
    if steps == 10 and not os.path.exists(done):
        m0.getField("customData").setSFString("written")
    if steps == 30 and not os.path.exists(done):
        open(done, "w").close()
        note(f"reload {supervisor.getTime():.3f} {m0.getField('customData').getSFString()!r}")
        supervisor.worldReload()
note(f"end {supervisor.getTime():.3f} {steps}")
