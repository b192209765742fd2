// Reads an inertial unit and a lidar through Webots' C++ classes as inertial_lidar_twin.py
// does, printed alike.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <webots/InertialUnit.hpp>
#include <webots/Lidar.hpp>
#include <webots/Motor.hpp>
#include <webots/Robot.hpp>

using namespace webots;

static void show(const char *label, const double *values, int count) {
  std::printf("%s", label);
  for (int i = 0; i < count; i++) {
    if (std::isnan(values[i]))
      std::printf(" none");
    else
      std::printf(" %.6f", values[i]);
  }
  std::printf("\n");
}

static std::string number(double value) {
  if (std::isnan(value))
    return "none";
  char text[32];
  std::snprintf(text, sizeof text, "%.6f", value);
  return text;
}

int main() {
  std::unique_ptr<Robot> robot(new Robot());
  int step = static_cast<int>(robot->getBasicTimeStep());
  InertialUnit *imu = robot->getInertialUnit("inertial unit");
  Lidar *lidar = robot->getLidar("lidar");
  Motor *left = robot->getMotor("left wheel motor");
  Motor *right = robot->getMotor("right wheel motor");
  imu->enable(step);
  lidar->enable(step);
  lidar->enablePointCloud();
  left->setControlPID(8.0, 0.0, 0.0);
  left->setPosition(INFINITY);
  right->setPosition(INFINITY);
  left->setVelocity(-1.0);
  right->setVelocity(1.0);
  int n = 0;
  while (robot->step(step) != -1) {
    if (++n % 8)
      continue;
    show("rpy", imu->getRollPitchYaw(), 3);
    show("quaternion", imu->getQuaternion(), 4);
    const float *ranges = lidar->getRangeImage();
    int resolution = lidar->getHorizontalResolution();
    int layers = lidar->getNumberOfLayers();
    if (ranges)
      std::printf("ranges %d", resolution * layers);
    else
      std::printf("ranges none");
    std::printf(" resolution %d layers %d\n", resolution, layers);
    const LidarPoint *cloud = lidar->getPointCloud();
    std::printf("cloud %s points %d fov %s max %s\n", cloud ? "some" : "none",
                lidar->getNumberOfPoints(), number(lidar->getFov()).c_str(),
                number(lidar->getMaxRange()).c_str());
    if (cloud && ranges) {  // the nearest point
      int k = 0;
      for (int i = 1; i < resolution * layers; i++)
        if (ranges[i] < ranges[k])
          k = i;
      std::printf("point %d %.4f %.4f %.4f %d %.4f range %.4f\n", k, cloud[k].x, cloud[k].y,
                  cloud[k].z, cloud[k].layer_id, cloud[k].time, ranges[k]);
    }
  }
  return 0;
}
