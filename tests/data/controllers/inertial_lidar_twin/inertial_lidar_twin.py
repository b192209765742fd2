"""The Python twin of c_inertial_lidar/c_inertial_lidar.c and cpp_inertial_lidar: the same
inertial unit and lidar readings, printed alike, and a motor's PID gains set."""

import math

from controller import Robot


def shown(value):
    return "none" if value is None or math.isnan(value) else f"{value:.6f}"


robot = Robot()
step = int(robot.getBasicTimeStep())
imu = robot.getDevice("inertial unit")
lidar = robot.getDevice("lidar")
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
imu.enable(step)
lidar.enable(step)
lidar.enablePointCloud()
left.setControlPID(8.0, 0.0, 0.0)
left.setPosition(float("inf"))
right.setPosition(float("inf"))
left.setVelocity(-1.0)
right.setVelocity(1.0)
n = 0
while robot.step(step) != -1:
    n += 1
    if n % 8:
        continue
    print("rpy " + " ".join(shown(v) for v in imu.getRollPitchYaw()))
    print("quaternion " + " ".join(shown(v) for v in imu.getQuaternion()))
    ranges = lidar.getRangeImage()
    print(f"ranges {'none' if ranges is None else len(ranges)}", end=" ")
    print(f"resolution {lidar.getHorizontalResolution()} layers {lidar.getNumberOfLayers()}")
    points = lidar.getPointCloud()
    cloud = "none" if points is None else "some"
    print(f"cloud {cloud} points {lidar.getNumberOfPoints()}", end=" ")
    print(f"fov {shown(lidar.getFov())} max {shown(lidar.getMaxRange())}")
    if points is not None and ranges is not None:  # the nearest point
        k = min(range(len(ranges)), key=lambda i: (ranges[i], i))
        p = points[k]
        print(
            f"point {k} {p.x:.4f} {p.y:.4f} {p.z:.4f} {p.layer_id} {p.time:.4f} "
            f"range {ranges[k]:.4f}"
        )
