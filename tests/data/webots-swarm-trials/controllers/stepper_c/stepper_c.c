/*
 * Steps by 32 ms in a world of 16 ms, wheels at 4 rad/s, until 1 s of simulated time; notes
 * how many steps it took and its clock at the first one.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <webots/motor.h>
#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  wb_motor_set_position(left, INFINITY);
  wb_motor_set_position(right, INFINITY);
  wb_motor_set_velocity(left, 4.0);
  wb_motor_set_velocity(right, 4.0);
  int steps = 0;
  double first = -1.0;
  while (wb_robot_step(32) != -1 && wb_robot_get_time() < 1.0 - 1e-9) {
    steps++;
    if (first < 0.0)
      first = wb_robot_get_time();
  }
  wb_motor_set_velocity(left, 0.0);
  wb_motor_set_velocity(right, 0.0);
  wb_robot_step(32);
  const char *dir = getenv("SWARM_LOG");
  char path[1024];
  snprintf(path, sizeof(path), "%s/middle.json", dir ? dir : ".");
  FILE *out = fopen(path, "w");
  if (out) {
    fprintf(out, "{\"steps\": %d, \"first\": %.6f}\n", steps, first);
    fclose(out);
  }
  wb_robot_cleanup();
  return 0;
}
