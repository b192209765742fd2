/* Drives straight ahead at the wheel speed of its first argument (rad/s). */
#include <math.h>
#include <stdlib.h>

#include <webots/motor.h>
#include <webots/robot.h>

int main(int argc, char **argv) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  const double speed = argc > 1 ? atof(argv[1]) : 0.0;
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  wb_motor_set_position(left, INFINITY);
  wb_motor_set_position(right, INFINITY);
  wb_motor_set_velocity(left, speed);
  wb_motor_set_velocity(right, speed);
  while (wb_robot_step(time_step) != -1) {
  }
  wb_robot_cleanup();
  return 0;
}
