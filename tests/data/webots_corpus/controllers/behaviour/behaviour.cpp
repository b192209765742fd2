// A C++ controller of the tiny corpus project: its run says which Webots header is missing.
#include <webots/Lidar.hpp>
#include <webots/Robot.hpp>

int main() {
  webots::Robot robot;
  webots::Lidar *lidar = robot.getLidar("lidar");
  while (robot.step(32) != -1 && lidar) {
  }
  return 0;
}
