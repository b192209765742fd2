// A camera's lens, a motor's torque and force, lookup tables, sensor types and the robot's
// battery, URDF and robot window through Webots' C++ classes, printed as lens_torque_twin.py
// prints them.
#include <cmath>
#include <iostream>
#include <sstream>
#include <string>

#include <webots/Accelerometer.hpp>
#include <webots/Camera.hpp>
#include <webots/GPS.hpp>
#include <webots/LightSensor.hpp>
#include <webots/Motor.hpp>
#include <webots/PositionSensor.hpp>
#include <webots/Robot.hpp>

using namespace webots;

static std::string shown(double value) {
  if (std::isnan(value))
    return "none";
  char text[32];
  snprintf(text, sizeof text, "%.6f", value);
  return text;
}

int main() {
  Robot robot;
  int step = (int)robot.getBasicTimeStep();
  Camera *camera = robot.getCamera("camera");
  Motor *motor = robot.getMotor("left wheel motor");
  PositionSensor *encoder = robot.getPositionSensor("left wheel sensor");
  LightSensor *light = robot.getLightSensor("ls0");
  Accelerometer *accelerometer = robot.getAccelerometer("accelerometer");
  camera->enable(step);
  camera->setFov(camera->getFov());
  camera->setExposure(2.0);
  camera->setFocalDistance(0.5);
  std::cout << "fov " << shown(camera->getFov()) << " " << shown(camera->getMinFov()) << " "
            << shown(camera->getMaxFov()) << "\n";
  std::cout << "exposure " << shown(camera->getExposure()) << " near "
            << shown(camera->getNear()) << "\n";
  std::cout << "focus " << shown(camera->getFocalLength()) << " "
            << shown(camera->getFocalDistance()) << " " << shown(camera->getMinFocalDistance())
            << " " << shown(camera->getMaxFocalDistance()) << "\n";
  motor->setAvailableTorque(5.0);
  motor->enableTorqueFeedback(step);
  std::cout << "torque " << shown(motor->getAvailableTorque()) << " "
            << shown(motor->getMaxTorque()) << "\n";
  std::cout << "force " << shown(motor->getAvailableForce()) << " "
            << shown(motor->getMaxForce()) << "\n";
  std::cout << "multiplier " << shown(motor->getMultiplier()) << " brake "
            << (motor->getBrake() ? 1 : 0) << "\n";
  const double *table = light->getLookupTable();
  std::cout << "light table " << light->getLookupTableSize() << " " << shown(table[0]) << " "
            << shown(table[1]) << " " << shown(table[2]) << "\n";
  std::cout << "accelerometer table " << accelerometer->getLookupTableSize() << "\n";
  std::cout << "encoder type " << encoder->getType() << " brake "
            << (encoder->getBrake() ? 1 : 0) << "\n";
  std::cout << "dms " << GPS::convertToDegreesMinutesSeconds(12.5826) << "\n";
  robot.batterySensorEnable(step);
  std::cout << "battery " << shown(robot.batterySensorGetValue()) << " "
            << robot.batterySensorGetSamplingPeriod() << "\n";
  std::istringstream urdf(robot.getUrdf("my_"));
  std::string line;
  std::getline(urdf, line);
  std::getline(urdf, line);
  std::cout << "type " << robot.getType() << " urdf " << line << "\n";
  robot.wwiSendText("hello");
  std::string window = robot.wwiReceiveText();
  std::cout << "window " << (window.empty() ? "none" : window) << "\n";
  int n = 0;
  while (robot.stepBegin(step) != -1) {
    robot.stepEnd();
    if (++n % 16 == 0)
      std::cout << "feedback " << shown(motor->getTorqueFeedback()) << " "
                << motor->getTorqueFeedbackSamplingPeriod() << std::endl;
  }
  return 0;
}
