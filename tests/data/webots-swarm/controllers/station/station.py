"""The only robot of its world, a supervisor with a body (a box): imports an e-puck that
drives at it, on the second step."""

from controller import Supervisor

E_PUCK = 'E-puck { translation -0.3 0 0 name "first" controller "cruise" }'

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
children = supervisor.getRoot().getField("children")
steps = 0
while supervisor.step(time_step) != -1:
    steps += 1
    if steps == 2:
        children.importMFNodeFromString(-1, E_PUCK)
