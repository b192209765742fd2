// A C++ controller of the tiny corpus project: its run says which Webots header is missing.
#include <webots/Microphone.hpp>
#include <webots/Robot.hpp>

int main() {
  webots::Robot robot;
  webots::Microphone *microphone = robot.getMicrophone("microphone");
  while (robot.step(32) != -1 && microphone) {
  }
  return 0;
}
