// Drives ahead at 3 rad/s for 30 steps with the C++ API and integrates its odometry from the
// wheel encoders; writes the encoders, the pose it integrated and the robot's time as JSON.
#include <webots/Motor.hpp>
#include <webots/PositionSensor.hpp>
#include <webots/Robot.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>

using namespace webots;

int main() {
  Robot *robot = new Robot();
  const int timeStep = static_cast<int>(robot->getBasicTimeStep());
  Motor *left = robot->getMotor("left wheel motor");
  Motor *right = robot->getMotor("right wheel motor");
  PositionSensor *leftSensor = left->getPositionSensor();
  PositionSensor *rightSensor = right->getPositionSensor();
  leftSensor->enable(timeStep);
  rightSensor->enable(timeStep);
  left->setPosition(INFINITY);
  right->setPosition(INFINITY);
  left->setVelocity(3.0);
  right->setVelocity(3.0);
  const double radius = 0.0205, axle = 0.052;
  double x = 0.0, y = 0.0, theta = 0.0, lastLeft = 0.0, lastRight = 0.0;
  int steps = 0;
  while (robot->step(timeStep) != -1 && steps < 30) {
    const double l = leftSensor->getValue(), r = rightSensor->getValue();
    if (steps > 0) {
      const double dl = (l - lastLeft) * radius, dr = (r - lastRight) * radius;
      x += (dl + dr) / 2.0 * std::cos(theta);
      y += (dl + dr) / 2.0 * std::sin(theta);
      theta += (dr - dl) / axle;
    }
    lastLeft = l;
    lastRight = r;
    steps++;
  }
  const char *dir = std::getenv("SWARM_LOG");
  std::ofstream out(std::string(dir ? dir : ".") + "/" + robot->getName() + ".json");
  out << "{\"left\": " << lastLeft << ", \"right\": " << lastRight << ", \"x\": " << x
      << ", \"theta\": " << theta << ", \"time\": " << robot->getTime()
      << ", \"sampling\": " << leftSensor->getSamplingPeriod() << "}\n";
  delete robot;
  return 0;
}
