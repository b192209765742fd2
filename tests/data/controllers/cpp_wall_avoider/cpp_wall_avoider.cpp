// The wall avoider of c_wall_avoider.c written against Webots' C++ API, for mazesim's tests: the
// same devices, steering rule and printed lines.
#include <webots/DistanceSensor.hpp>
#include <webots/LED.hpp>
#include <webots/Motor.hpp>
#include <webots/Robot.hpp>

#include <cstdio>

using namespace webots;

static const double CRUISE = 5.0;
static const double NEAR = 80.0;

int main() {
  Robot *robot = new Robot();
  int step = (int)robot->getBasicTimeStep();
  DistanceSensor *front[2] = {robot->getDistanceSensor("ps7"), robot->getDistanceSensor("ps0")};
  Motor *left = robot->getMotor("left wheel motor");
  Motor *right = dynamic_cast<Motor *>(robot->getDevice("right wheel motor"));
  PositionSensor *encoder = left->getPositionSensor();
  LED *led = robot->getLED("led0");
  for (int i = 0; i < 2; i++)
    front[i]->enable(step);
  encoder->enable(step);
  left->setPosition(INFINITY);
  right->setPosition(INFINITY);
  left->setVelocity(0.0);
  right->setVelocity(0.0);
  printf("devices %d, %s is a %s sensor\n", robot->getNumberOfDevices(),
         front[1]->getName().c_str(),
         front[1]->getNodeType() == WB_NODE_DISTANCE_SENSOR ? "distance" : "other");
  int steps = 0;
  while (robot->step(step) != -1) {
    double left_front = front[0]->getValue(), right_front = front[1]->getValue();
    double left_speed = CRUISE, right_speed = CRUISE;
    if (left_front > NEAR)
      right_speed = -CRUISE * 0.5;
    else if (right_front > NEAR)
      left_speed = -CRUISE * 0.5;
    else {
      left_speed += (left_front - right_front) * 0.01;
      right_speed -= (left_front - right_front) * 0.01;
    }
    left->setVelocity(left_speed);
    right->setVelocity(right_speed);
    led->set(left_speed < 0.0 || right_speed < 0.0);
    if (++steps % 31 == 0)
      printf("t %.3f encoder %.4f\n", robot->getTime(), encoder->getValue());
  }
  delete robot;
  return 0;
}
