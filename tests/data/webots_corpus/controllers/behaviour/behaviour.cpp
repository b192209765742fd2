// A C++ controller of the tiny corpus project: its run says the C++ API is missing.
#include <webots/Robot.hpp>

int main() {
  webots::Robot robot;
  while (robot.step(32) != -1) {
  }
  return 0;
}
