/*
 * Drives straight on at the wheel speed of its first argument (5 rad/s without one). Each run
 * appends a line to NAME.starts; every step it writes NAME.json with its step count, its clock
 * and its left wheel's position sensor.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <webots/motor.h>
#include <webots/position_sensor.h>
#include <webots/robot.h>

int main(int argc, char **argv) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  const double speed = argc > 1 ? atof(argv[1]) : 5.0;
  const char *dir = getenv("SWARM_LOG");
  char path[1024];
  snprintf(path, sizeof(path), "%s/%s.starts", dir ? dir : ".", wb_robot_get_name());
  FILE *starts = fopen(path, "a");
  if (starts) {
    fprintf(starts, "start\n");
    fclose(starts);
  }
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  WbDeviceTag encoder = wb_robot_get_device("left wheel sensor");
  wb_position_sensor_enable(encoder, time_step);
  wb_motor_set_position(left, INFINITY);
  wb_motor_set_position(right, INFINITY);
  wb_motor_set_velocity(left, speed);
  wb_motor_set_velocity(right, speed);
  int steps = 0;
  double earliest_after = -1.0;
  double previous = 0.0;
  while (wb_robot_step(time_step) != -1 && steps < 100) {
    steps++;
    const double now = wb_robot_get_time();
    if (now < previous && earliest_after < 0.0)
      earliest_after = now;
    previous = now;
    snprintf(path, sizeof(path), "%s/%s.json", dir ? dir : ".", wb_robot_get_name());
    FILE *out = fopen(path, "w");
    if (out) {
      fprintf(out, "{\"steps\": %d, \"time\": %.6f, \"clock_back_to\": %.6f, \"encoder\": %.6f}\n", steps,
              now, earliest_after, wb_position_sensor_get_value(encoder));
      fclose(out);
    }
  }
  wb_robot_cleanup();
  return 0;
}
