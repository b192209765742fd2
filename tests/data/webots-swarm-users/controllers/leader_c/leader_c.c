/*
 * A leader that moves its emitter to channel 3, drives straight at 2 rad/s and sends, after each
 * step, the number of that step as a 32-bit integer.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <webots/emitter.h>
#include <webots/motor.h>
#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag emitter = wb_robot_get_device("emitter");
  wb_emitter_set_channel(emitter, 3);
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  wb_motor_set_position(left, INFINITY);
  wb_motor_set_position(right, INFINITY);
  wb_motor_set_velocity(left, 2.0);
  wb_motor_set_velocity(right, 2.0);
  int step = 0;
  while (wb_robot_step(time_step) != -1 && step < 60) {
    step++;
    wb_emitter_send(emitter, &step, sizeof step);
  }
  char path[1024];
  const char *dir = getenv("SWARM_LOG");
  snprintf(path, sizeof path, "%s/%s.json", dir ? dir : ".", wb_robot_get_name());
  FILE *out = fopen(path, "w");
  if (out) {
    fprintf(out, "{\"sent\": %d, \"channel\": %d}\n", step, wb_emitter_get_channel(emitter));
    fclose(out);
  }
  wb_robot_cleanup();
  return 0;
}
