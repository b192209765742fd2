"""A bodiless supervisor that gives the e-puck its wheel speed by writing the speed into the
e-puck's customData field: 4 rad/s after its third step, 0 after its thirtieth."""

from controller import Supervisor

supervisor = Supervisor()
orders = supervisor.getFromDef("WORKER").getField("customData")
steps = 0
while supervisor.step(32) != -1 and steps < 40:
    steps += 1
    if steps == 3:
        orders.setSFString("4.0")
    if steps == 30:
        orders.setSFString("0.0")
