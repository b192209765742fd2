/* Turns on the spot and notes when it started and how many steps it ran. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <webots/motor.h>
#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  const double started = wb_robot_get_time();
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  wb_motor_set_position(left, INFINITY);
  wb_motor_set_position(right, INFINITY);
  wb_motor_set_velocity(left, -3.0);
  wb_motor_set_velocity(right, 3.0);
  int steps = 0;
  while (wb_robot_step(time_step) != -1)
    steps++;
  char path[1024];
  const char *dir = getenv("SWARM_LOG");
  snprintf(path, sizeof(path), "%s/spin.json", dir ? dir : ".");
  FILE *out = fopen(path, "w");
  if (out) {
    fprintf(out, "{\"started\": %.6f, \"steps\": %d}\n", started, steps);
    fclose(out);
  }
  wb_robot_cleanup();
  return 0;
}
