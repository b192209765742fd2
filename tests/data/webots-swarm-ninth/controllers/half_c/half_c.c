/*
 * Steps with wb_robot_step_begin / wb_robot_step_end: before each step it sends how many steps
 * it has done and drives at 2 rad/s; it stops after 50 steps.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <webots/emitter.h>
#include <webots/motor.h>
#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag emitter = wb_robot_get_device("emitter");
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  wb_motor_set_position(left, INFINITY);
  wb_motor_set_position(right, INFINITY);
  int done = 0, bad = 0;
  char text[32];
  while (done < 50) {
    snprintf(text, sizeof text, "c:%d", done);
    wb_emitter_send(emitter, text, strlen(text) + 1);
    wb_motor_set_velocity(left, 2.0);
    wb_motor_set_velocity(right, 2.0);
    if (wb_robot_step_begin(time_step) == -1)
      break;
    if (wb_robot_step_end() == -1)
      bad++;
    done++;
  }
  wb_motor_set_velocity(left, 0.0);
  wb_motor_set_velocity(right, 0.0);
  wb_robot_step(time_step);
  char path[1024];
  const char *dir = getenv("SWARM_LOG");
  snprintf(path, sizeof path, "%s/half_c.json", dir ? dir : ".");
  FILE *out = fopen(path, "w");
  if (out) {
    fprintf(out, "{\"done\": %d, \"bad\": %d, \"time\": %.6f}\n", done, bad, wb_robot_get_time());
    fclose(out);
  }
  wb_robot_cleanup();
  return 0;
}
