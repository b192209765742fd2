"""e-puck avoid-collision controller, written as a Webots controller (the source report's Alg. 1,
in the form of its Listing 3.1 and of Webots' e-puck tutorial).

It runs unchanged in Webots and in mazesim:

    mazesim webots run examples/webots/avoid_collision.py --world arena --seconds 60

Both wheels turn at half the maximum speed; when one of the three front-left proximity sensors
(ps5, ps6, ps7) reads above 80 the robot turns right, else when one of the three front-right
ones (ps0, ps1, ps2) does, it turns left.
"""

from controller import Robot

MAX_SPEED = 6.28
OBSTACLE = 80.0

# create the Robot instance.
robot = Robot()
# the value of the basicTimeStep field of the WorldInfo node, in milliseconds
timeStep = int(robot.getBasicTimeStep())

# motors: velocity control
leftMotor = robot.getDevice("left wheel motor")
rightMotor = robot.getDevice("right wheel motor")
leftMotor.setPosition(float("inf"))
rightMotor.setPosition(float("inf"))
leftMotor.setVelocity(0.0)
rightMotor.setVelocity(0.0)

# initialize devices: the eight infra-red proximity sensors
ps = []
psNames = ["ps0", "ps1", "ps2", "ps3", "ps4", "ps5", "ps6", "ps7"]
for i in range(8):
    ps.append(robot.getDevice(psNames[i]))
    ps[i].enable(timeStep)

# feedback loop: step simulation until receiving an exit event
while robot.step(timeStep) != -1:
    # read sensors outputs
    psValues = []
    for i in range(8):
        psValues.append(ps[i].getValue())

    # detect obstacles
    right_obstacle = psValues[0] > OBSTACLE or psValues[1] > OBSTACLE or psValues[2] > OBSTACLE
    left_obstacle = psValues[5] > OBSTACLE or psValues[6] > OBSTACLE or psValues[7] > OBSTACLE

    # initialize motor speeds at 50% of MAX_SPEED.
    leftSpeed = 0.5 * MAX_SPEED
    rightSpeed = 0.5 * MAX_SPEED
    # modify speeds according to obstacles
    if left_obstacle:
        # turn right
        leftSpeed += 0.5 * MAX_SPEED
        rightSpeed -= 0.5 * MAX_SPEED
    elif right_obstacle:
        # turn left
        leftSpeed -= 0.5 * MAX_SPEED
        rightSpeed += 0.5 * MAX_SPEED

    # write actuators inputs
    leftMotor.setVelocity(leftSpeed)
    rightMotor.setVelocity(rightSpeed)
