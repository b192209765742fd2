// A C++ controller of the tiny corpus project: its run says which Webots header is missing.
#include <webots/Radar.hpp>
#include <webots/Robot.hpp>

int main() {
  webots::Robot robot;
  webots::Radar *radar = robot.getRadar("radar");
  while (robot.step(32) != -1 && radar) {
  }
  return 0;
}
