"""A supervisor that only steps."""

from controller import Supervisor

supervisor = Supervisor()
while supervisor.step(int(supervisor.getBasicTimeStep())) != -1:
    pass
