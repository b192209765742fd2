/*
 * Drives straight at the speed its first argument names (the project's shared steer.c) for 1 s.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <webots/motor.h>
#include <webots/robot.h>

#include "steer.h"

int main(int argc, char **argv) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  const double speed = scout_speed(argc > 1 ? argv[1] : "");
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  wb_motor_set_position(left, INFINITY);
  wb_motor_set_position(right, INFINITY);
  wb_motor_set_velocity(left, speed);
  wb_motor_set_velocity(right, speed);
  while (wb_robot_step(time_step) != -1 && wb_robot_get_time() < 1.0 - 1e-9) {
  }
  wb_motor_set_velocity(left, 0.0);
  wb_motor_set_velocity(right, 0.0);
  char path[1024];
  const char *dir = getenv("SWARM_LOG");
  snprintf(path, sizeof path, "%s/%s.json", dir ? dir : ".", wb_robot_get_name());
  FILE *out = fopen(path, "w");
  if (out) {
    fprintf(out, "{\"speed\": %g, \"time\": %.6f}\n", speed, wb_robot_get_time());
    fclose(out);
  }
  wb_robot_cleanup();
  return 0;
}
