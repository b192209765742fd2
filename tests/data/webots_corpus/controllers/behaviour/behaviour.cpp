// A C++ controller of the tiny corpus project: its run says which Webots header is missing.
#include <webots/Joystick.hpp>
#include <webots/Robot.hpp>

int main() {
  webots::Robot robot;
  webots::Joystick *joystick = robot.getJoystick();
  while (robot.step(32) != -1 && joystick) {
  }
  return 0;
}
