"""The Python twin of c_wall_avoider/c_wall_avoider.c: the same devices, the same steering rule
and the same printed lines, so the two runs can be compared step for step."""

from controller import Node, Robot

CRUISE = 5.0
NEAR = 80.0


def steer(left_front: float, right_front: float) -> tuple[float, float]:
    left_speed = CRUISE
    right_speed = CRUISE
    if left_front > NEAR:
        right_speed = -CRUISE * 0.5
    elif right_front > NEAR:
        left_speed = -CRUISE * 0.5
    else:
        left_speed += (left_front - right_front) * 0.01
        right_speed -= (left_front - right_front) * 0.01
    return left_speed, right_speed


robot = Robot()
step = int(robot.getBasicTimeStep())
front = [robot.getDevice("ps7"), robot.getDevice("ps0")]
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
encoder = robot.getDevice("left wheel sensor")
led = robot.getDevice("led0")
for sensor in front:
    sensor.enable(step)
encoder.enable(step)
left.setPosition(float("inf"))
right.setPosition(float("inf"))
left.setVelocity(0.0)
right.setVelocity(0.0)
kind = "distance" if front[1].getNodeType() == Node.DISTANCE_SENSOR else "other"
print(f"devices {robot.getNumberOfDevices()}, {front[1].getName()} is a {kind} sensor")
steps = 0
while robot.step(step) != -1:
    left_speed, right_speed = steer(front[0].getValue(), front[1].getValue())
    left.setVelocity(left_speed)
    right.setVelocity(right_speed)
    led.set(int(left_speed < 0.0 or right_speed < 0.0))
    steps += 1
    if steps % 31 == 0:
        print(f"t {robot.getTime():.3f} encoder {encoder.getValue():.4f}")
